"""`gzclient` (also `rosrun gazebo_ros gzclient`, and the window of `gazebo` and of
empty_world.launch with gui:=true): Gazebo's window, a process of its own, the ROS node
/gazebo_gui (empty_world.launch's name; /gazebo_gui_<pid>_<ms> from rosrun). It draws what
gzserver sends and works the world through /gazebo's services; closing it leaves gzserver
running, as in Gazebo. Without a display, or without the gui extra
(PySide6, PyOpenGL), it says so in one line and ends: the server runs on."""

from __future__ import annotations

import importlib.util
import os
import subprocess
import sys
from collections.abc import MutableMapping, Sequence

# as empty_world.launch names gzclient's node; anonymous unless a launch file names it, so that two
# windows on one server (`gazebo`, then `gzclient`) do not push each other off the graph
NODE_NAME = "gazebo_gui"
WINDOW_SIZE = (1024, 720)


def no_window_reason(env: dict[str, str]) -> str | None:
    """Why gzclient cannot open its window here, in one line; None when it can."""
    from kame.net.window import window_problem

    problem = window_problem("gzclient", None, env)
    if problem is not None:
        return f"{problem.reason}; gzserver keeps simulating"
    if importlib.util.find_spec("OpenGL") is None:
        return "PyOpenGL is not installed (pip install 'kame[gui]'): gzclient runs without a window; " \
               "gzserver keeps simulating"
    return None


def forget_mujocos_platform(env: MutableMapping[str, str]) -> None:
    """MuJoCo, loaded with MUJOCO_GL=egl, sets PYOPENGL_PLATFORM=egl for its headless renderer, and
    a gzclient started by gzserver (`gazebo`) or from its environment inherits it: PyOpenGL would then
    look for an EGL context where Qt made the window's (GLX on X11) and draw nothing. The window's
    PyOpenGL finds Qt's platform by itself."""
    if env.get("PYOPENGL_PLATFORM") == "egl" and env.get("MUJOCO_GL") == "egl":
        del env["PYOPENGL_PLATFORM"]


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    forget_mujocos_platform(os.environ)
    reason = no_window_reason(dict(os.environ))
    if reason is not None:
        print(f"gzclient: {reason}", file=sys.stderr)
        return 0
    from PySide6.QtWidgets import QApplication

    from kame.client import core, process
    from kame.gzclient.source import ClientSource
    from kame.gzclient.window import GzClientWindow
    from kame.qt_quit import quit_on_signals

    process.init_node(NODE_NAME, argv=argv, anonymous=True)
    app = QApplication.instance() or QApplication(["gzclient"])
    quit_on_signals(app)
    source = ClientSource()
    try:
        window = GzClientWindow(source)
        window.resize(*WINDOW_SIZE)
        window.show()
        app.exec()
    finally:
        source.close()
        core.signal_shutdown("gzclient closed")
    return 0


def client_arguments(argv: Sequence[str]) -> list[str]:
    """The arguments `gazebo` gives its gzclient: the ROS remappings but a node name (two nodes
    named alike would push the server off the graph), none of the server's own options."""
    return [arg for arg in argv[1:] if ":=" in arg and not arg.startswith("__name:=")]


def start_client(argv: Sequence[str]) -> subprocess.Popen[bytes]:
    """gzclient beside the server, as `gazebo` runs both; it ends with the server (die_with_parent)."""
    from kame.net.process import die_with_parent

    return subprocess.Popen([sys.executable, "-m", "kame.gzclient.main", *client_arguments(argv)],
                            stdin=subprocess.DEVNULL, preexec_fn=die_with_parent())


if __name__ == "__main__":
    sys.exit(main())
