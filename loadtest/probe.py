"""Health-check latency while the service is loaded: GET /healthz every 50 ms over one
keep-alive connection for a given time; prints count, errors, p50, p99 and max in ms."""
import http.client
import sys
import time

host, port, seconds = sys.argv[1], int(sys.argv[2]), float(sys.argv[3])
lat, errors = [], 0
end = time.monotonic() + seconds
conn = http.client.HTTPConnection(host, port, timeout=10)
while time.monotonic() < end:
    t0 = time.perf_counter()
    try:
        conn.request("GET", "/healthz")
        r = conn.getresponse()
        r.read()
        if r.status != 200:
            errors += 1
    except Exception:
        errors += 1
        conn = http.client.HTTPConnection(host, port, timeout=10)
    lat.append((time.perf_counter() - t0) * 1e3)
    time.sleep(0.05)
lat.sort()
pick = lambda q: lat[min(len(lat) - 1, int(q * len(lat)))]
print(f"healthz_probes {len(lat)} errors {errors} p50_ms {pick(0.5):.2f} p99_ms {pick(0.99):.2f} max_ms {lat[-1]:.2f}")
