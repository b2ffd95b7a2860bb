# Sourced by the bench entry points. kame is measured as `pip install` leaves it, with its
# bytecode compiled (Debian's rospy ships compiled too). A checkout run under
# PYTHONDONTWRITEBYTECODE=1 would otherwise recompile every kame module at each process start.
kame_python="$(dirname "$0")/../.venv/bin/python"
if [ -x "$kame_python" ]; then
    "$kame_python" -m compileall -q "$(dirname "$0")/../src" >/dev/null
fi
