"""Minimal Chrome DevTools Protocol client for headless Chromium.

Talks to Chromium over ``--remote-debugging-pipe``: the browser reads
NUL-terminated JSON commands on its file descriptor 3 and writes
NUL-terminated JSON replies and events on its file descriptor 4.
Standard library only, so it runs under the system Python 3.
"""

import base64
import contextlib
import fcntl
import json
import os
import shutil
import signal
import subprocess
import tempfile
import threading
import time

DEFAULT_EXECUTABLE = "/usr/bin/chromium"
CANDIDATES = ("chromium", "chromium-browser", "google-chrome", "chrome")
LAUNCH_FLAGS = (
    "--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
    "--disable-background-networking", "--disable-component-update", "--disable-sync",
    "--remote-debugging-pipe", "--window-size=1280,900",
)
# Non-printable keys: DOM key name (equal to its code) -> windowsVirtualKeyCode.
NAMED_KEYS = {"ArrowLeft": 37, "ArrowUp": 38, "ArrowRight": 39, "ArrowDown": 40,
              "Enter": 13, "Escape": 27, "Tab": 9, "Backspace": 8, "Delete": 46,
              "Home": 36, "End": 35, "PageUp": 33, "PageDown": 34}
# US layout: (unshifted + shifted character, code, windowsVirtualKeyCode).
KEY_ROWS = [(c + c.upper(), f"Key{c.upper()}", ord(c.upper()))
            for c in "abcdefghijklmnopqrstuvwxyz"]
KEY_ROWS += [(d + s, f"Digit{d}", ord(d)) for d, s in zip("0123456789", ")!@#$%^&*(")]
KEY_ROWS += [("-_", "Minus", 189), ("=+", "Equal", 187), ("[{", "BracketLeft", 219),
             ("]}", "BracketRight", 221), ("\\|", "Backslash", 220), (";:", "Semicolon", 186),
             ("'\"", "Quote", 222), (",<", "Comma", 188), (".>", "Period", 190),
             ("/?", "Slash", 191), ("`~", "Backquote", 192), (" ", "Space", 32)]
SHIFT = 8  # Input.dispatchKeyEvent modifier bit


class DevToolsError(RuntimeError):
    """A protocol command failed, or the browser went away."""


def find_chromium():
    """Return the path of a Chromium-like browser, or None if there is none."""
    for name in (DEFAULT_EXECUTABLE, *CANDIDATES):
        if path := shutil.which(name):
            return path
    return None


def _key_description(key):
    """Return (code, windowsVirtualKeyCode, text, modifiers) for a key."""
    if key in NAMED_KEYS:
        return key, NAMED_KEYS[key], "\r" if key == "Enter" else None, 0
    for chars, code, vk in KEY_ROWS:
        if len(key) == 1 and key in chars:
            return code, vk, key, SHIFT if chars.index(key) == 1 else 0
    raise ValueError(f"unsupported key: {key!r}")


def _exception_text(details):
    """Return the readable message of a Runtime.ExceptionDetails."""
    return details.get("exception", {}).get("description") or details.get("text", "")


def _remote_text(obj):
    """Render a Runtime.RemoteObject console argument as text."""
    if "value" in obj:
        return obj["value"] if isinstance(obj["value"], str) else json.dumps(obj["value"])
    return obj.get("description") or obj.get("unserializableValue") or obj.get("type", "")


def _preexec(read_fd, write_fd):
    """Return a child-side hook that puts the pipe ends on fds 3 and 4.

    Popen runs it before closing the descriptors not in pass_fds=(3, 4); both
    are open in the parent since the log file and pipes took the lowest free.
    """
    def remap():
        # Move both ends above 4 first so neither dup2 clobbers the other.
        high = [fcntl.fcntl(fd, fcntl.F_DUPFD, 10) for fd in (read_fd, write_fd)]
        for target, fd in zip((3, 4), high):
            os.dup2(fd, target, inheritable=True)
            os.close(fd)
    return remap


class Browser:
    """A headless Chromium process driven over the DevTools pipe."""

    def __init__(self, executable=DEFAULT_EXECUTABLE, timeout_s=30, launch_tries=2, launch_timeout_s=60):
        self.timeout_s = timeout_s
        self._write_lock = threading.Lock()
        self._out = None
        failures = []
        for _ in range(launch_tries):  # a first start on a busy, fresh machine may hang; start again
            self._start(executable)
            try:
                self._await_first_reply(launch_timeout_s)
                return
            except TimeoutError as error:
                failures.append(str(error))
                self.close()
            except Exception:
                self.close()
                raise
        raise TimeoutError(f"Chromium did not answer in {launch_tries} starts of {launch_timeout_s} s each:\n"
                           + "\n".join(failures))

    def _start(self, executable):
        """Start the browser with a new profile, log and pipe, and the thread reading its replies."""
        self.events = []  # every event message: method, params, sessionId
        self._listeners = {}  # sessionId -> callable(event), run on the reader thread
        self._replies = {}
        self._next_id = 0
        self._alive = True
        self._cond = threading.Condition()
        self._profile = tempfile.mkdtemp(prefix="cdp-profile-")
        self._log = tempfile.NamedTemporaryFile(prefix="cdp-", suffix=".log", delete=False)
        to_child, self._out = os.pipe()
        self._in, from_child = os.pipe()
        try:
            self._proc = subprocess.Popen(
                [executable, *LAUNCH_FLAGS, f"--user-data-dir={self._profile}", "about:blank"],
                stdin=subprocess.DEVNULL, stdout=self._log, stderr=self._log,
                pass_fds=(3, 4), start_new_session=True, preexec_fn=_preexec(to_child, from_child))
        except OSError:
            self._release()
            raise
        finally:
            os.close(to_child)
            os.close(from_child)
        self._reader = threading.Thread(target=self._read_loop, daemon=True)
        self._reader.start()

    def _await_first_reply(self, timeout_s):
        """Ask for the version until the browser answers (a command sent before it reads may be lost)."""
        deadline = time.monotonic() + timeout_s
        while True:
            try:
                return self.send("Browser.getVersion", timeout_s=min(5, timeout_s))
            except TimeoutError:
                if time.monotonic() >= deadline:
                    raise

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        self.close()

    def log_tail(self, lines=20):
        """Return the last lines Chromium wrote to stdout/stderr."""
        try:
            with open(self._log.name, errors="replace") as log:
                return "".join(log.readlines()[-lines:])
        except OSError:
            return ""

    def _read_loop(self):
        """Split the browser's output at NULs; file replies by id, record events."""
        buffer = b""
        while chunk := os.read(self._in, 1 << 16):
            *messages, buffer = (buffer + chunk).split(b"\0")
            with self._cond:
                for message in map(json.loads, messages):
                    if "id" in message:
                        self._replies[message["id"]] = message
                        continue
                    self.events.append(message)
                    if listener := self._listeners.get(message.get("sessionId")):
                        listener(message)
                self._cond.notify_all()
        with self._cond:
            self._alive = False
            self._cond.notify_all()

    def _wait_until(self, find, what, timeout_s=None):
        """Wait for replies/events until find() is not None, and return it."""
        deadline = time.monotonic() + (timeout_s or self.timeout_s)
        with self._cond:
            while (found := find()) is None:
                if not self._alive:
                    raise DevToolsError(f"browser exited waiting for {what}\n{self.log_tail()}")
                if not self._cond.wait(deadline - time.monotonic()):
                    raise TimeoutError(f"timed out waiting for {what}\n{self.log_tail()}")
            return found

    def send(self, method, params=None, session_id=None, timeout_s=None):
        """Send a command and return its "result" dict."""
        if self._out is None:
            raise DevToolsError(f"{method}: browser is closed")
        with self._cond:
            self._next_id += 1
            message = {"id": self._next_id, "method": method, "params": params or {}}
        if session_id:
            message["sessionId"] = session_id
        try:
            with self._write_lock:  # not under _cond: a full pipe must not stall the reader
                os.write(self._out, json.dumps(message).encode() + b"\0")
        except OSError as error:
            raise DevToolsError(f"{method}: browser pipe closed ({error})\n{self.log_tail()}")
        reply = self._wait_until(lambda: self._replies.pop(message["id"], None),
                                 f"reply to {method}", timeout_s)
        if "error" in reply:
            raise DevToolsError(f"{method}: {reply['error'].get('message')}")
        return reply.get("result", {})

    def wait_event(self, method, session_id=None, since=0, timeout_s=None):
        """Return the first event called method (in that session) in self.events[since:]."""
        return self._wait_until(lambda: next(
            (event for event in self.events[since:]
             if event["method"] == method and event.get("sessionId") == session_id), None),
            f"{method} event", timeout_s)

    def new_page(self, url="about:blank"):
        """Open a new tab, attach to it and navigate it to url."""
        target = self.send("Target.createTarget", {"url": "about:blank"})["targetId"]
        session = self.send("Target.attachToTarget", {"targetId": target, "flatten": True})
        page = Page(self, session["sessionId"])
        if url != "about:blank":
            page.navigate(url)
        return page

    def close(self):
        """Shut the browser down and remove its profile and log; idempotent."""
        if self._out is None:
            return
        with contextlib.suppress(DevToolsError, TimeoutError):  # it may exit before replying
            self.send("Browser.close", timeout_s=3)
        with contextlib.suppress(subprocess.TimeoutExpired):
            self._proc.wait(5)
        with contextlib.suppress(ProcessLookupError):  # a hung browser or stray renderers
            os.killpg(self._proc.pid, signal.SIGKILL)
        self._proc.wait()
        self._reader.join(5)
        self._release()

    def _release(self):
        """Close our pipe ends; remove the temporary profile directory and log."""
        os.close(self._out)
        os.close(self._in)
        self._out = self._in = None
        shutil.rmtree(self._profile, ignore_errors=True)
        self._log.close()
        os.unlink(self._log.name)


class Page:
    """One tab, attached through a flat DevTools session."""

    def __init__(self, browser, session_id):
        self.browser = browser
        self.session_id = session_id
        self.console_errors = []  # readable console errors/warnings, exceptions, log errors
        browser._listeners[session_id] = self._record_problem
        for domain in ("Page", "Runtime", "Log"):
            self.send(f"{domain}.enable")

    def send(self, method, params=None, timeout_s=None):
        """Send a command within this page's session."""
        return self.browser.send(method, params, self.session_id, timeout_s)

    def _record_problem(self, event):
        """Append console errors/warnings, uncaught exceptions and log errors."""
        method, params = event["method"], event.get("params", {})
        if method == "Runtime.consoleAPICalled" and params["type"] in ("error", "warning"):
            text = " ".join(_remote_text(arg) for arg in params.get("args", []))
            self.console_errors.append(f"console.{params['type']}: {text}")
        elif method == "Runtime.exceptionThrown":
            self.console_errors.append(f"uncaught: {_exception_text(params['exceptionDetails'])}")
        elif method == "Log.entryAdded" and params["entry"]["level"] == "error":
            entry = params["entry"]
            text = f"{entry['source']}: {entry['text']} {entry.get('url', '')}"
            self.console_errors.append(text.rstrip())

    def navigate(self, url):
        """Load url and wait for its load event."""
        mark = len(self.browser.events)
        result = self.send("Page.navigate", {"url": url})
        if result.get("errorText"):
            raise DevToolsError(f"Page.navigate {url}: {result['errorText']}")
        self.browser.wait_event("Page.loadEventFired", self.session_id, since=mark)

    def evaluate(self, expression):
        """Evaluate a JavaScript expression, awaiting a promise, and return its value."""
        result = self.send("Runtime.evaluate", {
            "expression": expression, "returnByValue": True, "awaitPromise": True})
        if "exceptionDetails" in result:
            text = _exception_text(result["exceptionDetails"])
            raise DevToolsError(f"Runtime.evaluate {expression!r}: {text}")
        return result["result"].get("value")

    def wait_for(self, expression, timeout_s=10, poll_s=0.05):
        """Poll expression until it is truthy and return its value."""
        deadline = time.monotonic() + timeout_s
        while not (value := self.evaluate(expression)):
            if time.monotonic() > deadline:
                raise TimeoutError(f"timed out waiting for {expression!r} (last: {value!r})")
            time.sleep(poll_s)
        return value

    def screenshot(self, path):
        """Save a PNG screenshot of the viewport to path."""
        data = self.send("Page.captureScreenshot", {"format": "png"})["data"]
        with open(path, "wb") as out:
            out.write(base64.b64decode(data))

    def _mouse(self, kind, x, y, buttons, clicks=1):
        """Dispatch one left-button mouse event."""
        self.send("Input.dispatchMouseEvent", {"type": kind, "x": x, "y": y, "button": "left",
                                               "buttons": buttons, "clickCount": clicks})

    def click(self, x, y):
        """Left-click at viewport coordinates (x, y)."""
        self.mouse_drag(x, y, x, y, steps=0)

    def mouse_drag(self, x0, y0, x1, y1, steps=10):
        """Press the left button at (x0, y0), move in steps, release at (x1, y1)."""
        self.mouse_drag_along([(x0 + (x1 - x0) * k / steps, y0 + (y1 - y0) * k / steps)
                               for k in range(1, steps + 1)] if steps else [], start=(x0, y0))

    def mouse_drag_along(self, points, start):
        """Press the left button at start, move through points, release at the last one."""
        self._mouse("mouseMoved", *start, 0, 0)
        self._mouse("mousePressed", *start, 1)
        for x, y in points:
            self._mouse("mouseMoved", x, y, 1, 0)
        self._mouse("mouseReleased", *(points[-1] if points else start), 0)

    def key(self, key, shift=False):
        """Press and release one key: a DOM key name or a printable character."""
        code, vk, text, modifiers = _key_description(key)
        modifiers |= SHIFT if shift else 0
        params = {"key": key, "code": code, "windowsVirtualKeyCode": vk, "modifiers": modifiers}
        down = {"type": "keyDown", "text": text} if text else {"type": "rawKeyDown"}
        self.send("Input.dispatchKeyEvent", {**params, **down})
        self.send("Input.dispatchKeyEvent", {**params, "type": "keyUp"})

    def set_file_input(self, selector, paths):
        """Choose files in the <input type=file> matching selector, as a user does (change fires)."""
        root = self.send("DOM.getDocument")["root"]["nodeId"]
        node = self.send("DOM.querySelector", {"nodeId": root, "selector": selector})["nodeId"]
        self.send("DOM.setFileInputFiles", {"files": [os.path.abspath(p) for p in paths], "nodeId": node})

    def set_viewport(self, width, height):
        """Emulate a width x height viewport at device scale factor 1."""
        self.send("Emulation.setDeviceMetricsOverride", {
            "width": width, "height": height, "deviceScaleFactor": 1, "mobile": False})
