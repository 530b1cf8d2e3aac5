#!/usr/bin/env bash
# Builds the Python wheel in a fresh virtual environment, installs it and runs its tests.
# Usage: bash python/ci.sh (from anywhere). The test against the CLI needs
# target/release/honeycomb (cargo build --release -p honeycomb-cli) or $HONEYCOMB_BIN, and is
# skipped without it.
set -euo pipefail
here="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
venv="$(mktemp -d)/venv"
trap 'rm -rf "$(dirname "$venv")"' EXIT
python3 -m venv "$venv"
"$venv/bin/pip" install --quiet maturin pytest numpy
start=$SECONDS
"$venv/bin/pip" install --quiet "$here"
echo "python: wheel built and installed in $((SECONDS - start)) s"
cd "$here"
"$venv/bin/python" -m pytest -q tests
