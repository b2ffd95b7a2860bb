#!/usr/bin/env bash
# The main job: set kame up in .venv and run a ROS graph on it — roscore, the rospy tutorial
# talker and listener — until Ctrl-C. From another terminal: `source .venv/bin/activate`, then
# `rostopic echo /chatter`, `rosnode list`, `rosmsg show std_msgs/String`, ...
set -euo pipefail
cd "$(dirname "$0")/.."
python=${KAME_PYTHON:-python3}
if [ ! -x .venv/bin/python ]; then
  "$python" -m venv .venv
fi
.venv/bin/python -m pip install -q --disable-pip-version-check -e .
export PATH="$PWD/.venv/bin:$PATH"
export ROS_MASTER_URI=${ROS_MASTER_URI:-http://localhost:11311/}
port=${ROS_MASTER_URI##*:}; port=${port%%/*}
tutorials=src/kame/share/rospy_tutorials/scripts

pids=()
cleanup() {
  for pid in "${pids[@]}"; do kill -INT "$pid" 2>/dev/null || true; done
  for pid in "${pids[@]}"; do wait "$pid" 2>/dev/null || true; done
}
trap cleanup EXIT INT TERM

roscore -p "$port" &
pids+=($!)
for _ in $(seq 100); do
  python -c "import xmlrpc.client,sys; xmlrpc.client.ServerProxy('$ROS_MASTER_URI').getPid('/demo')" 2>/dev/null && break
  sleep 0.1
done
python "$tutorials/listener" &
pids+=($!)
python "$tutorials/talker" &
pids+=($!)
echo "kame demo: roscore, talker and listener are running (Ctrl-C stops them)." >&2
echo "  In another terminal: source $PWD/.venv/bin/activate && rostopic echo /chatter" >&2
wait "${pids[0]}"
