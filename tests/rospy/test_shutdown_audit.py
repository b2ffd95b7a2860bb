"""rospy's waits at shutdown, audited against Debian's rospy: the same program under both
interpreters, ended by rospy.signal_shutdown or by Ctrl-C (SIGINT), on the wall clock and on
simulated time, prints the same lines and exits cleanly.

On the wall clock rospy's sleep never raises (a Ctrl-C ends `while not rospy.is_shutdown():
rate.sleep()` quietly); on simulated time it raises ROSInterruptException; wait_for_message and
wait_for_service raise it on either clock; spin returns; a Timer's thread ends; a callback in
flight runs to its end; a loop busy in the program's own code ends at its next is_shutdown();
a wall-clock sleep begun after the shutdown sleeps its whole time."""

from __future__ import annotations

import sys
import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..libs import debian
from ..support import Proc, free_port, kame_command, ros_env, wait_for_master

DRIVER = Path(__file__).with_name("shutdown_driver.py")
HAS_DEBIAN_ROSPY = debian.has("rospy", "std_msgs.msg")


@pytest.fixture(scope="module")
def envs(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, dict[str, str]]]:
    """An environment per clock: a master each, the simulated one's with /use_sim_time set."""
    home = Path(tmp_path_factory.mktemp("shutdown_audit"))
    masters, environments = [], {}
    try:
        for clock in ("wall", "sim"):
            port = free_port()
            uri = f"http://127.0.0.1:{port}/"
            environments[clock] = ros_env(home / clock, uri)
            masters.append(Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environments[clock]))
            wait_for_master(uri, proc=masters[-1])
        xmlrpc.client.ServerProxy(environments["sim"]["ROS_MASTER_URI"]).setParam("/test", "/use_sim_time", True)
        yield environments
    finally:
        for master in masters:
            master.stop()


def run_all(runs: list[tuple[str, dict[str, str], list[str]]]) -> list[list[str]]:
    """Each (python, env, arguments) at once (they mostly wait), and each one's lines."""
    procs = [Proc([python, str(DRIVER), *args], env) for python, env, args in runs]
    results = []
    for proc in procs:
        try:
            proc.popen.wait(30)
        finally:
            out, err = proc.stop()
        assert proc.popen.returncode == 0, f"{proc.args}: exit {proc.popen.returncode}\n{out}\n{err}"
        assert "Traceback" not in err, f"{proc.args}:\n{err}"
        results.append(out.splitlines())
    return results


WALL = {
    "sleep": ["sleep: returned"],
    "rate": ["rate loop: returned"],
    "wait_for_message": ["wait_for_message: raised ROSInterruptException: rospy shutdown"],
    "wait_for_service": ["wait_for_service: raised ROSInterruptException: rospy shutdown"],
    "timer": ["spin: returned", "timer thread ended: True"],
    "spin": ["spin: returned"],
    "callback": ["spin: returned", "callback in flight finished: True and saw shutdown: [True]"],
    "busy": ["busy loop: returned"],  # rospy's Ctrl-C raises nothing: the loop sees is_shutdown()
    "after": ["sleep after shutdown: returned, slept whole: True"],  # a shutdown hook's last sleep
}
SIM = dict(WALL, sleep=["sleep: raised ROSInterruptException: ROS shutdown request"],
           rate=["rate loop: raised ROSInterruptException: ROS shutdown request"],
           after=["sleep after shutdown: raised ROSInterruptException: ROS shutdown request, slept whole: False"])


@pytest.mark.parametrize("wait", sorted(WALL))
def test_a_wait_at_shutdown_does_what_rospys_does(envs: dict[str, dict[str, str]], wait: str) -> None:
    # the same lines from kame and Debian
    pythons = [(sys.executable, lambda env: env)]
    if HAS_DEBIAN_ROSPY:
        pythons.append((str(debian.SYSTEM_PYTHON), debian_env))
    # Ctrl-C reaches a wait through the same handler on either clock: on simulated time
    # signal_shutdown alone keeps the test quick
    cases = [("wall", "signal_shutdown"), ("wall", "sigint"), ("sim", "signal_shutdown")]
    runs = [(python, env_for(envs[clock]), [wait, clock, how]) for python, env_for in pythons for clock, how in cases]
    printed = run_all(runs)
    for (python, _, args), lines in zip(runs, printed, strict=True):
        expected = [*(WALL if args[1] == "wall" else SIM)[wait], "is_shutdown: True"]
        assert lines == expected, f"{python} {args}"


def debian_env(env: dict[str, str]) -> dict[str, str]:
    return {key: value for key, value in env.items() if key not in ("PYTHONPATH", "VIRTUAL_ENV")}
