"""`petroscope serve` started as a user starts it, for the tests of this folder: on any free port, read
from the address it prints, and stopped with Ctrl-C (SIGINT), which must end it cleanly."""

import contextlib
import re
import signal
import subprocess


@contextlib.contextmanager
def running_server(binary):
    """Yields (process, port); on leaving, checks that SIGINT stops the server with exit 0."""
    process = subprocess.Popen([binary, "serve", "--port", "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = process.stdout.readline()
    match = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
    assert match, "no address printed: " + line + process.stderr.read()
    yield process, int(match.group(1))
    process.send_signal(signal.SIGINT)
    assert process.wait(timeout=20) == 0, process.stderr.read()
    assert "stopped" in process.stdout.read()
