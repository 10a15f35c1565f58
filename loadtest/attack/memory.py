"""Peak resident memory of `glint serve` under the two loads of issue 18:

  downloads  4 concurrent GET /v1/jobs/{id}/result of one large stored result, as JSON and
             as CSV (each on a freshly started server, so its peak is the downloads' own)
  meshes     24 concurrent POST /v1/lightcurves, each a 1M-triangle OBJ mesh

Usage: memory.py BINARY PORT WORKDIR [downloads|meshes|all] [RESULT_MB]
Prints `key value` lines. Loopback only; every wait is bounded."""
import datetime
import json
import os
import sys
import threading
import time

sys.path.insert(0, os.path.dirname(__file__))
from common import Server, request, wait_job  # noqa: E402

binary, port, work = sys.argv[1], int(sys.argv[2]), sys.argv[3]
what = sys.argv[4] if len(sys.argv) > 4 else "all"
result_mb = float(sys.argv[5]) if len(sys.argv) > 5 else 200


def concurrently(n, fn):
    out = [None] * n
    threads = [threading.Thread(target=lambda i=i: out.__setitem__(i, fn(i))) for i in range(n)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(timeout=600)
    return out


def iso(seconds):
    t = datetime.datetime(2026, 12, 3, tzinfo=datetime.timezone.utc)
    return (t + datetime.timedelta(seconds=seconds)).isoformat(timespec="milliseconds").replace("+00:00", "Z")


def large_result_request(mb):
    # A one-plate object along an orbit every 0.1 s: ~440 bytes of JSON an epoch, from a
    # body of a few hundred bytes (the epochs come from `geometry`).
    epochs = int(mb * 1e6 / 440)
    return {
        "object": {"mesh": {"builtin": "plate"},
                   "materials": [{"name": "surface", "model": "lambert", "albedo": 0.5}]},
        "geometry": {
            "orbit": {"tle": [
                "1 25544U 98067A   26336.50000000  .00016717  00000-0  30306-3 0  9992",
                "2 25544  51.6400 200.0000 0005000  90.0000 270.0000 15.50000000 49995"]},
            "site": {"lat_deg": 32.78, "lon_deg": -105.82, "alt_m": 2790},
            "times": {"start": iso(0), "stop": iso((epochs - 1) * 0.1), "step_s": 0.1},
            "attitude": {"law": "nadir", "yaw_deg": 0},
        },
        "illumination": {"band_um": [0.4, 0.7], "earthshine": "off"},
    }


def downloads():
    data = os.path.join(work, "downloads")
    s = Server(binary, port, data).start()
    try:
        st, _, body = request("POST", port, "/v1/jobs", json.dumps(large_result_request(result_mb)))
        assert st == 202, body
        job = json.loads(body)["id"]
        final = wait_job(port, job, 900)
        assert final["state"] == "done", final
    finally:
        s.stop()
    for form, accept in (("json", "application/json"), ("csv", "text/csv")):
        s = Server(binary, port, data).start()
        try:
            time.sleep(0.5)
            idle = s.rss_mib()
            t0 = time.monotonic()
            got = concurrently(4, lambda i: request(
                "GET", port, f"/v1/jobs/{job}/result", headers={"Accept": accept}, read=False))
            secs = time.monotonic() - t0
            assert all(g[0] == 200 for g in got), [g[0] for g in got]
            sizes = {int(g[2]) for g in got}
            assert len(sizes) == 1, sizes
            print(f"download_{form}_bytes {sizes.pop()}")
            print(f"download_{form}_4x_seconds {secs:.1f}")
            print(f"download_{form}_idle_rss_mib {idle:.0f}")
            print(f"download_{form}_4x_peak_rss_mib {s.peak_rss_mib():.0f}")
        finally:
            s.stop()


def mesh_body(side=708):
    # A flat side x side grid of vertices: 2 (side - 1)^2 triangles (999,698 at 708).
    lines = [f"v {i % side} {i // side} 0" for i in range(side * side)]
    for y in range(side - 1):
        for x in range(side - 1):
            a = y * side + x + 1
            lines.append(f"f {a} {a + 1} {a + side}")
            lines.append(f"f {a + 1} {a + side + 1} {a + side}")
    return json.dumps({
        "object": {"mesh": {"obj": "\n".join(lines) + "\n"},
                   "materials": [{"name": "surface", "model": "lambert", "albedo": 0.5}]},
        "epochs": [{"t": 0, "sun": [0, 0, 1], "observer": [0, 0, 1e6]}],
    }).encode()


def meshes():
    body = mesh_body()
    s = Server(binary, port, os.path.join(work, "meshes"), "--request-timeout-secs", "120").start()
    try:
        time.sleep(0.5)
        idle = s.rss_mib()
        t0 = time.monotonic()
        got = concurrently(24, lambda i: request("POST", port, "/v1/lightcurves", body, timeout=300)[0])
        secs = time.monotonic() - t0
        counts = {c: got.count(c) for c in sorted(set(got), key=str)}
        assert all(c in (200, 503) for c in got), counts
        print(f"meshes_body_mib {len(body) / 2**20:.1f}")
        print(f"meshes_24x_statuses {json.dumps(counts)}")
        print(f"meshes_24x_seconds {secs:.1f}")
        print(f"meshes_idle_rss_mib {idle:.0f}")
        print(f"meshes_24x_peak_rss_mib {s.peak_rss_mib():.0f}")
    finally:
        s.stop()


if what in ("downloads", "all"):
    downloads()
if what in ("meshes", "all"):
    meshes()
