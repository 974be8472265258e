#!/usr/bin/env bash
# The Python package's CI: build the abi3 wheel with maturin, install it into a fresh
# venv with the test dependencies, run pytest on python/tests. Exits non-zero on any
# failure (and when pytest collected no test).
set -euo pipefail
cd "$(dirname "$0")/.."
WORK=$(mktemp -d)
trap 'rm -rf "$WORK"' EXIT
python3 -m venv "$WORK/venv"
PY="$WORK/venv/bin/python"
"$PY" -m pip install --quiet --disable-pip-version-check \
  "maturin>=1.9,<2" numpy scipy pytest shapely ezdxf matplotlib
start=$(date +%s)
"$WORK/venv/bin/maturin" build --release --quiet -o "$WORK/wheels" 2>&1 | grep -v "^\s*$" | tail -n 3
echo "wheel built in $(( $(date +%s) - start )) s: $(basename "$WORK"/wheels/*.whl)"
"$PY" -m pip install --quiet --disable-pip-version-check --no-deps "$WORK"/wheels/*.whl
# run from outside the repository, so the installed wheel is what is imported
cd "$WORK"
MPLBACKEND=Agg "$PY" -m pytest -q -p no:cacheprovider "$OLDPWD/python/tests"
