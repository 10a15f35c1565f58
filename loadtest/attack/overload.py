"""Overload: wrk at each of CONNECTIONS (e.g. 64 and 128) against POST /v1/lightcurves of a
100-epoch box-wing request, DURATION seconds each, while /healthz is probed every 50 ms on
its own connection. Reports successful (200) requests/s, the other answers, and the
/healthz p50/p99/max; checks that nothing but 200 and 503 came back, that successful
throughput at the most connections is at least RATIO of that at the fewest, and that the
/healthz p99 is under P99_MS (the last two only when `--strict`).

Usage: overload.py BINARY PORT WORKDIR DURATION CONNECTIONS[,CONNECTIONS…] [--strict]
Needs `wrk` on PATH. Loopback only; every run is bounded by DURATION."""
import json
import os
import re
import subprocess
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(__file__))
from common import HOST, Server, request  # noqa: E402
import http.client  # noqa: E402

binary, port, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
duration = int(sys.argv[4])
levels = [int(c) for c in sys.argv[5].split(",")]
strict = "--strict" in sys.argv
RATIO, P99_MS = 0.9, 20.0
here = os.path.dirname(os.path.abspath(__file__))

r = json.load(open(os.path.join(here, "..", "..", "scenes", "box-wing.json")))
r["epochs"] = r["epochs"][:100]
body_file = os.path.join(work, "overload-request.json")
os.makedirs(work, exist_ok=True)
with open(body_file, "w") as f:
    json.dump(r, f)


def probe(seconds, out):
    lat, errors = [], 0
    end = time.monotonic() + seconds
    conn = http.client.HTTPConnection(HOST, port, timeout=10)
    while time.monotonic() < end:
        t0 = time.perf_counter()
        try:
            conn.request("GET", "/healthz")
            resp = conn.getresponse()
            resp.read()
            errors += resp.status != 200
        except OSError:
            errors += 1
            conn = http.client.HTTPConnection(HOST, port, timeout=10)
        lat.append((time.perf_counter() - t0) * 1e3)
        time.sleep(0.05)
    lat.sort()
    out.update(n=len(lat), errors=errors, p50=lat[len(lat) // 2],
               p99=lat[min(len(lat) - 1, int(0.99 * len(lat)))], max=lat[-1])


server = Server(binary, port, os.path.join(work, "overload")).start()
failures, results = [], {}
try:
    st, _, b = request("POST", port, "/v1/lightcurves", json.dumps(r))
    assert st == 200, b[:200]
    for c in levels:
        got = {}
        # probe while saturated, not during the ramp-up
        t = threading.Timer(2, probe, args=(max(1, duration - 4), got))
        t.start()
        env = dict(os.environ, GLINT_LOADTEST_BODY=body_file)
        out = subprocess.run(
            ["wrk", "-t2", f"-c{c}", f"-d{duration}s", "--timeout", "30s",
             "-s", os.path.join(here, "overload.lua"), f"http://{HOST}:{port}/v1/lightcurves"],
            env=env, capture_output=True, text=True, timeout=duration + 60).stdout
        t.join()
        counts = {int(s): int(n) for s, n in re.findall(r"^status (\d+) (\d+)$", out, re.M)}
        took = re.search(r"requests in ([\d.]+)s", out)
        secs = float(took.group(1)) if took else duration
        sock = re.search(r"Socket errors: (.*)", out)
        ok_rps = counts.get(200, 0) / secs
        results[c] = ok_rps
        print(f"overload_{c}_ok_per_s {ok_rps:.1f}")
        print(f"overload_{c}_answers {json.dumps(dict(sorted(counts.items())))}")
        print(f"overload_{c}_socket_errors {sock.group(1) if sock else 'none'}")
        print(f"overload_{c}_healthz_ms p50 {got['p50']:.2f} p99 {got['p99']:.2f} max {got['max']:.2f} "
              f"(n={got['n']}, errors={got['errors']})")
        other = {s: n for s, n in counts.items() if s not in (200, 503)}
        if other:
            failures.append(f"{c} connections: answers other than 200/503: {other}")
        if got["errors"]:
            failures.append(f"{c} connections: /healthz failed {got['errors']} times")
        if strict and got["p99"] >= P99_MS:
            failures.append(f"{c} connections: /healthz p99 {got['p99']:.1f} ms >= {P99_MS} ms")
    lo, hi = min(levels), max(levels)
    if len(levels) > 1 and results[lo] > 0:
        ratio = results[hi] / results[lo]
        print(f"overload_ratio_{hi}_to_{lo} {ratio:.3f}")
        if strict and ratio < RATIO:
            failures.append(f"successful req/s at {hi} is {ratio:.1%} of that at {lo} (< {RATIO:.0%})")
    print(f"overload_peak_rss_mib {server.peak_rss_mib():.0f}")
finally:
    server.stop()
for f in failures:
    print(f"  FAIL {f}")
sys.exit(1 if failures else 0)
