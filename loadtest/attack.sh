#!/usr/bin/env bash
# The attack suite (issue 18): `glint serve` on loopback attacked as a hostile client would.
#
#   schemathesis  Schemathesis (pinned, installed into target/attack-venv) over every
#                 operation of the served OpenAPI document: no 5xx, answers as documented
#   hostile       ~200 hand-made hostile requests (malformed and extreme JSON, path
#                 traversal, bad queries, methods and headers, oversized URIs and heads):
#                 each a 4xx with the JSON error shape, quickly (loadtest/attack/hostile.py)
#   kill9         kill -9 while jobs run, restarts on the same data: no job lost,
#                 duplicated or changed (loadtest/attack/kill9.py)
#   overload      wrk at 64 and 128 connections on POST /v1/lightcurves with /healthz
#                 probed meanwhile: only 200s and 503s; in the full run also successful
#                 req/s at 128 >= 90 % of 64 and /healthz p99 < 20 ms (loadtest/attack/overload.py)
#   memory        (full run only) peak RSS for 4 concurrent downloads of a ~200 MB result
#                 and for 24 concurrent 1M-triangle requests (loadtest/attack/memory.py)
# A full disk is covered by tests/service_disk.rs (a real tmpfs where the machine allows).
#
#   loadtest/attack.sh          # the full run: release build, figures for the record (~10 min)
#   loadtest/attack.sh quick    # the short bounded pass .ci/run makes: debug build, ~1 min
#
# All traffic goes to 127.0.0.1; every loop is bounded in count and time. Exits non-zero
# when any part fails, after running them all. Other load on the machine skews the
# overload figures: check `uptime` first.
set -euo pipefail
cd "$(dirname "$0")/.."

MODE=${1:-full}
PORT=${PORT:-18190}
# where cargo puts the binaries (CARGO_TARGET_DIR when set, as for a second work tree)
TARGET=${CARGO_TARGET_DIR:-target}
SCHEMATHESIS_VERSION=4.32.5
WORK=$(mktemp -d -t glint-attack.XXXXXX)
trap 'rm -rf "$WORK"' EXIT

case "$MODE" in
quick)
    # the debug binary `cargo test` builds (a plain `cargo build` would compile it again,
    # with the features of the normal dependencies only)
    cargo test --locked --no-run --test service_restart >&2
    BIN=$TARGET/debug/glint
    EXAMPLES=3 SCHEMA_SECONDS=120
    JOBS=6 KILLS=2 EPOCHS=20
    OVERLOAD=(4 64,128)
    HOSTILE_MAX_S=10
    ;;
full)
    cargo build --release --locked --bin glint >&2
    BIN=$TARGET/release/glint
    EXAMPLES=100 SCHEMA_SECONDS=1200
    JOBS=40 KILLS=10 EPOCHS=400
    OVERLOAD=(20 64,128 --strict)
    HOSTILE_MAX_S=1
    ;;
*)
    echo "usage: $0 [quick|full]" >&2
    exit 2
    ;;
esac

# what a fresh Debian machine lacks is installed from its package registry
apt_install() {
    local SUDO
    SUDO=$([ "$(id -u)" = 0 ] || echo sudo)
    $SUDO apt-get install -y -qq "$@" >/dev/null 2>&1 \
        || { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq "$@" >/dev/null; }
}
command -v python3 >/dev/null || { echo "installing python3…" >&2; apt_install python3 python3-venv; }
VENV=target/attack-venv
if ! "$VENV/bin/schemathesis" --version 2>/dev/null | grep -q "$SCHEMATHESIS_VERSION"; then
    echo "installing schemathesis $SCHEMATHESIS_VERSION into $VENV…" >&2
    # Debian splits venv (and the pip it seeds) into python3-venv
    python3 -m venv "$VENV" 2>/dev/null || { rm -rf "$VENV"; apt_install python3-venv; python3 -m venv "$VENV"; }
    "$VENV/bin/pip" install --quiet --disable-pip-version-check "schemathesis==$SCHEMATHESIS_VERSION"
fi
if ! command -v wrk >/dev/null; then
    echo "installing wrk…" >&2
    apt_install wrk
fi

FAILED=()
step() { # name, command…: runs one part, keeps its output, notes a failure
    local name=$1
    shift
    echo "== $name" >&2
    if "$@" > "$WORK/$name.txt" 2> "$WORK/$name.err"; then
        cat "$WORK/$name.txt"
    else
        cat "$WORK/$name.txt"
        tail -n 30 "$WORK/$name.err" >&2
        FAILED+=("$name")
    fi
}

schemathesis_run() {
    local data="$WORK/schemathesis-data"
    # Small work limits: generated valid requests stay cheap, and jobs run at once
    "$BIN" serve --addr "127.0.0.1:$PORT" --data-dir "$data" --max-sync-epochs 50 \
        --max-job-epochs 200 --max-triangles 20000 --max-sync-pixel-samples 1000000 \
        --request-timeout-secs 10 2> "$WORK/schemathesis-server.log" &
    local server=$!
    for _ in $(seq 100); do
        python3 -c "import urllib.request as u; u.urlopen('http://127.0.0.1:$PORT/healthz', timeout=1)" 2>/dev/null && break
        sleep 0.1
    done
    local rc=0
    # run from the scratch directory: Schemathesis leaves a `.schemathesis/` where it runs
    (cd "$WORK" && timeout "$SCHEMA_SECONDS" "$OLDPWD/$VENV/bin/schemathesis" run "http://127.0.0.1:$PORT/openapi.json" \
        --checks not_a_server_error,status_code_conformance,content_type_conformance,response_schema_conformance \
        --phases examples,coverage,fuzzing --max-examples "$EXAMPLES" --seed 18 --workers 1 \
        --request-timeout 30 --suppress-health-check all --generation-database none --no-color \
        --report ndjson --report-ndjson-path "$WORK/schemathesis.ndjson") >&2 || rc=$?
    kill "$server" 2>/dev/null || true
    wait "$server" 2>/dev/null || true
    python3 - "$WORK/schemathesis.ndjson" "$WORK/schemathesis-server.log" <<'PY'
import json, re, sys
statuses = {}
for line in open(sys.argv[1]):
    for m in re.finditer(r'"status_code":\s*(\d+)', line):
        statuses[int(m.group(1))] = statuses.get(int(m.group(1)), 0) + 1
print(f"schemathesis_requests {sum(statuses.values())}")
print(f"schemathesis_statuses {json.dumps(dict(sorted(statuses.items())))}")
print(f"schemathesis_5xx {sum(n for s, n in statuses.items() if s >= 500)}")
PY
    return $rc
}

step schemathesis schemathesis_run
step hostile python3 loadtest/attack/hostile.py "$BIN" "$PORT" "$WORK" "$HOSTILE_MAX_S"
step kill9 python3 loadtest/attack/kill9.py "$BIN" "$PORT" "$WORK" "$JOBS" "$KILLS" "$EPOCHS"
step overload python3 loadtest/attack/overload.py "$BIN" "$PORT" "$WORK" "${OVERLOAD[@]}"
if [ "$MODE" = full ]; then
    step memory python3 loadtest/attack/memory.py "$BIN" "$PORT" "$WORK" all 200
fi

echo "load average: $(cut -d' ' -f1-3 /proc/loadavg)"
PARTS=$(ls "$WORK"/*.txt | wc -l)
if [ ${#FAILED[@]} -gt 0 ]; then
    echo "attack suite ($MODE): failed: ${FAILED[*]}" >&2
fi
echo "attack: $((PARTS - ${#FAILED[@]})) passed, ${#FAILED[@]} failed"
[ ${#FAILED[@]} -eq 0 ]
