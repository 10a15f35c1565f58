#!/usr/bin/env bash
# Accuracy on every built-in class against references the engine did not produce: the peer
# (Mitsuba 3, f32) at 1024 px and 64 samples a pixel, raw and extrapolated to no shadow-ray
# offset (two runs, the mesh at scale 1 and 10: see mitsuba_lightcurve.py), glint's own
# `image` method at 2048 px and 2 x 2 rays a pixel, glint's per-face exact clipping
# (`adaptive` at tolerance 1e-7), and glint at tolerance 1e-6. Every
# material Lambertian (albedo 0.5), sunlight alone, every 24th epoch of each class's
# tumbling request (benches/peer/lambertize.py).
#
#   benches/peer/accuracy.sh        # from the repo root; a few minutes on an idle machine
#
# Settings (environment): CLASSES, DETAILS (medium), ADAPTIVE_DETAILS (coarse medium: the
# per-face route at tolerance 1e-7 takes minutes a class at 200k triangles), STRIDE (24), RES (1024), SPP (64),
# IMAGE_SIZE (2048), OUT (target/accuracy), SKIP_SETUP=1 (the peer's dependencies already
# installed). Writes OUT/accuracy.csv (one row per class, detail and reference) and prints it.
set -euo pipefail
cd "$(dirname "$0")/../.."

CLASSES=${CLASSES:-"box-wing rocket-body fragment dish-sat cubesat"}
DETAILS=${DETAILS:-"medium"}
ADAPTIVE_DETAILS=${ADAPTIVE_DETAILS:-"coarse medium"}
STRIDE=${STRIDE:-24}
RES=${RES:-1024}
SPP=${SPP:-64}
IMAGE_SIZE=${IMAGE_SIZE:-2048}
OUT=${OUT:-target/accuracy}
TARGET=${CARGO_TARGET_DIR:-target}
mkdir -p "$OUT"

request() { [ "$1" = box-wing ] && echo box-wing-tumbling || echo "$1"; }
# a copy of request $1 with top-level fields set from JSON $3, written to $2
with() { python3 -c 'import json,sys; r=json.load(open(sys.argv[1])); r.update(json.loads(sys.argv[3])); json.dump(r,open(sys.argv[2],"w"))' "$1" "$2" "$3"; }

[ -n "${SKIP_SETUP:-}" ] || bash benches/peer/setup.sh
cargo build --release --bin glint
glint="$TARGET/release/glint"
summary="$OUT/accuracy.csv"
rm -f "$summary"

for d in $DETAILS; do
    "$glint" export-objects --detail "$d" --dir "$OUT/objects/$d" >/dev/null
    for c in $CLASSES; do
        echo "accuracy: $c $d" >&2
        w="$OUT/$c-$d"
        mesh="$OUT/objects/$d/$c.obj"
        python3 benches/peer/lambertize.py "scenes/$(request "$c").json" "$w.json" \
            --obj "$mesh" --stride "$STRIDE"
        with "$w.json" "$w-image.json" "{\"method\": \"image\", \"image_size\": $IMAGE_SIZE, \"image_samples\": 2}"
        with "$w.json" "$w-exact.json" '{"tolerance": 1e-6}'
        runs=("" -image -exact)
        adaptive=
        if [[ " $ADAPTIVE_DETAILS " == *" $d "* ]]; then
            adaptive=1
            with "$w.json" "$w-adaptive.json" '{"method": "adaptive", "tolerance": 1e-7}'
            runs+=(-adaptive)
        fi
        for r in "${runs[@]}"; do
            "$glint" simulate "$w$r.json" --out "$w-glint$r.json" >/dev/null
        done
        # two scales whose leaks are narrow bands against the triangles (at 0.1 the
        # offset is an eighth of the fine fragment's sides and the leak no longer grows
        # in proportion): the extrapolation is linear
        for s in 1 10; do
            python3 benches/peer/mitsuba_lightcurve.py "$mesh" "$w.json" --materials lambert \
                --res "$RES" --spp "$SPP" --scale "$s" --out "$w-peer-$s.csv" >/dev/null
        done
        python3 benches/peer/compare.py "$w-glint.json" "$w-peer-1.csv" --peer2 "$w-peer-10.csv" \
            --request "$w.json" --summary "$summary" --label "$c,$d,peer ${RES} px ${SPP} spp" >/dev/null
        python3 benches/peer/compare.py "$w-glint.json" "$w-glint-image.json" --request "$w.json" \
            --summary "$summary" --label "$c,$d,glint image ${IMAGE_SIZE} px" >/dev/null
        [ -z "$adaptive" ] || python3 benches/peer/compare.py "$w-glint.json" \
            "$w-glint-adaptive.json" --request "$w.json" \
            --summary "$summary" --label "$c,$d,glint adaptive 1e-7" >/dev/null
        python3 benches/peer/compare.py "$w-glint.json" "$w-glint-exact.json" --request "$w.json" \
            --summary "$summary" --label "$c,$d,glint tolerance 1e-6" >/dev/null
    done
done
# the label holds class, detail and reference: name the columns
sed -i '1s/^label,/class,detail,reference,/' "$summary"
column -s, -t < "$summary"
