"""Shared by the attack scripts: start and stop `glint serve` on loopback, plain HTTP over
one socket, and the process's peak memory. Standard library only; every wait is bounded."""
import http.client
import json
import os
import signal
import subprocess
import time

HOST = "127.0.0.1"


class Server:
    """`glint serve` on 127.0.0.1:`port` with its own data directory; stderr to a log."""

    def __init__(self, binary, port, data_dir, *extra, log=None):
        self.binary, self.port, self.data_dir, self.extra = binary, port, data_dir, list(extra)
        self.log = log or os.path.join(data_dir + ".log")
        self.proc = None

    def start(self, timeout=30):
        os.makedirs(self.data_dir, exist_ok=True)
        args = [self.binary, "serve", "--addr", f"{HOST}:{self.port}",
                "--data-dir", self.data_dir, *self.extra]
        env = dict(os.environ)
        env.pop("GLINT_API_TOKEN", None)
        env.setdefault("GLINT_LOG", "warn")
        self.proc = subprocess.Popen(args, stdout=subprocess.DEVNULL,
                                     stderr=open(self.log, "ab"), env=env)
        end = time.monotonic() + timeout
        while time.monotonic() < end:
            if self.proc.poll() is not None:
                raise RuntimeError(f"glint serve exited with {self.proc.returncode}; see {self.log}")
            try:
                if request("GET", self.port, "/healthz", timeout=1)[0] == 200:
                    return self
            except OSError:
                pass
            time.sleep(0.05)
        raise RuntimeError(f"glint serve did not answer within {timeout} s")

    @property
    def pid(self):
        return self.proc.pid

    def peak_rss_mib(self):
        """VmHWM: the most resident memory the process has had since it started."""
        with open(f"/proc/{self.pid}/status") as f:
            for line in f:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024
        raise RuntimeError("no VmHWM")

    def rss_mib(self):
        with open(f"/proc/{self.pid}/status") as f:
            for line in f:
                if line.startswith("VmRSS:"):
                    return int(line.split()[1]) / 1024
        raise RuntimeError("no VmRSS")

    def kill9(self):
        self.proc.send_signal(signal.SIGKILL)
        self.proc.wait(timeout=30)

    def stop(self, timeout=60):
        if self.proc and self.proc.poll() is None:
            self.proc.send_signal(signal.SIGTERM)
            try:
                self.proc.wait(timeout=timeout)
            except subprocess.TimeoutExpired:
                self.kill9()


def request(method, port, path, body=None, headers=None, timeout=120, read=True):
    """One request on its own connection: (status, headers dict (lower-case), body bytes)."""
    conn = http.client.HTTPConnection(HOST, port, timeout=timeout)
    try:
        h = {"Content-Type": "application/json"} if body is not None else {}
        h.update(headers or {})
        if isinstance(body, str):
            body = body.encode()
        try:
            conn.request(method, path, body=body, headers=h)
        except (BrokenPipeError, ConnectionResetError):
            # Answered (413, 503) and closed before the whole body was sent: the answer
            # may still be there to read.
            pass
        r = conn.getresponse()
        data = r.read() if read else drain(r)
        return r.status, {k.lower(): v for k, v in r.getheaders()}, data
    finally:
        conn.close()


def drain(resp, chunk=1 << 20):
    """Reads a body to its end without keeping it; returns its length as bytes of text."""
    n = 0
    while True:
        b = resp.read(chunk)
        if not b:
            return str(n).encode()
        n += len(b)


def wait_job(port, job_id, timeout):
    """Polls a job until it is final; returns its status (dict)."""
    end = time.monotonic() + timeout
    while time.monotonic() < end:
        status, _, body = request("GET", port, f"/v1/jobs/{job_id}")
        s = json.loads(body)
        if status == 200 and s["state"] in ("done", "failed", "cancelled"):
            return s
        time.sleep(0.1)
    raise TimeoutError(f"job {job_id} not final within {timeout} s")


def raw(port, data, timeout=30):
    """Sends `data` as is on a fresh connection and reads until the server closes (the
    request should say `Connection: close`): (status, headers dict, body bytes, seconds).
    Status 0 when nothing parseable came back."""
    import socket

    t0 = time.monotonic()
    s = socket.create_connection((HOST, port), timeout=timeout)
    try:
        try:
            s.sendall(data)
        except (BrokenPipeError, ConnectionResetError):
            pass  # answered and closed before everything was sent
        out = b""
        try:
            while True:
                b = s.recv(1 << 16)
                if not b:
                    break
                out += b
        except (ConnectionResetError, socket.timeout):
            pass
    finally:
        s.close()
    secs = time.monotonic() - t0
    head, _, body = out.partition(b"\r\n\r\n")
    lines = head.decode("latin-1").split("\r\n")
    try:
        status = int(lines[0].split(" ")[1])
    except (IndexError, ValueError):
        return 0, {}, out, secs
    headers = {}
    for line in lines[1:]:
        k, _, v = line.partition(":")
        headers[k.strip().lower()] = v.strip()
    if "chunked" in headers.get("transfer-encoding", ""):
        joined, rest = b"", body
        while rest:
            size, _, rest = rest.partition(b"\r\n")
            n = int(size.split(b";")[0] or b"0", 16)
            if n == 0:
                break
            joined, rest = joined + rest[:n], rest[n + 2:]
        body = joined
    return status, headers, body, secs
