#!/usr/bin/env bash
# The main job: set kame up in .venv (with the GUI extra when it installs) and roslaunch
# scripts/turtlesim_demo.launch: a master, turtlesim and draw_square, so a turtle draws squares at once.
# Drive it from another terminal: `source .venv/bin/activate && rosrun turtlesim turtle_teleop_key`.
# With no display the same simulation runs headless, and turtlesim says why there is no window.
# Ctrl-C stops everything.
set -euo pipefail
cd "$(dirname "$0")/.."
python=${KAME_PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$python" -m venv .venv
fi
# Install once, and again only when pyproject.toml changes (its checksum is kept in .venv).
stamp=.venv/.kame-demo-installed
want=$(cksum < pyproject.toml)
if [ "$(cat "$stamp" 2>/dev/null)" != "$want" ]; then
  echo "kame demo: installing kame into .venv (the first time takes a minute or so)..." >&2
  pip=(.venv/bin/python -m pip install -q --disable-pip-version-check)
  log=$(mktemp)
  if "${pip[@]}" -e '.[gui]' 2>"$log"; then
    rm -f "$log"
  else
    echo "kame demo: the GUI extra (PySide6) did not install; turtlesim will run headless. pip said:" >&2
    tail -n 5 "$log" | sed 's/^/  /' >&2
    rm -f "$log"
    "${pip[@]}" -e .
  fi
  echo "$want" > "$stamp"
fi
export PATH="$PWD/.venv/bin:$PATH"
export ROS_MASTER_URI=${ROS_MASTER_URI:-http://localhost:11311/}
port=${ROS_MASTER_URI##*:}; port=${port%%/*}

# turtlesim itself decides whether it can have a window, and says why not.
if [ -z "${DISPLAY:-}${WAYLAND_DISPLAY:-}${QT_QPA_PLATFORM:-}" ]; then
  echo "kame demo: no display (DISPLAY is not set), so turtlesim runs headless (try: rostopic echo /turtle1/pose)." >&2
else
  # Qt's X11 plugin needs system libraries a fresh Debian lacks; turtlesim checks before it
  # opens its window, and names the missing one (then runs headless) when this could not help.
  bash scripts/install-gui-libs.sh || true
fi
cat >&2 <<MSG
kame demo: turtlesim with a turtle drawing squares (Ctrl-C stops it).
  Drive it yourself from another terminal:
    source $PWD/.venv/bin/activate
    rosrun turtlesim turtle_teleop_key
MSG
exec roslaunch -p "$port" scripts/turtlesim_demo.launch
