"""The README's main job, scripts/demo.sh, runs `roslaunch scripts/turtlesim_demo.launch`: here
that launch file headless, as demo.sh runs it without a display: its own master, turtlesim and
draw_square, the turtle driving its square at once, and Ctrl-C ending it all."""

from __future__ import annotations

from pathlib import Path

from tests.support import REPO, Proc, free_port, ros_env
from tests.turtlesim.sim import BIN, Sim, wait_until


def test_the_demo_launch_draws_squares_and_ends_on_ctrl_c(tmp_path: Path) -> None:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path, uri)
    demo = Proc([str(BIN / "roslaunch"), "-p", str(port), str(REPO / "scripts" / "turtlesim_demo.launch"),
                 "headless:=true"], env, cwd=tmp_path)
    sim = Sim(tmp_path, uri, env)
    try:
        demo.wait_line("Spawning turtle [turtle1]", timeout=60)
        start = sim.pose()
        wait_until(lambda: sim.pose() != start, timeout=20, what="draw_square to drive the turtle")
        nodes = sim.run("rosnode", "list").stdout.split()
        assert {"/turtlesim", "/draw_square", "/rosout"} <= set(nodes), nodes
    finally:
        out, err = demo.stop(timeout=15)
    assert demo.popen.returncode == 0, out + err
    assert "Traceback" not in out + err, out + err
