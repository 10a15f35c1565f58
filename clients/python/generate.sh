#!/usr/bin/env bash
# Regenerates the Python client (clients/python/glint_client, setup.py, pyproject.toml,
# README.md, .gitignore) from the committed openapi/openapi.json with the pinned
# openapi-python-client. `generate.sh check` regenerates into a temporary directory and
# fails on any difference from the committed files (CI).
#
# The generator is installed from PyPI into target/client-venv (Debian's python3-venv is
# installed with apt-get when missing, as loadtest/attack.sh does).
set -euo pipefail
cd "$(dirname "$0")/../.."
GENERATOR="openapi-python-client==0.29.1"
GENERATED=(glint_client setup.py pyproject.toml README.md .gitignore)
VENV=${GLINT_CLIENT_VENV:-target/client-venv}

SUDO=""
[ "$(id -u)" = 0 ] || SUDO="sudo"
apt_install() {
    $SUDO apt-get install -y -qq "$@" >/dev/null 2>&1 \
        || { $SUDO apt-get update -qq && $SUDO apt-get install -y -qq "$@" >/dev/null; }
}
command -v python3 >/dev/null || apt_install python3 python3-venv
if [ ! -x "$VENV/bin/pip" ]; then
    python3 -m venv "$VENV" 2>/dev/null || { rm -rf "$VENV"; apt_install python3-venv; python3 -m venv "$VENV"; }
fi
"$VENV/bin/pip" install -q "$GENERATOR"

TMP=$(mktemp -d)
trap 'rm -rf "$TMP"' EXIT
"$VENV/bin/openapi-python-client" generate --path openapi/openapi.json \
    --config clients/python/config.yml --meta setup --output-path "$TMP/gen" >"$TMP/log" 2>&1 \
    || { cat "$TMP/log" >&2; exit 1; }
if grep -q "Warning\|Unable to process" "$TMP/log"; then
    cat "$TMP/log" >&2
    echo "openapi-python-client warned about the spec: fix the spec" >&2
    exit 1
fi

if [ "${1:-}" = check ]; then
    status=0
    for f in "${GENERATED[@]}"; do
        diff -r -x __pycache__ "$TMP/gen/$f" "clients/python/$f" >&2 || status=1
    done
    [ "$status" = 0 ] || echo "clients/python differs from the spec: run clients/python/generate.sh" >&2
    exit "$status"
fi
for f in "${GENERATED[@]}"; do
    rm -rf "clients/python/$f"
    cp -r "$TMP/gen/$f" "clients/python/$f"
done
echo "regenerated clients/python from openapi/openapi.json ($GENERATOR)"
