#!/bin/bash
# Instructions per epoch and for preparation of `examples/scale`, counted by callgrind:
# a measure the machine's noise does not move (timings on the shared 2-core machines vary
# by ±40 %). Usage: benches/instructions.sh FLAT_LEVELS DISH_RINGS DISH_SECTORS [EPOCHS
# [EXAMPLE OPTIONS...]] (e.g. `3 48 128` for the fine-dish box-wing, `3 48 128 342
# --sun-drift 0.01` with a Sun that never repeats, `3 48 128 31 --first 310` for the
# stretch at phase 155°–170°). Needs valgrind (Debian package `valgrind`).
set -euo pipefail
cd "$(dirname "$0")/.."
n=${4:-342}
extra=("${@:5}")
cargo build --release --example scale >/dev/null 2>&1
bin=target/release/examples/scale
count() {
    RAYON_NUM_THREADS=1 valgrind --tool=callgrind --callgrind-out-file=/dev/null \
        "$bin" "${extra[@]}" "$1" "$2" "$3" "$4" 2>&1 | awk '/Collected/ {print $4}'
}
one=$(count "$1" "$2" "$3" 1)
many=$(count "$1" "$2" "$3" "$n")
echo "scale ${extra[*]} $1 $2 $3: $(( (many - one) / (n - 1) )) instructions/epoch over $n epochs, $one to prepare and run 1"
