#!/usr/bin/env bash
# The object suite, measured in one sitting: glint and its peer (Mitsuba 3) on every
# built-in class at every level of detail, then the chart docs/suite.svg. glint runs twice:
# on the requests as they are (suite.csv: sunlight and the paper's earthshine) and on
# sunlight alone (suite-sun.csv), which is what the peer renders and what the chart shows.
#
#   benches/suite.sh            # from the repo root; takes a while on an idle machine
#
# Settings (environment): CLASSES, DETAILS (space-separated), PEER_EPOCHS (40: the peer's
# first N epochs of each request), RES (256), SPP (16), THREADS (both engines; default all
# cores), REPEAT (5: glint runs per row, best and median), OUT (target/suite), SKIP_PEER=1,
# SKIP_SETUP=1 (the peer's dependencies already installed).
set -euo pipefail
cd "$(dirname "$0")/.."

CLASSES=${CLASSES:-"box-wing rocket-body fragment dish-sat cubesat"}
DETAILS=${DETAILS:-"coarse medium fine"}
PEER_EPOCHS=${PEER_EPOCHS:-40}
RES=${RES:-256}
SPP=${SPP:-16}
THREADS=${THREADS:-}
REPEAT=${REPEAT:-5}
OUT=${OUT:-target/suite}
TARGET=${CARGO_TARGET_DIR:-target}
mkdir -p "$OUT"

request() { [ "$1" = box-wing ] && echo box-wing-tumbling || echo "$1"; }

cargo build --release --bin glint --example suite --example suite_chart
glint="$TARGET/release/glint"

if [ -z "${SKIP_PEER:-}" ]; then
    [ -n "${SKIP_SETUP:-}" ] || bash benches/peer/setup.sh
    rm -f "$OUT/peer.csv"
    for d in $DETAILS; do
        "$glint" export-objects --detail "$d" --dir "$OUT/objects/$d"
    done
    for c in $CLASSES; do
        for d in $DETAILS; do
            echo "peer: $c $d" >&2
            python3 benches/peer/mitsuba_lightcurve.py "$OUT/objects/$d/$c.obj" "scenes/$(request "$c").json" \
                --epochs "$PEER_EPOCHS" --res "$RES" --spp "$SPP" ${THREADS:+--threads "$THREADS"} \
                --materials timing --summary "$OUT/peer.csv" --label "$c" | tee "$OUT/peer-$c-$d.log"
        done
    done
fi

args=()
for c in $CLASSES; do args+=(--class "$c"); done
for d in $DETAILS; do args+=(--detail "$d"); done
# glint on the requests as they are (earthshine included), then on sunlight alone: what
# the peer renders, so that the ratio compares the same work
"$TARGET/release/examples/suite" "${args[@]}" --repeat "$REPEAT" ${THREADS:+--threads "$THREADS"} \
    --out "$OUT/suite.csv" | tee "$OUT/suite.txt"
"$TARGET/release/examples/suite" "${args[@]}" --repeat "$REPEAT" ${THREADS:+--threads "$THREADS"} \
    --earthshine off --out "$OUT/suite-sun.csv" | tee "$OUT/suite-sun.txt"

peer_csv=()
[ -s "$OUT/peer.csv" ] && peer_csv=("$OUT/peer.csv")
"$TARGET/release/examples/suite_chart" "$OUT/suite-sun.csv" "${peer_csv[@]}" --out docs/suite.svg
