#!/usr/bin/env bash
# Load test of the HTTP service on loopback: box-wing, 100-epoch light-curve requests.
#
# Reports, at saturation: requests/s, p50/p99 latency and errors (wrk); p99 of /healthz
# probed while saturated (probe.py); and the engine's own epochs/s on the same request
# (engine_rate example) for the service/engine ratio. Bounded: DURATION seconds of load.
# Loopback only. Other processes on the machine skew every number: check `uptime` first.
#
#   loadtest/run.sh                 # defaults below
#   DURATION=30 CONNECTIONS=8 loadtest/run.sh
set -euo pipefail
cd "$(dirname "$0")/.."

DURATION=${DURATION:-20}        # seconds of load
CONNECTIONS=${CONNECTIONS:-4}   # concurrent clients: 2 slots busy + 2 waiting
PORT=${PORT:-18181}
EPOCHS=${EPOCHS:-100}
WORK=$(mktemp -d /tmp/glint-loadtest.XXXXXX)

if ! command -v wrk >/dev/null; then
    echo "installing wrk…" >&2
    if [ "$(id -u)" = 0 ]; then apt-get install -y wrk >/dev/null; else sudo apt-get install -y wrk >/dev/null; fi
fi
command -v python3 >/dev/null || { echo "python3 is needed (request cutting, health probe)" >&2; exit 1; }

cargo build --release --locked --bin glint --example engine_rate >&2

# The request: scenes/box-wing.json cut to its first $EPOCHS epochs.
python3 - "$EPOCHS" > "$WORK/request.json" <<'PY'
import json, sys
r = json.load(open("scenes/box-wing.json"))
r["epochs"] = r["epochs"][: int(sys.argv[1])]
print(json.dumps(r))
PY

target/release/glint serve --addr "127.0.0.1:$PORT" --data-dir "$WORK/data" 2> "$WORK/server.log" &
SERVER=$!
trap 'kill $SERVER 2>/dev/null || true; rm -rf "$WORK"' EXIT
for _ in $(seq 100); do
    python3 -c "import urllib.request as u; u.urlopen('http://127.0.0.1:$PORT/healthz', timeout=1)" 2>/dev/null && break
    sleep 0.1
done
# One request first: it must succeed (and warms the caches).
python3 - "$PORT" "$WORK/request.json" <<'PY'
import sys, urllib.request as u
req = u.Request(f"http://127.0.0.1:{sys.argv[1]}/v1/lightcurves", data=open(sys.argv[2], "rb").read(),
                headers={"Content-Type": "application/json"})
assert u.urlopen(req, timeout=60).status == 200
PY

# Baseline: /healthz with the service idle, to tell the service's own effect on the
# saturated p99 from whatever else runs on the machine.
python3 loadtest/probe.py 127.0.0.1 "$PORT" 8 > "$WORK/probe-idle.txt"

echo "== load: $CONNECTIONS connections, ${DURATION}s, box-wing $EPOCHS epochs per request" >&2
python3 loadtest/probe.py 127.0.0.1 "$PORT" "$((DURATION - 4))" > "$WORK/probe.txt" &
PROBE=$!
sleep 2   # probe while saturated, not during ramp-up
GLINT_LOADTEST_BODY="$WORK/request.json" wrk -t1 -c"$CONNECTIONS" -d"${DURATION}s" --timeout 30s --latency \
    -s loadtest/post.lua "http://127.0.0.1:$PORT/v1/lightcurves" | tee "$WORK/wrk.txt" >&2 &
WRK=$!
wait $PROBE
wait $WRK
kill -TERM $SERVER; wait $SERVER || true

echo "== engine alone, same request, 2 requests in flight (the service's slots)" >&2
# At the niceness of the service's light-curve threads, so that other load on the machine
# weighs on both alike.
nice -n 10 target/release/examples/engine_rate "$WORK/request.json" 10 2 | tee "$WORK/engine.txt" >&2

echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)" >&2
python3 - "$WORK" "$EPOCHS" <<'PY'
import re, sys
work, epochs = sys.argv[1], int(sys.argv[2])
wrk = open(f"{work}/wrk.txt").read()
rps = float(re.search(r"Requests/sec:\s+([\d.]+)", wrk).group(1))
def pct(p):
    m = re.search(rf"^\s+{p}%\s+([\d.]+)(us|ms|s)\s*$", wrk, re.M)
    v, unit = float(m.group(1)), m.group(2)
    return v * {"us": 1e-3, "ms": 1.0, "s": 1e3}[unit]
non2xx = re.search(r"Non-2xx or 3xx responses: (\d+)", wrk)
sock = re.search(r"Socket errors: (.*)", wrk)
def load_probe(name):
    words = open(f"{work}/{name}").read().split()
    return dict(zip(words[::2], words[1::2]))
probe, idle = load_probe("probe.txt"), load_probe("probe-idle.txt")
engine = open(f"{work}/engine.txt").read().split()
eng = float(engine[engine.index("engine_simulate_epochs_per_s") + 1])
eng_full = float(engine[engine.index("engine_full_epochs_per_s") + 1])
svc = rps * epochs
print(f"requests_per_s        {rps:.1f}")
print(f"latency_p50_ms        {pct(50):.1f}")
print(f"latency_p99_ms        {pct(99):.1f}")
print(f"errors                non2xx={non2xx.group(1) if non2xx else 0} socket={sock.group(1) if sock else 'none'}")
print(f"healthz_p50_ms        {probe['p50_ms']}  (n={probe['healthz_probes']}, errors={probe['errors']})")
print(f"healthz_p99_ms        {probe['p99_ms']}  (max {probe['max_ms']}; idle service: p99 {idle['p99_ms']}, max {idle['max_ms']})")
print(f"service_epochs_per_s  {svc:.0f}")
print(f"engine_epochs_per_s   {eng:.0f}  (simulate only; {eng_full:.0f} with parse+validate+serialise)")
print(f"service/engine        {100 * svc / eng:.1f}%  (vs parse+simulate+serialise: {100 * svc / eng_full:.1f}%)")
PY
