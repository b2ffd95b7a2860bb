"""roslaunch end to end, as a user runs it: a master auto-started, nodes started, respawned,
required, stopped on Ctrl-C with nothing left behind; listings compared with Debian's roslaunch."""

from __future__ import annotations

import json
import os
import re
import signal
import subprocess
import sys
import time
import xmlrpc.client
from pathlib import Path

import pytest

from tests.support import SYSTEM_PYTHON, Proc, free_port, kame_command, ros_env, wait_for_master

RECORDER = """#!/usr/bin/env python3
# Writes what it was started with (argv, env, cwd) to $RECORD_DIR/<__name>.json, then sleeps.
import json, os, signal, subprocess, sys, time
name = [a.split(":=", 1)[1] for a in sys.argv if a.startswith("__name:=")][0]
if os.environ.get("STUBBORN"):
    signal.signal(signal.SIGINT, signal.SIG_IGN)
    signal.signal(signal.SIGTERM, signal.SIG_IGN)
    grandchild = subprocess.Popen(["sleep", "60"])
    os.environ["GRANDCHILD"] = str(grandchild.pid)
record = os.path.join(os.environ["RECORD_DIR"], name + ".json")
with open(record + ".part", "w") as f:
    json.dump({"argv": sys.argv, "env": dict(os.environ), "cwd": os.getcwd(), "pid": os.getpid()}, f)
os.replace(record + ".part", record)  # whole once it exists
with open(os.path.join(os.environ["RECORD_DIR"], name + ".runs"), "a") as f:
    f.write("run\\n")
if os.environ.get("AFTER_RUNS"):  # "<name>:<n>": live on only once that node has started n times
    other, n = os.environ["AFTER_RUNS"].split(":")
    runs = os.path.join(os.environ["RECORD_DIR"], other + ".runs")
    deadline = time.monotonic() + 60
    while time.monotonic() < deadline:
        if os.path.exists(runs) and open(runs).read().count("\\n") >= int(n):
            break
        time.sleep(0.05)
print("recorder", name, "up", flush=True)
lifetime = float(os.environ.get("LIFETIME", "60"))
try:
    time.sleep(lifetime)
except KeyboardInterrupt:
    sys.exit(0)
sys.exit(int(os.environ.get("EXIT_CODE", "0")))
"""

PACKAGE_XML = """<package format="2"><name>demo</name><version>0.0.1</version><description>d</description>
<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>"""

FILES = {
    "launch/talker_listener.launch": """<launch>
  <node name="listener" pkg="rospy_tutorials" type="listener" output="screen">
    <remap from="chatter" to="chat2"/>
  </node>
  <node name="talker" pkg="rospy_tutorials" type="talker" output="screen">
    <remap from="chatter" to="chat2"/>
  </node>
</launch>""",
    "launch/lifecycle.launch": """<launch>
  <env name="RECORD_DIR" value="$(env RECORD_DIR)"/>
  <node name="resp" pkg="demo" type="recorder.py" respawn="true" respawn_delay="0.2">
    <env name="LIFETIME" value="0.1"/><env name="EXIT_CODE" value="3"/>
  </node>
  <node name="prefixed" pkg="demo" type="recorder.py" launch-prefix="env PREFIXED=yes"/>
  <node name="boss" pkg="demo" type="recorder.py" required="true">
    <env name="AFTER_RUNS" value="resp:3"/><env name="LIFETIME" value="1.5"/>
  </node>
  <node name="brief" pkg="demo" type="recorder.py"><env name="LIFETIME" value="0.1"/></node>
</launch>""",
    "launch/main.launch": """<launch>
  <arg name="robot" default="r1"/>
  <arg name="use_extra" default="true"/>
  <env name="RECORD_DIR" value="$(env RECORD_DIR)"/>
  <param name="rate" value="10"/>
  <rosparam command="load" file="$(find demo)/config/params.yaml" ns="cfg"/>
  <group ns="$(arg robot)">
    <include file="$(find demo)/launch/robot.launch">
      <arg name="speed" value="2.5"/>
    </include>
  </group>
  <group if="$(arg use_extra)">
    <node name="extra" pkg="demo" type="recorder.py"/>
  </group>
  <group unless="$(arg use_extra)">
    <node name="instead" pkg="demo" type="recorder.py" cwd="node" args="--flag 'two words'"/>
  </group>
</launch>""",
    "launch/robot.launch": """<launch>
  <arg name="speed"/>
  <param name="speed" value="$(arg speed)"/>
  <node name="driver" pkg="demo" type="recorder.py">
    <remap from="cmd_vel" to="/mux/cmd_vel"/>
    <param name="~gain" type="double" value="3"/>
  </node>
</launch>""",
    "launch/stubborn.launch": """<launch>
  <node name="stubborn" pkg="demo" type="recorder.py">
    <env name="RECORD_DIR" value="$(env RECORD_DIR)"/><env name="STUBBORN" value="1"/>
  </node>
</launch>""",
    "launch/lone.launch": """<launch>
  <node name="lone" pkg="demo" type="recorder.py"><env name="RECORD_DIR" value="$(env RECORD_DIR)"/></node>
</launch>""",
    "launch/crashy.launch": """<launch>
  <node name="crashy" pkg="demo" type="recorder.py" respawn="true">
    <env name="RECORD_DIR" value="$(env RECORD_DIR)"/><env name="LIFETIME" value="0"/><env name="EXIT_CODE" value="1"/>
  </node>
</launch>""",
    "launch/bad.launch": """<launch>
  <node name="ok" pkg="demo" type="recorder.py"/>
  <param name="p" value="$(arg missing)"/>
</launch>""",
    "launch/orphans.launch": """<launch>
  <env name="RECORD_DIR" value="$(env RECORD_DIR)"/>
  <node name="stubborn" pkg="demo" type="recorder.py"><env name="STUBBORN" value="1"/></node>
  <node name="wrapped" pkg="demo" type="wrapper.sh"/>
</launch>""",
    "launch/only_param.launch": """<launch><param name="set_by_launch" value="1"/></launch>""",
    "config/params.yaml": "gains: {p: 1.0, i: 0.1}\nnames: [a, b]\nenabled: yes\n",
}


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    pkg = tmp_path / "ws" / "demo"
    for rel, text in FILES.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text)
    (pkg / "package.xml").write_text(PACKAGE_XML)
    script = pkg / "scripts" / "recorder.py"
    script.parent.mkdir()
    script.write_text(RECORDER)
    script.chmod(0o755)
    wrapper = pkg / "scripts" / "wrapper.sh"  # a shell that runs the node as its child, not exec
    wrapper.write_text('#!/bin/sh\n"$(dirname "$0")/recorder.py" "$@"\n')
    wrapper.chmod(0o755)
    (tmp_path / "records").mkdir()
    return tmp_path


def launch_env(workspace: Path, port: int) -> dict[str, str]:
    env = ros_env(workspace / "home", f"http://127.0.0.1:{port}")
    env.update(ROS_PACKAGE_PATH=str(workspace / "ws"), RECORD_DIR=str(workspace / "records"))
    return env


def started_pids(out: str) -> dict[str, int]:
    return {m[0]: int(m[1]) for m in re.findall(r"process\[([^\]]+)\]: started with pid \[(\d+)\]", out)}


def gone(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def wait_for(predicate, timeout: float = 10.0) -> None:  # type: ignore[no-untyped-def]
    deadline = time.monotonic() + timeout
    while not predicate():
        if time.monotonic() > deadline:
            raise AssertionError("condition not met in time")
        time.sleep(0.05)


def record(workspace: Path, name: str) -> dict:  # type: ignore[type-arg]
    path = workspace / "records" / f"{name}.json"
    wait_for(path.exists)  # written aside and moved there: whole
    return json.loads(path.read_text())  # type: ignore[no-any-return]


def test_talker_listener_autostarts_master_and_stops_cleanly(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    proc = Proc(kame_command("kame.cli.roslaunch", "demo", "talker_listener.launch"), env)
    try:
        proc.wait_line("I heard hello world", timeout=20)
        master = xmlrpc.client.ServerProxy(f"http://127.0.0.1:{port}")
        publishers, subscribers, _ = master.getSystemState("/t")[2]
        assert ["/chat2", ["/talker"]] in publishers
        assert ["/chat2", ["/listener"]] in subscribers
        assert master.getParam("/t", "/rosdistro")[2] == "noetic\n"
        run_id = master.getParam("/t", "/run_id")[2]
        server = re.search(r"started roslaunch server (http://127\.0\.0\.1:(\d+)/)",  # type: ignore[union-attr]
                           proc.wait_line("started roslaunch server"))
        assert master.getParam("/t", f"/roslaunch/uris/host_127_0_0_1__{server.group(2)}")[2] == server.group(1)
        launcher = xmlrpc.client.ServerProxy(server.group(1))
        assert launcher.list_processes() == [1, "processes on parent machine",
                                             [[["master", 1], ["rosout-1", 1], ["listener-2", 1], ["talker-3", 1]], []]]
        assert launcher.get_node_names()[2] == ["master", "rosout-1", "listener-2", "talker-3"]
    finally:
        out, err = proc.stop(timeout=10)
    assert proc.popen.returncode == 0, err
    pids = started_pids(out)
    assert list(pids) == ["master", "rosout-1", "listener-2", "talker-3"]
    assert "auto-starting new master" in out
    assert "NODES\n  /\n    listener (rospy_tutorials/listener)\n    talker (rospy_tutorials/talker)\n" in out
    kills = re.findall(r"^\[([^\]\n]+)\] killing on exit", out, re.M)
    assert kills == ["talker-3", "listener-2", "rosout-1", "master"]
    assert "\033[1mdone\033[0m" in out
    assert all(gone(pid) for pid in pids.values())
    assert (workspace / "home" / "log" / run_id / "master.log").exists()


def test_respawn_required_and_launch_prefix(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    proc = Proc(kame_command("kame.cli.roslaunch", "demo", "lifecycle.launch"), env)
    try:
        proc.popen.wait(20)
    finally:
        out, err = proc.stop()
    assert proc.popen.returncode == 0, out + err
    assert out.count("[resp-2] restarting process") >= 2
    assert "REQUIRED process [boss-4] has died!\nprocess has finished cleanly" in err
    assert "[resp-2] process has died [pid" in err and "exit code 3" in err
    assert "[brief-5] process has finished cleanly" in out
    # as pmon: the ended required one is still listed, one that ended for good (brief) no longer
    kills = re.findall(r"^\[([^\]\n]+)\] killing on exit", out, re.M)
    assert kills == ["boss-4", "prefixed-3", "resp-2", "rosout-1", "master"]
    prefixed = record(workspace, "prefixed")
    assert prefixed["env"]["PREFIXED"] == "yes"
    assert all(gone(pid) for pid in started_pids(out).values())


def test_args_groups_include_rosparam(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    proc = Proc(kame_command("kame.cli.roslaunch", "demo", "main.launch", "robot:=r2", "use_extra:=false"), env)
    try:
        proc.wait_line("process[instead-3]", timeout=20)
        driver = record(workspace, "driver")
        instead = record(workspace, "instead")
        master = xmlrpc.client.ServerProxy(f"http://127.0.0.1:{port}")
        tree = master.getParam("/t", "/")[2]
        assert not (workspace / "records" / "extra.json").exists()
    finally:
        out, _ = proc.stop(timeout=10)
    assert tree["rate"] == 10 and tree["r2"]["speed"] == 2.5 and tree["r2"]["driver"] == {"gain": 3.0}
    assert tree["cfg"] == {"gains": {"p": 1.0, "i": 0.1}, "names": ["a", "b"], "enabled": True}
    run_dir = workspace / "home" / "log" / tree["run_id"]
    assert driver["argv"][1:] == ["cmd_vel:=/mux/cmd_vel", "__name:=driver", f"__log:={run_dir}/r2-driver-2.log"]
    assert driver["env"]["ROS_NAMESPACE"] == "/r2" and driver["cwd"] == str(workspace / "home")
    assert driver["env"]["ROS_MASTER_URI"] == f"http://127.0.0.1:{port}"
    assert instead["argv"][1:3] == ["--flag", "two words"] and "ROS_NAMESPACE" not in instead["env"]
    assert instead["cwd"] == str(workspace / "ws" / "demo" / "scripts")
    assert (run_dir / "r2-driver-2-stdout.log").read_text() == "recorder driver up\n"
    assert " * /r2/driver/gain: 3.0\n" in out and " * /cfg/names: ['a', 'b']\n" in out
    assert all(gone(pid) for pid in started_pids(out).values())


def test_ctrl_c_escalates_and_leaves_no_orphan(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    proc = Proc(kame_command("kame.cli.roslaunch", "--sigint-timeout", "0.5", "--sigterm-timeout", "0.5",
                             "demo", "stubborn.launch"), env)
    try:
        stubborn = record(workspace, "stubborn")
    finally:
        out, err = proc.stop(timeout=10)
    assert "[stubborn-2] escalating to SIGTERM" in err and "[stubborn-2] escalating to SIGKILL" in err
    assert gone(stubborn["pid"])
    assert gone(int(stubborn["env"]["GRANDCHILD"]))
    assert all(gone(pid) for pid in started_pids(out).values())


def test_a_node_that_crashes_at_start_is_restarted_ever_more_slowly(workspace: Path) -> None:
    # It used to be restarted every 0.06 s for as long as the launch ran.
    env = launch_env(workspace, free_port())
    proc = Proc(kame_command("kame.cli.roslaunch", "demo", "crashy.launch"), env)
    try:
        wait_for(lambda: "restarting in 2 s" in "".join(proc.err), timeout=30)
        runs = (workspace / "records" / "crashy.runs").read_text().count("\n")
    finally:
        _, err = proc.stop(timeout=10)
    # started, died, restarted at once; then 0.5 s, 1 s, 2 s between starts, each step said once
    assert runs == 4
    for step in ("0.5", "1", "2"):
        assert err.count(f"times in a row: restarting in {step} s") == 1, err
    assert "[crashy-2] died 0." in err and "2 times in a row: restarting in 0.5 s" in err


def test_children_die_with_a_roslaunch_killed_outright(workspace: Path) -> None:
    # SIGKILL on roslaunch used to leave its master, rosout and nodes running as orphans.
    env = launch_env(workspace, free_port())
    proc = Proc(kame_command("kame.cli.roslaunch", "demo", "lone.launch"), env)
    pids: dict[str, int] = {}
    try:
        lone = record(workspace, "lone")
        pids = started_pids("".join(proc.out))
        os.kill(proc.pid, signal.SIGKILL)
        proc.popen.wait(10)
        for pid in pids.values():
            wait_for(lambda pid=pid: gone(pid))  # type: ignore[misc]
    finally:
        proc.stop()
        for pid in pids.values():  # had they outlived it, the test must not leave them behind
            if not gone(pid):
                os.kill(pid, signal.SIGKILL)
    assert set(pids) == {"master", "rosout-1", "lone-2"} and pids["lone-2"] == lone["pid"]


def test_a_stubborn_node_and_a_wrappers_child_die_with_a_roslaunch_killed_outright(workspace: Path) -> None:
    # PDEATHSIG's SIGTERM alone left both running: one ignores it, the other never gets it
    env = launch_env(workspace, free_port())
    proc = Proc(kame_command("kame.cli.roslaunch", "--sigint-timeout", "0.5", "--sigterm-timeout", "0.5",
                             "demo", "orphans.launch"), env)
    victims: list[int] = []
    try:
        stubborn, wrapped = record(workspace, "stubborn"), record(workspace, "wrapped")
        victims = [stubborn["pid"], int(stubborn["env"]["GRANDCHILD"]), wrapped["pid"]]
        os.kill(proc.pid, signal.SIGKILL)
        proc.popen.wait(10)
        for pid in victims:
            wait_for(lambda pid=pid: gone(pid), timeout=15)  # type: ignore[misc]
    finally:
        _, err = proc.stop()
        for pid in victims:  # had they outlived it, the test must not leave them behind
            if not gone(pid):
                os.kill(pid, signal.SIGKILL)
    assert f"roslaunch [{proc.pid}] is gone and left " in err and ": sending SIGKILL" in err, err


def test_load_error_starts_nothing(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    result = subprocess.run(kame_command("kame.cli.roslaunch", "demo", "bad.launch"), env=env,
                            capture_output=True, text=True, timeout=30)
    bad = workspace / "ws" / "demo" / "launch" / "bad.launch"
    assert result.returncode == 1
    assert f"RLException: [{bad}] requires the 'missing' arg to be set\n  at {bad}:3" in result.stderr
    assert "started with pid" not in result.stdout
    assert not (workspace / "records" / "ok.json").exists()


def test_a_missing_node_type_is_reported_and_the_rest_run(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    xml = ('<launch><node name="none" pkg="demo" type="nonexist.py"/>'
           '<node name="ok" pkg="demo" type="recorder.py"><env name="RECORD_DIR" value="$(env RECORD_DIR)"/>'
           "</node></launch>")
    (workspace / "mixed.launch").write_text(xml)
    proc = Proc(kame_command("kame.cli.roslaunch", str(workspace / "mixed.launch")), env)
    try:
        record(workspace, "ok")
    finally:
        out, err = proc.stop(timeout=10)
    assert ("ERROR: cannot launch node of type [demo/nonexist.py]: Cannot locate node of type [nonexist.py] in "
            "package [demo]. Make sure file exists in package path and permission is set to executable") in err
    assert "process[ok-2]" in out


# ------------------------------------------------------------------ side by side with Debian's roslaunch


def have_debian_roslaunch() -> bool:
    if not os.path.exists("/usr/bin/roslaunch"):
        return False
    return subprocess.run([SYSTEM_PYTHON, "-c", "import roslaunch"], capture_output=True).returncode == 0


@pytest.mark.skipif(not have_debian_roslaunch(), reason="Debian's roslaunch is not installed")
@pytest.mark.parametrize("option", [["--dump-params"], ["--nodes"], ["--files"], ["--args", "/r2/driver"],
                                    ["--find-node", "/r2/driver"], ["--ros-args"]])
def test_listings_match_debian(workspace: Path, option: list[str]) -> None:
    env = launch_env(workspace, free_port())
    args = [*option, "demo", "main.launch", "robot:=r2"]
    real = subprocess.run([SYSTEM_PYTHON, "/usr/bin/roslaunch", *args], env=env, capture_output=True, text=True,
                          timeout=60)
    ours = subprocess.run([sys.executable, "-m", "kame.cli.roslaunch", *args], env=env, capture_output=True,
                          text=True, timeout=60)
    assert (ours.returncode, ours.stderr) == (real.returncode, real.stderr)
    if option == ["--files"]:  # roslaunch prints a set: its order is arbitrary
        assert sorted(ours.stdout.splitlines()) == sorted(real.stdout.splitlines())
    elif option[0] == "--args":  # the program: Debian runs the script, kame runs it with its interpreter
        assert ours.stdout.replace(sys.executable + " ", "") == real.stdout
    else:
        assert ours.stdout == real.stdout


def test_each_launch_removes_its_server_uri_from_the_master_it_leaves(workspace: Path) -> None:
    # roslaunch sets /roslaunch/uris/host_<host>__<port> and left it there: one stale entry a launch
    port = free_port()
    env = launch_env(workspace, port)
    uri = f"http://127.0.0.1:{port}"
    with_master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    try:
        wait_for_master(uri, proc=with_master)
        master = xmlrpc.client.ServerProxy(uri)
        for _ in range(2):  # nothing to run: the launch ends by itself
            done = subprocess.run(kame_command("kame.cli.roslaunch", "demo", "only_param.launch"), env=env,
                                  capture_output=True, text=True, timeout=60)
            assert done.returncode == 0 and "No processes to monitor" in done.stdout, done.stdout + done.stderr
        proc = Proc(kame_command("kame.cli.roslaunch", "demo", "lone.launch"), env)
        try:
            record(workspace, "lone")
            assert len(master.getParam("/test", "/roslaunch/uris")[2]) == 1  # this one's, while it runs
        finally:
            proc.stop(timeout=25)  # Ctrl-C
        assert proc.popen.returncode == 0
        code, _, uris = master.getParam("/test", "/roslaunch/uris")
        assert code == 1 and uris == {}, uris
        assert master.getParam("/test", "/set_by_launch")[2] == 1  # what the launch set stays
    finally:
        with_master.stop()


def test_master_already_running(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    with_master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    try:
        wait_for_master(f"http://127.0.0.1:{port}", proc=with_master)
        proc = Proc(kame_command("kame.cli.roslaunch", "demo", "stubborn.launch"), env)
        try:
            proc.wait_line("process[stubborn-1]")
        finally:
            out, _ = proc.stop(timeout=25)
    finally:
        with_master.stop()
    assert "auto-starting" not in out and f"ROS_MASTER_URI=http://127.0.0.1:{port}" in out


@pytest.mark.parametrize("args", [["demo", "nope.launch"], ["--nodes", "demo", "nope.launch"], ["/no/such.launch"]])
def test_a_file_not_found_is_said_once(workspace: Path, args: list[str]) -> None:
    result = subprocess.run(kame_command("kame.cli.roslaunch", *args), env=launch_env(workspace, free_port()),
                            capture_output=True, text=True, timeout=30)
    text = (f"[{args[-1]}] is not a launch file name" if len(args) == 1 else
            "[nope.launch] is neither a launch file in package [demo] nor is [demo] a launch file name")
    assert (result.returncode, result.stdout) == (1, "")
    # as Debian's roslaunch: the red RLException and the traceback line, and no bare copy of the text
    assert result.stderr == (f"\033[31mRLException: {text}\033[0m\n"
                             "\033[31mThe traceback for the exception was written to the log file\033[0m\n")


def test_wait_waits_for_a_master_started_later(workspace: Path) -> None:
    port = free_port()
    env = launch_env(workspace, port)
    proc = Proc(kame_command("kame.cli.roslaunch", "--wait", "demo", "stubborn.launch"), env)
    try:
        proc.wait_line("roscore/master is not yet running, will wait for it to start")
        # roscore, not a bare master: --wait then waits for the /run_id that roscore sets, as roslaunch does
        master = Proc(kame_command("kame.cli.roscore", "-p", str(port)), env)
        try:
            proc.wait_line("master has started, initiating launch", timeout=20)
            proc.wait_line("process[stubborn-1]", timeout=20)
        finally:
            out, _ = proc.stop(timeout=25)
            master.stop()
    finally:
        proc.stop()
    assert "auto-starting" not in out


@pytest.mark.parametrize("args", [["--help"], [], ["--bogus"]])
def test_usage_help_and_errors_are_debians(tmp_path: Path, args: list[str]) -> None:
    # optparse's texts: "Usage:", the blank line before "roslaunch: error: ...", exit status 2
    debian = Path("/usr/bin/roslaunch")
    if not debian.exists():
        pytest.skip("Debian's roslaunch is not installed")
    env = dict(ros_env(tmp_path), COLUMNS="80")
    ours = subprocess.run(kame_command("kame.cli.roslaunch", *args), capture_output=True, text=True, env=env,
                          timeout=60)
    theirs = subprocess.run([SYSTEM_PYTHON, str(debian), *args], capture_output=True, text=True, env=env,
                            timeout=60)
    assert (ours.returncode, ours.stdout, ours.stderr) == (theirs.returncode, theirs.stdout, theirs.stderr)
