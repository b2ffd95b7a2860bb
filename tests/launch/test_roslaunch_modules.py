"""roslaunch's modules file for file (issue 35): core, loader, substitution_args, node_args,
param_dump, arg_dump, depends, rlutil, xmlloader, pmon, nodeprocess, launch, server's child side,
remote. Each is run on the same inputs under kame's interpreter and Debian's real roslaunch
(roslaunch_modules_driver.py, roslaunch_run_driver.py) and the answers compared; kame's are also
checked on their own, so the tests mean something where Debian's roslaunch is not installed.
"""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from tests.libs import debian
from tests.support import free_port, ros_env

HERE = Path(__file__).resolve().parent
DRIVER = HERE / "roslaunch_modules_driver.py"
RUN_DRIVER = HERE / "roslaunch_run_driver.py"
LAUNCH = HERE / "rl_pkg" / "launch" / "demo.launch"
NEEDS_DEBIAN = pytest.mark.skipif(not debian.has("roslaunch.loader", "roslaunch.pmon"),
                                  reason="Debian's python3-roslaunch is not installed")
_answers: dict[tuple[str, ...], Any] = {}


def answer(python: str, *args: str, tmp: Path) -> Any:
    """The driver's JSON (its last line) under `python`; cached per interpreter and arguments."""
    key = (python, *args)
    if key not in _answers:
        env = {**ros_env(tmp / "home", f"http://127.0.0.1:{free_port()}/"), "ROS_PACKAGE_PATH": str(HERE)}
        if python == str(debian.SYSTEM_PYTHON):
            env = {k: v for k, v in env.items() if k not in ("PYTHONPATH", "VIRTUAL_ENV")}
        done = subprocess.run([python, *args], capture_output=True, text=True, env=env, timeout=120)
        assert done.returncode == 0, done.stderr
        _answers[key] = json.loads(done.stdout.splitlines()[-1])
    return _answers[key]


def kame(section: str, tmp: Path) -> Any:
    return answer(sys.executable, str(DRIVER), section, str(LAUNCH), tmp=tmp)


def ros(section: str, tmp: Path) -> Any:
    return answer(str(debian.SYSTEM_PYTHON), str(DRIVER), section, str(LAUNCH), tmp=tmp)


SECTIONS = ["core", "loader", "substitution", "files", "process"]


@NEEDS_DEBIAN
@pytest.mark.parametrize("section", SECTIONS)
def test_the_same_answers_as_debians_roslaunch(section: str, tmp_path: Path) -> None:
    assert kame(section, tmp_path) == ros(section, tmp_path)


def test_core(tmp_path: Path) -> None:
    core = kame("core", tmp_path)
    assert core["bad nodes"] == {
        "empty package": ["ValueError", "package must be non-empty"],
        "blank type": ["ValueError", "type must be non-empty"],
        "namespaced name": ["ValueError", "node name cannot contain a namespace"],
        "respawn and required": ["ValueError", "respawn and required cannot both be set to true"],
        "bad output": ["ValueError", "output must be one of 'log', 'screen'"],
        "bad cwd": ["ValueError", "cwd must be one of 'ROS_HOME', 'node'"],
        "zero time limit": ["ValueError", "'time-limit' must be a positive number"],
        "text time limit": ["ValueError", "'time-limit' must be a number"]}
    cwd, ns, same_remaps, xmltype, _, xml, remote_xml, _, _ = core["node"]
    assert (cwd, ns, same_remaps, xmltype) == ("ROS_HOME", "/ns/sub/", True, "node")
    assert xml.startswith('<node pkg="pkg" type="type" machine="m" ns="/ns/sub/" args="x &quot;y&quot;"')
    assert '  <env name="E" value="v&<>" />\n' in xml and 'machine=' not in remote_xml  # ROS escapes attributes only
    assert core["machines"][2:] == [True, False, 10.0, None]
    assert core["master"][:2] == ["ServerProxy", "MultiCall"]
    assert core["executables"] == ["cmd a b", "ros/bin/rosparam dump f", "run", "setup", "teardown", 60]
    handled, out, err = core["printlog"]
    assert handled == [["log", "plain"], ["log", "bold"], ["err", "error"]]
    assert out == "plain\n\x1b[1mbold\x1b[0m\n" and err == "\x1b[31merror\x1b[0m\n"
    assert core["child mode"] == [False, True] and core["run id"] == [36, 4]
    assert core["env"] == {"ROS_MASTER_URI": "http://m:1/", "ROS_NAMESPACE": "/ns/sub", "KEEP": "k", "E": "v&<>"}
    assert core["rle_wrapper"][0] == "RLException"


def test_loader(tmp_path: Path) -> None:
    loader = kame("loader", tmp_path)
    assert loader["values"]["010"]["auto"] == 10 and loader["values"]["1_0"]["auto"] == "1_0"
    assert loader["values"][" 0 "]["bool"] is False and loader["values"]["x"]["nope"][0] == "ValueError"
    remaps, child_remaps, child_ns = loader["remaps"][:3]
    assert remaps == [["a", "c"]] and child_remaps == [["a", "c"], ["d", "/e"]] and child_ns == "/ns/sub/"
    names, resolved, errors, *_ = loader["args"]
    assert names == ["one", "two", "three", "three2"]
    assert errors[0] == ["LoadException", "arg 'one' has already been declared"]
    assert resolved["arg"] == {"a": "1", "__ns": "x", "b": "c"}  # load_sysargs_into_context's: _private left out
    assert loader["args"][7] == ["LoadException", "include args must have declared values"]
    assert ["exe", "ros/bin/rosparam dump out.yaml /r/q", "setup", "RosbinExecutable"] in loader["added"]
    assert ["param", "/top/b/c", "x"] in loader["added"] and ["param", "/r/z", 2] in loader["added"]
    assert loader["param values"][3] == 42 and loader["rosparam"] is False


def test_substitution_args(tmp_path: Path) -> None:
    subst = kame("substitution", tmp_path)
    cases = subst["cases"]
    assert cases[1:4] == ["dflt val", "", "1-x"] and cases[4] == str(HERE / "rl_pkg" / "launch")
    assert cases[6:9] == ["2", "xy", "True"] and cases[9:12] == ["plain", "", None]
    assert cases[12] == ["ArgException", "missing"] and cases[14] == ["ResourceNotFound", ["no_such_pkg"]]
    assert cases[15][0] == cases[19][0] == "SubstitutionException"
    assert subst["anon"] == [True, True, ["foo"]]


def test_files_node_args_depends_check(tmp_path: Path) -> None:
    files = kame("files", tmp_path)
    assert files["node list"] == ["/first", "/g/second", "/g/third", "/ghost", "/nowhere", "/t"]
    exiter = str(HERE / "rl_pkg" / "scripts" / "exiter")
    assert files["process args"] == [exiter, "3", "a:=b", "__name:=first"]
    assert files["node args"] == ['ROS_NAMESPACE="/g"', exiter, "0", "__name:=second"]
    assert files["missing program"][0] == "NodeParamsException"
    assert files["depends"][2] == {"rl_pkg": ["no_such_pkg"]}
    assert files["check"][0] == "Missing package dependencies: rl_pkg/package.xml: no_such_pkg"
    assert "cannot find node [missing_node] in package [rl_pkg]" in files["check"]
    assert files["args"] == {"code": ["the exit status", "3"], "who": [None, None]}
    assert "rate: 7" in files["dump_params"][1] and "who: me" in files["dump_params"][1]
    assert files["remap args"][0] == ["list", ["list"], [["a", "b"]]]
    assert [n[0] for n in files["xml nodes"][:6]] == ["XmlParseException"] * 6
    assert files["xml nodes"][6] == [["n", "ROS_HOME", None]]


def test_process_monitor_watches_real_processes(tmp_path: Path) -> None:
    proc = kame("process", tmp_path)
    assert proc["died"] == [["again", 0], ["dead", 3], ["sleeper", None]] and proc["respawned"]
    assert proc["duplicate"] == ["RLException", "cannot add process with duplicate name 'sleeper'"]
    assert proc["killed"][:2] == [True, False] and proc["names"] == [["again"], ["dead", "sleeper"]]
    assert proc["done"] == [True, True, False]
    assert proc["master process"][3] == ["--core", "-p", "11999", "-w", "4", "-t", "2.5", "--master-logger-level",
                                         "debug"]


def run_launch(python: str, tmp: Path) -> Any:
    return answer(python, str(RUN_DRIVER), str(LAUNCH), tmp=tmp)


def test_a_launch_through_the_runner_and_a_child(tmp_path: Path) -> None:
    run = run_launch(sys.executable, tmp_path)
    assert run["launched"] == [["Process<first", "Process<g/second", "Process<g/third"], ["ghost", "nowhere"]]
    assert run["params"] == [7, "me", {"max": 2.5, "names": ["a", "b"]}, "run-1"]
    assert run["first died"] and run["third respawned"] and run["test"] == ["t", False]
    assert run["deaths"] == [["first", 4], ["g/second", 0], ["t", 0]]
    assert run["active"] == ["g/third", "master", "rosout"] and run["master after stop"] == "gone"
    child = run["child"]
    assert child["registered"] and child["launch"] == [1, "launched", ["Process<remote_one"], ["remote_two"]]
    assert child["died"] == [True, [["remote_one", 5]]] and child["bad xml"] == [-1, [[], []]]


@NEEDS_DEBIAN
def test_a_launch_as_debians_runner_runs_it(tmp_path: Path) -> None:
    assert run_launch(sys.executable, tmp_path) == run_launch(str(debian.SYSTEM_PYTHON), tmp_path)


KAME_CHILD = """#!{python}
# roslaunch -c NAME -u SERVER_URI --run_id ID --sigint-timeout S --sigterm-timeout T, on kame's roslaunch.child
import argparse
import roslaunch.child

parser = argparse.ArgumentParser()
for flag in ("-c", "-u", "--run_id", "--sigint-timeout", "--sigterm-timeout"):
    parser.add_argument(flag)
a = parser.parse_args()
roslaunch.child.ROSLaunchChild(a.run_id, a.c, a.u, float(a.sigint_timeout), float(a.sigterm_timeout)).run()
"""


@pytest.mark.parametrize("child", ["debian", "kame"])
def test_the_remote_runner_drives_a_child(child: str, tmp_path: Path) -> None:
    """ROSRemoteRunner and SSHChildROSLaunchProcess with a child run here in place of over SSH:
    Debian's `roslaunch -c`, or kame's ROSLaunchChild. It registers, runs its node, reports its death."""
    loader = tmp_path / "env.sh"
    if child == "debian":
        if not (Path("/usr/bin/roslaunch").exists() and debian.has("roslaunch.child")):
            pytest.skip("Debian's roslaunch is not installed")
        setup = "export PATH=/usr/bin:/bin\nunset PYTHONPATH VIRTUAL_ENV"
    else:
        bin_dir = tmp_path / "bin"
        bin_dir.mkdir()
        (bin_dir / "roslaunch").write_text(KAME_CHILD.format(python=sys.executable))
        (bin_dir / "roslaunch").chmod(0o755)
        setup = f'export PATH="{bin_dir}:$PATH"'
    loader.write_text(f'#!/bin/sh\n# the other machine\'s ROS 1\n{setup}\nexec "$@"\n')
    loader.chmod(0o755)
    run = answer(sys.executable, str(HERE / "roslaunch_remote_driver.py"), str(loader), tmp=tmp_path)
    assert run == {"child": ["127.0.0.1-0", True, ["roslaunch", "-c", "127.0.0.1-0"], True],
                   "launched": [["Process<far_node"], []], "died": True, "heard": [["far_node", 6]], "answer": 42,
                   "child after stop": [False, True]}


def test_an_unreachable_machine_fails_the_launch(tmp_path: Path) -> None:
    """SSHChildROSLaunchProcess over kame's SSH to a port where nothing listens: start() is False and
    ROSRemoteRunner ends the launch with ROS's words."""
    code = f"""
import roslaunch.config, roslaunch.pmon, roslaunch.remote, roslaunch.server
xml = ('<launch><machine name="far" address="127.0.0.1" user="someone_else" ssh-port="{free_port()}" '
       'env-loader="/bin/env"/><node machine="far" pkg="p" type="t" name="n"/></launch>')
config = roslaunch.config.load_config_default([], None, roslaunch_strs=[xml])
pm = roslaunch.pmon.start_process_monitor()
server = roslaunch.server.ROSLaunchParentNode(config, pm)
server.start()
try:
    roslaunch.remote.ROSRemoteRunner("r", config, pm, server).start_children()
except roslaunch.core.RLException as exc:
    print("RLException:", exc)
finally:
    server.shutdown("over")
    roslaunch.pmon.pmon_shutdown()
"""
    env = {**ros_env(tmp_path), "ROSLAUNCH_SSH_UNKNOWN": "1"}
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=60)
    assert "RLException: unable to start remote roslaunch child: 127.0.0.1-0" in done.stdout, done.stderr
    assert "remote[127.0.0.1-0]: failed to launch on far:" in done.stderr


def test_scriptapi_takes_roslaunch_core_nodes() -> None:
    import kame.launch.scripting
    import roslaunch.core
    import roslaunch.scriptapi

    assert issubclass(roslaunch.core.Node, kame.launch.scripting.Node)
    assert roslaunch.scriptapi.Node is roslaunch.core.Node


def test_master_get_calls_a_real_master(tmp_path: Path) -> None:
    """Master.get() and get_multi() against kame's master: answers, a multicall, a fault."""
    from kame.protocol.xmlrpc import Fault
    from roslaunch.core import Master
    from tests.support import kame_command, running, wait_for_master

    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    with running(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), ros_env(tmp_path, uri)) as proc:
        wait_for_master(uri, proc=proc)
        master = Master(uri=uri)
        assert master.is_running()
        assert master.get().setParam("/t", "/x", 5)[0] == 1
        multi = master.get_multi()
        multi.getParam("/t", "/x")
        multi.hasParam("/t", "/nope")
        multi.noSuchMethod()
        answers = multi()
        assert next(answers)[2] == 5 and next(answers)[2] is False
        with pytest.raises(Fault):
            next(answers)
        with master.get() as proxy:
            assert proxy.getPid("/t")[0] == 1 and "ServerProxy for" in repr(proxy)
            proxy("close")()
