#!/usr/bin/env bash
# Installs what the peer benchmark (benches/peer/mitsuba_lightcurve.py) needs:
# libLLVM 19 (Dr.Jit 1.5 aborts in Debian 12's default libLLVM 15) and the pinned Python
# packages. Idempotent: does nothing that is already done. Run as root (Debian/Ubuntu).
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"

if [ ! -e /usr/lib/x86_64-linux-gnu/libLLVM-19.so ] && ! ls /usr/lib/*/libLLVM.so.19* >/dev/null 2>&1; then
    apt-get update
    DEBIAN_FRONTEND=noninteractive apt-get install -y libllvm19
fi

py="${PYTHON:-python3}"
if ! "$py" - "$here/requirements.txt" <<'PY'
import sys
from importlib.metadata import version, PackageNotFoundError
for line in open(sys.argv[1]):
    line = line.split("#")[0].strip()
    if not line:
        continue
    name, want = line.split("==")
    try:
        if version(name) != want:
            sys.exit(1)
    except PackageNotFoundError:
        sys.exit(1)
PY
then
    "$py" -m pip install -r "$here/requirements.txt"
fi
"$py" -c "import mitsuba, drjit; print('peer ready: mitsuba', mitsuba.__version__, 'drjit', drjit.__version__)"
