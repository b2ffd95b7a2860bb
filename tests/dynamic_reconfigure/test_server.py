"""The dynamic_reconfigure tutorial's server node (rospy, no build step) against Debian's dynparam and client."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from kame.msg.catalog import SHARE_DIR

from ..libs import debian
from ..support import Proc, free_port, kame_command, ros_env, running, wait_for_master

HERE = Path(__file__).parent
TUTORIALS = HERE / "dynamic_tutorials"
SERVER = TUTORIALS / "nodes" / "server.py"
CLIENT = HERE / "client_driver.py"
DEBIAN_SERVER = HERE / "debian_server.py"
DEBIAN_DYNPARAM = Path("/usr/lib/dynamic_reconfigure/dynparam")
NO_DEBIAN = "Debian's python3-dynamic-reconfigure is not installed"


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


def debian_ros_env(env: dict[str, str]) -> dict[str, str]:
    environment = {k: v for k, v in debian.debian_env().items() if not k.startswith("ROS_")}
    environment.update({k: v for k, v in env.items() if k.startswith("ROS_")})
    # roslib.load_manifest('dynamic_reconfigure') looks for the package; Debian ships its modules but no package.xml
    environment["ROS_PACKAGE_PATH"] = os.pathsep.join([env["ROS_PACKAGE_PATH"], str(SHARE_DIR / "dynamic_reconfigure")])
    return environment


def debian_dynparam(env: dict[str, str], *args: str) -> str:
    result = subprocess.run([str(debian.SYSTEM_PYTHON), str(DEBIAN_DYNPARAM), *args], env=debian_ros_env(env),
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def run_client(python: str, env: dict[str, str], server: str, *changes: dict[str, Any]) -> dict[str, Any]:
    result = subprocess.run([python, str(CLIENT), server, *map(json.dumps, changes)], env=env, capture_output=True,
                            text=True, timeout=90)
    assert result.returncode == 0, result.stdout + result.stderr
    answer: dict[str, Any] = json.loads(result.stdout.splitlines()[-1])
    return answer


TUTORIAL_DEFAULTS = {"int_param": 50, "double_param": 0.5, "str_param": "Hello World", "bool_param": True, "size": 1}
# as dynparam's users type them: text for numbers and bools, an enum constant by name; 500 is clamped to 100
TUTORIAL_CHANGES = ({"int_param": 20}, {"bool_param": "false", "size": "Large", "double_param": "0.25"},
                    {"int_param": 500, "str_param": "kame"}, TUTORIAL_DEFAULTS)


def test_kames_client_changes_the_tutorial_server(master_env: dict[str, str], tutorial_server: Proc) -> None:
    answer = run_client(sys.executable, master_env, "/dynamic_tutorials", *TUTORIAL_CHANGES)
    assert answer["names"] == ["int_param", "double_param", "str_param", "bool_param", "size", "speed", "label"]
    assert answer["first"] == {**TUTORIAL_DEFAULTS, "speed": 1.0, "label": ""}
    assert answer["answers"][0]["int_param"] == 20
    assert {k: answer["answers"][1][k] for k in ("bool_param", "size", "double_param")} == {
        "bool_param": False, "size": 2, "double_param": 0.25}
    assert (answer["answers"][2]["int_param"], answer["answers"][2]["str_param"]) == (100, "kame")
    assert answer["last_seen"] == answer["first"] and answer["groups"] == ["Limits"]
    assert answer["services"] == ["/dynamic_tutorials"] and answer["callback_error"]
    assert answer["unknown"] == ["DynamicReconfigureParameterException", "don't know parameter: no_such_param", True]
    tutorial_server.wait_line("Reconfigure Request: 100, 0.25,          kame, False, 2")


@pytest.mark.skipif(not debian.has("rospy", "dynamic_reconfigure.client"), reason=NO_DEBIAN)
def test_kames_and_debians_client_agree_on_kames_server(master_env: dict[str, str], tutorial_server: Proc) -> None:
    ours = run_client(sys.executable, master_env, "/dynamic_tutorials", *TUTORIAL_CHANGES)
    theirs = run_client(str(debian.SYSTEM_PYTHON), debian_ros_env(master_env), "/dynamic_tutorials",
                        *TUTORIAL_CHANGES)
    assert ours == theirs


@pytest.mark.skipif(not debian.has("rospy", "dynamic_reconfigure.server"), reason=NO_DEBIAN)
def test_kames_client_on_debians_server(master_env: dict[str, str]) -> None:
    with running([str(debian.SYSTEM_PYTHON), str(DEBIAN_SERVER)], debian_ros_env(master_env)) as server:
        server.wait_line("configured int_=0 str_=foo level=-1")
        answer = run_client(sys.executable, master_env, "/debian_reconfigure",
                            {"int_": 5, "str_": "kame"}, {"int_enum_": "Large"}, {"int_": 99})
        server.wait_line("configured int_=10 str_=kame level=1")
    assert answer["first"]["some_param"] == 20 and answer["first"]["group2_string"] == "test string"
    assert [a["int_"] for a in answer["answers"]] == [5, 5, 10]  # 99 is above int_'s max of 10
    assert answer["answers"][1]["int_enum_"] == 2
    assert answer["groups"] == ["Group_One", "Upper_Group_2"]


@pytest.mark.skipif(not (DEBIAN_DYNPARAM.exists() and debian.has("rospy", "dynamic_reconfigure.client")),
                    reason=NO_DEBIAN)
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


def kame_dynparam(env: dict[str, str], *args: str) -> str:
    result = subprocess.run(kame_command("kame.cli.rosrun", "dynamic_reconfigure", "dynparam", *args), env=env,
                            capture_output=True, text=True, timeout=60)
    assert result.returncode == 0, result.stdout + result.stderr
    return result.stdout


def test_kames_dynparam_on_the_tutorial_server(master_env: dict[str, str], tutorial_server: Proc,
                                               tmp_path: Path) -> None:
    assert kame_dynparam(master_env, "list").split() == ["/dynamic_tutorials"]
    kame_dynparam(master_env, "set", "/dynamic_tutorials", "int_param", "-5")  # below min 0: clamped
    tutorial_server.wait_line("Reconfigure Request: 0, 0.5,          Hello World, True, 1")
    kame_dynparam(master_env, "set", "--timeout=10", "/dynamic_tutorials", "{str_param: dyn, size: ExtraLarge}")
    tutorial_server.wait_line("Reconfigure Request: 0, 0.5,          dyn, True, 3")
    got = kame_dynparam(master_env, "get", "/dynamic_tutorials")
    assert "'str_param': 'dyn'" in got and "'size': 3" in got
    if debian.has("rospy", "dynamic_reconfigure.client"):
        assert got == debian_dynparam(master_env, "get", "/dynamic_tutorials")
    dumped = tmp_path / "dump.yaml"
    kame_dynparam(master_env, "dump", "/dynamic_tutorials", str(dumped))
    kame_dynparam(master_env, "set", "/dynamic_tutorials", "{str_param: changed, int_param: 9}")
    tutorial_server.wait_line("Reconfigure Request: 9, 0.5,          changed, True, 3")
    kame_dynparam(master_env, "load", "/dynamic_tutorials", str(dumped))
    assert "'str_param': 'dyn'" in kame_dynparam(master_env, "get", "/dynamic_tutorials")
    kame_dynparam(master_env, "set_from_parameters", "/dynamic_tutorials", "_int_param:=33", "_bool_param:=false")
    tutorial_server.wait_line("Reconfigure Request: 33, 0.5,          dyn, False, 3")


def test_dynparam_usage_and_errors(master_env: dict[str, str]) -> None:
    usage = subprocess.run(kame_command("kame.cli.dynparam"), env=master_env, capture_output=True, text=True,
                           timeout=60)
    assert usage.returncode == 1 and "dynparam list                 list configurable nodes" in usage.stdout
    bad = subprocess.run(kame_command("kame.cli.dynparam", "set", "/n", "[1, 2]"), env=master_env,
                         capture_output=True, text=True, timeout=60)
    assert bad.returncode == 2 and "dynparam: error: invalid arguments. Please specify either" in bad.stderr
