#!/usr/bin/env python3
"""radiant serve under load (issue 38): many concurrent and malformed requests
that the server survives and keeps answering, in bounded time.

Usage: serve_stress_test.py path/to/radiant

A model of 100 000 triangles (2.4 MB, so that a response is still being sent
when a client hangs up) and a viewer folder of our own (no npm packages
needed) in a scratch folder; then, while the server runs:

- slow clients that hold connections open, sending their headers a byte at a
  time, while a plain client must still be answered promptly;
- huge request lines and headers (refused, not read without end);
- garbage, an empty request, a bare newline, HTTP/0.9, unknown methods;
- paths out of the folder, plain and escaped (never the file's bytes);
- clients that close the connection mid-response, many times over;
- many concurrent good requests, every one answered with the right bytes.

Afterwards the server still answers, and Ctrl-C ends it with status 0.
"""
import os
import signal
import socket
import struct
import subprocess
import sys
import tempfile
import threading
import time

failures = 0
passes = 0


def check(ok, what):
    global failures, passes
    if ok:
        passes += 1
    else:
        failures += 1
        print("FAIL: " + what, flush=True)


def write_model(path, triangles):
    """A GLB of `triangles` separate triangles in a strip along x (positions only)."""
    positions = bytearray()
    for i in range(triangles):
        x = i * 1e-3
        positions += struct.pack("<9f", x, 0, 0, x + 1e-3, 0, 0, x, 1e-3, 0)
    count = 3 * triangles
    gltf = (
        '{"asset":{"version":"2.0"},"scene":0,"scenes":[{"nodes":[0]}],"nodes":[{"mesh":0}],'
        '"meshes":[{"primitives":[{"attributes":{"POSITION":0}}]}],'
        '"buffers":[{"byteLength":%d}],"bufferViews":[{"buffer":0,"byteLength":%d}],'
        '"accessors":[{"bufferView":0,"componentType":5126,"count":%d,"type":"VEC3",'
        '"min":[0,0,0],"max":[%g,0.001,0]}]}' % (len(positions), len(positions), count, triangles * 1e-3)
    ).encode()
    gltf += b" " * (-len(gltf) % 4)
    body = struct.pack("<II", len(gltf), 0x4E4F534A) + gltf + struct.pack("<II", len(positions), 0x004E4942) + positions
    with open(path, "wb") as f:
        f.write(struct.pack("<III", 0x46546C67, 2, 12 + len(body)) + body)


def request(port, raw, timeout=10.0, keep_alive_wait=0.3):
    """Sends raw bytes, returns what the server sends back (b"" on a reset) until it closes the
    connection, or, once something came, until it is silent for keep_alive_wait seconds (a
    connection it keeps open for the next request)."""
    with socket.create_connection(("127.0.0.1", port), timeout=timeout) as s:
        chunks = []
        try:
            s.sendall(raw)
            while True:
                c = s.recv(1 << 16)
                if not c:
                    break
                chunks.append(c)
                if keep_alive_wait:
                    s.settimeout(keep_alive_wait)
        except (ConnectionResetError, BrokenPipeError, socket.timeout):
            pass
        return b"".join(chunks)


def get(port, path, timeout=10.0):
    """A whole response: the server closes the connection after it (Connection: close)."""
    raw = ("GET %s HTTP/1.1\r\nHost: 127.0.0.1\r\nConnection: close\r\n\r\n" % path).encode()
    return request(port, raw, timeout, keep_alive_wait=None)


def status(response):
    line = response.split(b"\r\n", 1)[0].split()
    return int(line[1]) if len(line) >= 2 and line[1].isdigit() else None


def body(response):
    return response.split(b"\r\n\r\n", 1)[1] if b"\r\n\r\n" in response else b""


def answered(port, deadline):
    """A plain GET of index.html, answered within `deadline` seconds."""
    start = time.monotonic()
    try:
        r = get(port, "/index.html", timeout=deadline)
    except OSError:
        return False
    return status(r) == 200 and body(r) == b"<html>viewer</html>\n" and time.monotonic() - start < deadline


def main():
    radiant = sys.argv[1]
    work = tempfile.mkdtemp(prefix="serve-stress-")
    os.chdir(work)
    os.makedirs("viewer/node_modules/three/build")
    with open("viewer/index.html", "w") as f:
        f.write("<html>viewer</html>\n")
    with open("viewer/node_modules/three/build/three.module.js", "w") as f:
        f.write("export {};\n")
    with open("secret.txt", "w") as f:
        f.write("secret bytes\n")
    write_model("model.glb", 100_000)
    model = open("model.glb", "rb").read()

    server = subprocess.Popen([radiant, "serve", "model.glb", "--port", "0", "--viewer", "viewer", "-q"],
                              stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        url = server.stdout.readline().strip()  # http://127.0.0.1:PORT/index.html?model=model.glb
        port = int(url.split(":")[2].split("/")[0])
        check(answered(port, 5), "a plain GET before the load")

        # Slow clients: each sends a byte of its request every 0.5 s and never
        # finishes. While they hold their connections, a plain client is answered.
        slow = []
        stop = threading.Event()

        def dribble():
            try:
                s = socket.create_connection(("127.0.0.1", port), timeout=5)
            except OSError:
                return
            slow.append(s)
            text = b"GET /index.html HTTP/1.1\r\nHost: 127.0.0.1\r\nX-Slow: " + b"a" * 10_000
            for byte in text:
                if stop.wait(0.5):
                    break
                try:
                    s.send(bytes([byte]))
                except OSError:
                    break

        slow_clients = 32
        dribblers = [threading.Thread(target=dribble, daemon=True) for _ in range(slow_clients)]
        for t in dribblers:
            t.start()
        time.sleep(1.5)
        check(answered(port, 3), "a plain GET while %d slow clients hold connections" % slow_clients)

        # Huge request line and huge headers: refused (or the connection closed), in bounded time.
        start = time.monotonic()
        r = request(port, b"GET /" + b"a" * 1_000_000 + b" HTTP/1.1\r\nHost: x\r\n\r\n")
        check(status(r) in (None, 400, 414) and time.monotonic() - start < 10, "a 1 MB request line: %r" % r[:40])
        r = request(port, b"GET /index.html HTTP/1.1\r\n" + b"X-Big: " + b"b" * 1_000_000 + b"\r\n\r\n")
        check(status(r) in (None, 400, 431) and time.monotonic() - start < 20, "a 1 MB header: %r" % r[:40])
        many = b"".join(b"X-%d: v\r\n" % i for i in range(100_000))
        r = request(port, b"GET /index.html HTTP/1.1\r\nHost: x\r\n" + many + b"\r\n")
        check(status(r) in (None, 400, 431) and time.monotonic() - start < 30, "100 000 headers: %r" % r[:40])
        r = request(port, b"GET /index.html HTTP/1.1\r\nHost: x\r\n" + b"".join(b"X-%d: v\r\n" % i for i in range(50)) +
                    b"\r\n")
        check(status(r) == 200, "a request with 50 headers is answered: %r" % r[:40])

        # Not HTTP at all: an error status or a closed connection, never a crash.
        for raw in [b"\r\n\r\n", b"\n", b"GARBAGE\r\n\r\n", b"GET\r\n\r\n", b"GET /\r\n\r\n",
                    b"BREW /index.html HTTP/1.1\r\nHost: x\r\n\r\n", bytes(range(256)) * 16,
                    b"POST /index.html HTTP/1.1\r\nHost: x\r\nContent-Length: 99999999999\r\n\r\nabc"]:
            try:
                r = request(port, raw, timeout=10)
                check(status(r) is None or status(r) >= 400, "malformed %r: answered %r" % (raw[:30], r[:40]))
            except OSError:
                pass  # a reset is an answer too
        # A GET with odd framing (a future version, a negative length, a broken
        # chunked body it has no use for): any answer, as long as one comes.
        for raw in [b"GET /index.html HTTP/9.9\r\nHost: x\r\n\r\n",
                    b"GET /index.html HTTP/1.1\r\nHost: x\r\nContent-Length: -5\r\n\r\n",
                    b"GET /index.html HTTP/1.1\r\nHost: x\r\nTransfer-Encoding: chunked\r\n\r\nzz\r\n"]:
            try:
                request(port, raw, timeout=10)
            except OSError:
                pass
        check(server.poll() is None, "the server is still running after malformed requests")

        # Paths out of the viewer's folder, plain and escaped: never the file's bytes.
        for path in ["/../secret.txt", "/../../etc/passwd", "/%2e%2e/secret.txt", "/..%2fsecret.txt",
                     "/%2e%2e%2fsecret.txt", "/.%2e/secret.txt", "/viewer/../../secret.txt", "//etc/passwd",
                     "/..\\secret.txt", "/%2e%2e%5csecret.txt", "/model.glb/../../secret.txt"]:
            r = get(port, path)
            check(status(r) in (400, 403, 404) and b"secret bytes" not in r and b"root:" not in r,
                  "%s: %r" % (path, r[:60]))

        # Clients that hang up mid-response, many times.
        for _ in range(50):
            with socket.create_connection(("127.0.0.1", port), timeout=10) as s:
                s.sendall(b"GET /model.glb HTTP/1.1\r\nHost: x\r\n\r\n")
                s.recv(1000)
                s.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))  # a reset, not a FIN
        check(server.poll() is None, "the server is still running after 50 clients hung up mid-response")

        # Many good requests at once: every one answered with the model's bytes.
        results = []

        def fetch():
            try:
                r = get(port, "/model.glb", timeout=30)
                results.append(status(r) == 200 and body(r) == model)
            except OSError:
                results.append(False)

        fetchers = [threading.Thread(target=fetch) for _ in range(64)]
        for t in fetchers:
            t.start()
        for t in fetchers:
            t.join(60)
        check(len(results) == 64 and all(results), "64 concurrent downloads: %d of 64 whole" % sum(results))

        stop.set()
        for s in slow:
            s.close()
        for t in dribblers:
            t.join(10)
        check(answered(port, 5), "a plain GET after the load")
    finally:
        if server.poll() is None:
            server.send_signal(signal.SIGINT)
        try:
            code = server.wait(15)
        except subprocess.TimeoutExpired:
            server.kill()
            code = "hung"
    check(code == 0, "Ctrl-C ends serve with status 0, got %s (stderr: %s)" % (code, server.stderr.read()[-500:]))
    print("%d passed, %d failed" % (passes, failures))
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())
