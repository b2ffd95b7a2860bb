#!/usr/bin/env bash
# Sets up everything the tests need and runs all of them: lint, types, unit and interop tests,
# and turtlesim's window offscreen and on a real X server (Xvfb).
# Usage: scripts/test.sh [pytest args...]   (e.g. -n 0 to run in one process)
# KAME_DEPS (newest, oldest) is set by scripts/dependency-sweep.sh.
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/install-ros-peers.sh
bash scripts/install-gui-libs.sh --xvfb  # turtlesim's window, tested under Xvfb
bash scripts/install-web-peers.sh  # headless Chromium and the npm web clients the bridges are tested with
python=${KAME_PYTHON:-python3}
venv=.venv
if [ ! -x "$venv/bin/python" ]; then
  "$python" -m venv "$venv"
fi
pip=("$venv/bin/python" -m pip install -q --disable-pip-version-check)
case ${KAME_DEPS:-} in
  "") "${pip[@]}" -e '.[test]' ;;
  newest) "${pip[@]}" --upgrade --upgrade-strategy eager -e '.[test,gui,robot,sim,image]' ;;
  oldest)
    # pip cannot pick the lowest versions; uv can. Direct dependencies at their floors, as wheels
    # for this interpreter where the package has compiled code (numpy 1.22 has none for 3.11, so
    # the floor there is the first that installs: 1.23.2); the pure-Python ones from source
    "${pip[@]}" uv
    "$venv/bin/uv" pip install -q --python "$venv/bin/python" --resolution lowest-direct --only-binary :all: \
      --no-binary urdf-parser-py --no-binary pycollada --no-binary xacro --no-binary empy \
      -e '.[test,gui,robot,sim,image]'
    ;;
  *) echo "KAME_DEPS must be newest or oldest, not '$KAME_DEPS'" >&2; exit 2 ;;
esac
"$venv/bin/python" -m pip list --format=freeze 2>/dev/null | sed 's/^/  /' > "$venv/installed.txt"
"$venv/bin/python" -m ruff check src tests bench
if [ "${KAME_DEPS:-}" = oldest ]; then
  # mypy reads numpy's own annotations: before numpy 2.0 ndarray's type parameters have no
  # defaults, so every bare numpy.ndarray is an error there. The types are checked in the other runs
  echo "test.sh: mypy skipped with the oldest dependencies (numpy $("$venv/bin/python" -c 'import numpy; print(numpy.__version__)'))"
else
  "$venv/bin/python" -m mypy
fi
# one worker per core (-n auto); a test file's tests stay together on one worker (--dist loadfile),
# so a module's shared roscore or workspace is made once. `scripts/test.sh -n 0 ...` runs serially
"$venv/bin/python" -m pytest -q -n auto --dist loadfile "$@"
