#!/usr/bin/env bash
# CI for the Python client: regenerate it from openapi/openapi.json and fail on any
# difference (generate.sh check), then install it (`pip install ./clients/python`) into a
# fresh venv and run its tests against a live `glint serve` they start (GLINT_BIN, default
# target/debug/glint, which `cargo test` builds).
set -euo pipefail
cd "$(dirname "$0")/../.."
bash clients/python/generate.sh check

SUDO=""
[ "$(id -u)" = 0 ] || SUDO="sudo"
apt_install() {
    $SUDO apt-get install -y -qq "$@" >/dev/null 2>&1 \
        || { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq "$@" >/dev/null; }
}
VENV=target/client-test-venv
rm -rf "$VENV"
python3 -m venv "$VENV" 2>/dev/null || { rm -rf "$VENV"; apt_install python3-venv; python3 -m venv "$VENV"; }
"$VENV/bin/pip" install -q ./clients/python "pytest==9.2.0"
# pip builds in a copy, but leave nothing of it in the tree either way
rm -rf clients/python/build clients/python/*.egg-info
GLINT_BIN=${GLINT_BIN:-target/debug/glint} "$VENV/bin/python" -m pytest -q -p no:cacheprovider clients/python/tests
