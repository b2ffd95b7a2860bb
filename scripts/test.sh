#!/usr/bin/env bash
# Sets up everything the tests need and runs all of them: lint, types, unit and interop tests,
# and turtlesim's window offscreen and on a real X server (Xvfb).
# Usage: scripts/test.sh [pytest args...]
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-ros-peers.sh
bash scripts/install-gui-libs.sh --xvfb  # turtlesim's window, tested under Xvfb
python=${KAME_PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$python" -m venv .venv
fi
.venv/bin/python -m pip install -q --disable-pip-version-check -e '.[test]'
.venv/bin/python -m ruff check src tests bench
.venv/bin/python -m mypy
.venv/bin/python -m pytest -q "$@"
