"""`petroscope serve` under load and abuse, over real sockets: many clients at once asking for views,
numbers and files, bad parameters, foreign Host headers, oversized bodies and long queries. Every request
gets its expected status, the server stays up, and Ctrl-C still stops it cleanly."""

import concurrent.futures
import http.client
import json
import os
import re
import signal
import subprocess
import time
import urllib.parse

import pytest

BINARY = os.environ.get("PETROSCOPE_BINARY")
pytestmark = pytest.mark.skipif(not BINARY, reason="needs the petroscope binary")


@pytest.fixture(scope="module")
def port():
    process = subprocess.Popen([BINARY, "serve", "--port", "0"], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    line = process.stdout.readline()
    match = re.search(r"http://127\.0\.0\.1:(\d+)/", line)
    assert match, "no address printed: " + line + process.stderr.read()
    yield int(match.group(1))
    process.send_signal(signal.SIGINT)
    assert process.wait(timeout=20) == 0, process.stderr.read()


def request(port, path, method="GET", body=None, host=None):
    """(status, body) of one request on its own connection; status 0 when the server closed it unanswered."""
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    headers = {"Host": host or f"127.0.0.1:{port}"}
    try:
        connection.request(method, path, body=body, headers=headers)
        response = connection.getresponse()
        return response.status, response.read()
    except (ConnectionError, http.client.RemoteDisconnected):
        return 0, b""
    finally:
        connection.close()


def view(**parameters):
    return "/api/view?" + urllib.parse.urlencode(parameters)


# (path, expected status): what a busy classroom and a careless script send at once.
MIXED_LOAD = [
    ("/", 200), ("/microscope.js", 200), ("/api/catalog", 200),
    (view(mineral="quartz", cut="optic-axis", tilt_deg=50), 200),
    (view(mineral="calcite", cut="optic-axis", optics="conoscope", size_px=64), 200),
    ("/api/grain?section=granite&x=10&y=20", 200),
    (view(thickness_um="-3"), 400), (view(section="../../etc/passwd"), 400), (view(size_px=99999, optics="conoscope"), 400),
    (view(mineral="\x1b[31mred"), 400), ("/api/view?plate=mica&plate=gypsum", 400), (view(zoom=3), 400),
    ("/../../etc/passwd", 404), ("/api/secret", 404),
]


def test_many_clients_at_once_get_their_answers(port):
    started = time.monotonic()
    with concurrent.futures.ThreadPoolExecutor(max_workers=16) as pool:
        futures = {pool.submit(request, port, path): expected for path, expected in MIXED_LOAD * 6}
        statuses = [(future.result()[0], expected) for future, expected in futures.items()]
    elapsed = time.monotonic() - started
    assert all(status == expected for status, expected in statuses), [s for s in statuses if s[0] != s[1]]
    print(f"server load: {len(statuses)} requests from 16 clients in {elapsed:.2f} s")
    assert request(port, "/api/catalog")[0] == 200


def test_bad_parameters_get_a_message_that_names_them(port):
    status, body = request(port, view(mineral="kryptonite\x1b[2J"))
    assert status == 400
    message = json.loads(body)["error"]
    assert "parameter 'mineral'" in message and "\\x1b[2J" in message and "\x1b" not in message


def test_a_page_of_another_site_cannot_reach_the_server(port):
    """DNS rebinding: a name that resolves to 127.0.0.1 still arrives with its own Host header."""
    status, _ = request(port, "/api/catalog", host=f"attacker.example:{port}")
    assert status == 403


def multipart(files):
    """A multipart/form-data body of (field, filename, bytes), as a browser's FormData sends it."""
    boundary = "petroscope-test-boundary"
    parts = [f'--{boundary}\r\nContent-Disposition: form-data; name="{field}"; filename="{name}"\r\n'
             f"Content-Type: application/octet-stream\r\n\r\n".encode() + content + b"\r\n" for field, name, content in files]
    return b"".join(parts) + f"--{boundary}--\r\n".encode(), f"multipart/form-data; boundary={boundary}"


def post_section(port, files):
    body, content_type = multipart(files)
    connection = http.client.HTTPConnection("127.0.0.1", port, timeout=60)
    try:
        connection.request("POST", "/api/section", body=body, headers={"Content-Type": content_type, "Host": f"127.0.0.1:{port}"})
        response = connection.getresponse()
        return response.status, json.loads(response.read())
    finally:
        connection.close()


def example_files(name="granite"):
    folder = os.path.join(os.environ["PETROSCOPE_SOURCE_DIR"], "thin_sections", name)
    with open(os.path.join(folder, "section.txt"), "rb") as description, open(os.path.join(folder, "grains.png"), "rb") as grains:
        return description.read(), grains.read()


def test_a_section_sent_to_the_server_is_viewed_by_the_name_it_gets(port):
    description, grains = example_files()
    status, answer = post_section(port, [("description", "section.txt", description), ("map", "grains.png", grains)])
    assert status == 200, answer
    assert answer["grains"] > 100 and answer["width_px"] == 512
    status, body = request(port, view(section=answer["section"]))
    assert status == 200 and int.from_bytes(body[4:8], "little") == 512


def test_a_section_sent_to_the_server_reads_nothing_but_what_was_sent(port):
    description, grains = example_files()
    cases = [
        ([("map", "grains.png", grains)], "no section description"),
        ([("description", "section.txt", description), ("map", "../grains.png", grains)], "plain name"),
        ([("description", "section.txt", description), ("map", "grains.png", b"GIF89a" + grains)], "is not a PNG file"),
        ([("description", "section.txt", description.replace(b"grain_map: grains.png", b"grain_map: /etc/passwd")),
          ("map", "grains.png", grains)], "'/etc/passwd' was not sent with the description"),
        ([("description", "mine.txt", description.replace(b"pixel_size_um: 8", b"pixel_size_um: -8")), ("map", "grains.png", grains)],
         "'mine.txt':"),
    ]
    for files, expected in cases:
        status, answer = post_section(port, files)
        assert status == 400 and expected in answer["error"], (expected, answer)
        assert "petroscope-upload-" not in answer["error"]  # the private folder stays private


def test_oversized_bodies_and_queries_are_refused(port):
    status, _ = request(port, "/api/section", method="POST", body=b"x" * (17 << 20))
    assert status in (0, 413)  # refused before or after reading the cap; never served
    status, _ = request(port, "/api/view", method="POST", body=b"x")
    assert status == 404
    status, _ = request(port, "/api/view?mineral=" + "q" * 20000)
    assert status in (400, 414)
    assert request(port, "/api/catalog")[0] == 200
