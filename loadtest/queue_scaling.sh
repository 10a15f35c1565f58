#!/usr/bin/env bash
# Throughput of the shared PostgreSQL queue: one big job computed by 1, 2 and 4
# `glint worker` processes, each pinned to one core with taskset (worker i on core
# i mod cores) and computing on one thread; epochs/s from the job's own times (created to
# finished, from the database), and the queue's overhead per chunk (claim + write, in
# ms, as each worker measures it) against the chunk's computation.
#
#   loadtest/queue_scaling.sh [EPOCHS] [SCENE]     (default 3000 epochs of scenes/rocket-body.json)
#
# Starts its own PostgreSQL (.ci/postgres.sh) and a release build of glint; chunks are
# sized by the service (about a second of work each), as in production.
set -euo pipefail
cd "$(dirname "$0")/.."
epochs=${1:-3000}
scene=${2:-scenes/rocket-body.json}
cores=$(nproc)

cargo build --release --locked --quiet
bin=target/release/glint
work=$(mktemp -d /tmp/glint-scaling.XXXXXX)
chmod 755 "$work"
port=$(python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1])')
pids=()
cleanup() {
    for p in "${pids[@]}"; do kill "$p" 2>/dev/null || true; done
    bash .ci/postgres.sh stop "$work/pg" >/dev/null 2>&1 || true
    rm -rf "$work"
}
trap cleanup EXIT
url=$(bash .ci/postgres.sh start "$work/pg" "$port")

python3 - "$scene" "$epochs" >"$work/job.json" <<'PY'
import json, sys
d = json.load(open(sys.argv[1]))
n = int(sys.argv[2])
e = d["epochs"]
d["epochs"] = [e[i % len(e)] for i in range(n)]
print(json.dumps(d))
PY

GLINT_LOG=warn "$bin" serve --addr 127.0.0.1:0 --database-url "$url" --workers 0 2>"$work/api.log" &
pids+=($!)
for _ in $(seq 100); do grep -q "listening on" "$work/api.log" && break; sleep 0.1; done
addr=$(sed -n 's/.*listening on http:\/\/\([^ ]*\).*/\1/p' "$work/api.log")

echo "job: $epochs epochs of $scene; $cores cores on this machine; $(uptime | sed 's/.*load/load/')"
printf '%-8s %-12s %-10s %-8s %-12s %-12s %-14s %s\n' workers epochs/s speed-up chunks claim_ms write_ms compute_ms overhead
base=""
for n in 1 2 4; do
    wpids=()
    for i in $(seq 0 $((n - 1))); do
        GLINT_LOG=warn taskset -c $((i % cores)) "$bin" worker --database-url "$url" --threads 1 \
            2>"$work/worker-$n-$i.log" &
        wpids+=($!)
        pids+=($!)
    done
    sleep 1
    id=$(curl -sf -H 'Content-Type: application/json' --data-binary @"$work/job.json" "http://$addr/v1/jobs" \
        | python3 -c 'import json,sys; print(json.load(sys.stdin)["id"])')
    while :; do
        state=$(curl -sf "http://$addr/v1/jobs/$id" | python3 -c 'import json,sys; print(json.load(sys.stdin)["state"])')
        [ "$state" = done ] && break
        [ "$state" = failed ] && { echo "job failed" >&2; exit 1; }
        sleep 0.2
    done
    for p in "${wpids[@]}"; do kill -TERM "$p"; wait "$p" || true; done
    ms=$(psql -tA "$url" -c "SELECT finished_ms - created_ms FROM glint_jobs WHERE id = '$id'")
    chunks=$(psql -tA "$url" -c "SELECT count(*) FROM glint_chunks WHERE job_id = '$id'")
    rate=$(python3 -c "print(f'{$epochs / ($ms / 1000):.0f}')")
    [ -z "$base" ] && base=$rate
    # the workers' own measurement: mean claim, write and compute per chunk
    stats=$(cat "$work"/worker-$n-*.log | python3 -c '
import re, sys
rows = [tuple(map(float, m.groups())) for m in
        (re.search(r"(\d+) chunks written; per chunk: claim ([\d.]+) ms, write ([\d.]+) ms, compute ([\d.]+) ms", l) for l in sys.stdin) if m]
n = sum(r[0] for r in rows)
mean = lambda k: sum(r[0] * r[k] for r in rows) / n
c, w, x = mean(1), mean(2), mean(3)
print(f"{c:.2f} {w:.2f} {x:.0f} {100 * (c + w) / x:.2f}%")')
    read -r claim write compute overhead <<<"$stats"
    printf '%-8s %-12s %-10s %-8s %-12s %-12s %-14s %s\n' "$n" "$rate" \
        "$(python3 -c "print(f'{$rate / $base:.2f}x')")" "$chunks" "$claim" "$write" "$compute" "$overhead"
done
