"""The dynamic_reconfigure tutorial's server node (rospy, no build step) against Debian's dynparam and client."""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.msg.catalog import SHARE_DIR

from ..libs import debian
from ..support import Proc, free_port, kame_command, ros_env, wait_for_master

HERE = Path(__file__).parent
TUTORIALS = HERE / "dynamic_tutorials"
SERVER = TUTORIALS / "nodes" / "server.py"
DEBIAN_DYNPARAM = Path("/usr/lib/dynamic_reconfigure/dynparam")


@pytest.fixture
def master_env(tmp_path: Path) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(tmp_path / "home", uri)
    environment["ROS_PACKAGE_PATH"] = str(TUTORIALS)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


@pytest.fixture
def tutorial_server(master_env: dict[str, str]) -> Iterator[Proc]:
    server = Proc([sys.executable, str(SERVER)], master_env)
    try:
        server.wait_line("Reconfigure Request: 50, 0.5,          Hello World, True, 1")
        yield server
    finally:
        server.stop()


def debian_dynparam(env: dict[str, str], *args: str) -> str:
    environment = {k: v for k, v in debian.debian_env().items() if not k.startswith("ROS_")}
    environment.update({k: v for k, v in env.items() if k.startswith("ROS_")})
    # dynparam's roslib.load_manifest looks for the package; Debian ships its modules but no package.xml
    environment["ROS_PACKAGE_PATH"] = os.pathsep.join([env["ROS_PACKAGE_PATH"], str(SHARE_DIR / "dynamic_reconfigure")])
    result = subprocess.run([str(debian.SYSTEM_PYTHON), str(DEBIAN_DYNPARAM), *args], env=environment,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


@pytest.mark.skipif(not (DEBIAN_DYNPARAM.exists() and debian.has("rospy", "dynamic_reconfigure.client")),
                    reason="Debian's python3-dynamic-reconfigure is not installed")
def test_debians_dynparam_sets_and_gets_on_kames_server(master_env: dict[str, str], tutorial_server: Proc) -> None:
    assert debian_dynparam(master_env, "list").split() == ["/dynamic_tutorials"]
    debian_dynparam(master_env, "set", "/dynamic_tutorials", "int_param", "70")
    tutorial_server.wait_line("Reconfigure Request: 70, 0.5,          Hello World, True, 1")
    debian_dynparam(master_env, "set", "/dynamic_tutorials", "{double_param: 7.5, str_param: kame, size: 2}")
    # 7.5 is above double_param's max of 1: the server clamps it
    tutorial_server.wait_line("Reconfigure Request: 70, 1.0,          kame, True, 2")
    got = debian_dynparam(master_env, "get", "/dynamic_tutorials")
    assert "'int_param': 70" in got and "'double_param': 1.0" in got and "'str_param': 'kame'" in got
    assert "'groups': {" in got
