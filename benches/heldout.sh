#!/usr/bin/env bash
# Speed beyond the suite: glint and its peer (Mitsuba 3, as in benches/suite.sh) on objects
# no code in glint was tuned to (benches/heldout.py), in one sitting.
#
#   benches/heldout.sh          # from the repo root
#
# Settings (environment): DECIMALS (9: the OBJ coordinates' decimals; 6 is what most
# exporters write), DIGITS (significant digits instead, as `%g` writes them), F32 (`full`,
# `shortest` or `nine`: single precision instead, printed in full, shortest or to 9 digits), THREADS (2,
# both engines), PEER_EPOCHS (40), RES (256), SPP (16), OUT (target/heldout), SKIP_PEER=1,
# SKIP_SETUP=1 (the peer's dependencies installed).
# Prints per object: triangles, faces, glint ms an epoch (the simulate call, preparation
# included), the peer's, and their ratio.
set -euo pipefail
cd "$(dirname "$0")/.."

DECIMALS=${DECIMALS:-9}
THREADS=${THREADS:-2}
PEER_EPOCHS=${PEER_EPOCHS:-40}
RES=${RES:-256}
SPP=${SPP:-16}
OUT=${OUT:-target/heldout}
TARGET=${CARGO_TARGET_DIR:-target}

cargo build --release --bin glint
python3 benches/heldout.py --out "$OUT" --decimals "$DECIMALS" ${DIGITS:+--digits "$DIGITS"} \
    ${F32:+--f32 "$F32"}
names="torus truss station cluster"

if [ -z "${SKIP_PEER:-}" ]; then
    [ -n "${SKIP_SETUP:-}" ] || bash benches/peer/setup.sh
    rm -f "$OUT/peer.csv"
    for n in $names; do
        python3 benches/peer/mitsuba_lightcurve.py "$OUT/$n.obj" "$OUT/$n.json" --epochs "$PEER_EPOCHS" \
            --res "$RES" --spp "$SPP" --threads "$THREADS" --materials timing --summary "$OUT/peer.csv" \
            --label "$n" > "$OUT/peer-$n.log"
    done
fi

printf '%-8s %9s %6s %12s %12s %7s\n' object triangles faces glint_ms peer_ms ratio
for n in $names; do
    RAYON_NUM_THREADS=$THREADS "$TARGET/release/glint" simulate "$OUT/$n.json" --out "$OUT/$n-glint.json" -q
    python3 - "$OUT" "$n" <<'PY'
import csv, json, os, sys
out, n = sys.argv[1], sys.argv[2]
s = json.load(open(os.path.join(out, n + "-glint.json")))["summary"]
ms = s["elapsed_ms"] / s["epochs"]
peer = None
path = os.path.join(out, "peer.csv")
if os.path.exists(path):
    rows = [r for r in csv.DictReader(open(path)) if r["class"] == n]
    peer = float(rows[-1]["ms_per_epoch"]) if rows else None
print("%-8s %9d %6d %12.3f %12s %7s" % (n, s["triangles"], s["faces"], ms,
      "%.2f" % peer if peer else "-", "%.1f" % (peer / ms) if peer else "-"))
PY
done
