"""roslaunch's <machine> nodes, the parts that need no second host: what the parent sends and
prints, and the child (`roslaunch -c`) run here as sshd would run it. tests/hosts runs the whole
over SSH between network namespaces."""

from __future__ import annotations

import subprocess
import time
from pathlib import Path

import paramiko
import pytest

from kame.launch import plan
from kame.launch.errors import LaunchError
from kame.launch.model import LaunchConfig, Machine, Node
from kame.launch.remote import CHILD_READY, ENV_LOADER, child_command
from kame.net.ssh import known_hosts_problem
from tests.support import Proc, free_port, kame_command, ros_env, wait_for_master


def test_the_nodes_sent_to_a_child_come_back_the_same_and_garbage_is_refused() -> None:
    nodes = [Node("rospy_tutorials", "talker.py", "talker", namespace="/ns/", machine_name="laptop",
                  remap_args=[("chatter", "chat")], env_args=[("A", "1")], output="screen", respawn=True)]
    [back] = plan.nodes_from_json(plan.nodes_to_json(nodes))
    assert back.remap_args == [("chatter", "chat")] and back.env_args == [("A", "1")]
    assert back.resolved_name == "/ns/talker" and back.respawn and back.output == "screen"
    assert back.machine_name is None  # on the child, the node is local
    for garbage in ("", "{}", "[1]", '[{"package": "p", "bogus": 1}]'):
        with pytest.raises(LaunchError, match="the parent roslaunch sent no list of nodes"):
            plan.nodes_from_json(garbage)


def test_the_child_command_is_roslaunchs_with_kames_env_loader_by_default() -> None:
    machine = Machine("laptop", "laptop", env_loader="/opt/my env.sh")
    assert child_command(machine, "laptop-0", "r1", "http://robot:11311/", 15.0, 2.0) == (
        "env ROS_MASTER_URI=http://robot:11311/ '/opt/my env.sh' roslaunch -c laptop-0 --run_id r1 "
        "--sigint-timeout 15.0 --sigterm-timeout 2.0")
    default = child_command(Machine("laptop", "laptop"), "laptop-0", "r1", "http://robot:11311/", 15.0, 2.0)
    assert f" {ENV_LOADER} roslaunch " in default and ENV_LOADER.is_file()


def test_the_summary_lists_machines_only_when_nodes_run_elsewhere() -> None:
    config = LaunchConfig(nodes=[Node("p", "a", "here"), Node("p", "b", "there", machine_name="laptop")],
                          machines={"laptop": Machine("laptop", "laptop")})
    remote = plan.summary(config, local=False)
    assert "MACHINES\n * laptop" in remote and "there (p/b)" in remote
    local = plan.summary(config, local=True, is_local=lambda n: n.machine_name is None)
    assert "MACHINES" not in local and "here (p/a)" in local and "there" not in local


def test_an_unknown_host_is_named_with_the_ssh_command_and_the_override(tmp_path: Path,
                                                                        monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("HOME", str(tmp_path))
    (tmp_path / ".ssh").mkdir()
    key = paramiko.ECDSAKey.generate()
    (tmp_path / ".ssh" / "known_hosts").write_text(f"[known]:2222 {key.get_name()} {key.get_base64()}\n")
    client = paramiko.SSHClient()
    assert known_hosts_problem(client, "known", 2222, "root", {}) is None
    problem = known_hosts_problem(paramiko.SSHClient(), "known", 22, None, {})  # port 22 is another entry
    assert problem is not None and "Please manually:\n  ssh known\n" in problem
    problem = known_hosts_problem(paramiko.SSHClient(), "robot", 2200, "me", {})
    assert problem is not None and problem.startswith("robot is not in your SSH known_hosts file.")
    assert "  ssh -p 2200 me@robot\n" in problem and "ROSLAUNCH_SSH_UNKNOWN=1" in problem
    assert known_hosts_problem(paramiko.SSHClient(), "robot", 2200, "me", {"ROSLAUNCH_SSH_UNKNOWN": "1"}) is None


def test_a_child_runs_its_nodes_until_its_input_ends(tmp_path: Path) -> None:
    """What sshd runs on the remote machine: the nodes on stdin, `ready` on stdout, EOF to stop."""
    uri = f"http://127.0.0.1:{free_port()}/"
    env = ros_env(tmp_path, uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", uri.rsplit(":", 1)[1].strip("/")), env)
    child: Proc | None = None
    try:
        wait_for_master(uri, proc=master)
        child = Proc(kame_command("kame.cli.roslaunch", "-c", "here-0", "--run_id", "r1"), env,
                     stdin=subprocess.PIPE)
        assert child.popen.stdin is not None
        child.popen.stdin.write(plan.nodes_to_json([Node("rospy_tutorials", "talker.py", "talker",
                                                         output="screen")]) + "\n")
        child.popen.stdin.flush()
        child.wait_line(CHILD_READY, timeout=30)
        child.wait_line("hello world", timeout=30)  # the node's screen output on the child's stdout
        child.popen.stdin.close()  # the parent stops us (or its connection is lost)
        child.popen.wait(30)
        out = "".join(child.out)
        assert child.popen.returncode == 0, out + "".join(child.err)
        assert "[talker-1] killing on exit" in out
        deadline = time.monotonic() + 10
        while "/talker" in subprocess.run(kame_command("kame.cli.rosnode", "list"), env=env, capture_output=True,
                                          text=True).stdout.split():
            assert time.monotonic() < deadline, "the talker is still registered"
            time.sleep(0.05)
    finally:
        if child is not None:
            child.stop()
        master.stop()


def test_a_child_needs_a_run_id() -> None:
    done = subprocess.run(kame_command("kame.cli.roslaunch", "-c", "x-0"), capture_output=True, text=True)
    assert done.returncode == 2 and "--child option requires --run_id to be set as well" in done.stderr


def test_nodes_are_remote_by_their_machines_address_and_local_with_dash_dash_local(tmp_path: Path) -> None:
    from kame.launch.runner import LaunchRun, RunOptions

    config = LaunchConfig(
        nodes=[Node("p", "a", "plain"), Node("p", "b", "here", machine_name="me"),
               Node("p", "c", "there", machine_name="laptop"), Node("p", "d", "too", machine_name="laptop")],
        machines={"me": Machine("me", "localhost"), "laptop": Machine("laptop", "laptop.invalid")})

    def run(local_only: bool) -> LaunchRun:
        return LaunchRun(config, RunOptions("r1", "http://localhost:11311/", tmp_path, tmp_path, {},
                                            local_only=local_only))

    remote = run(local_only=False).remote_nodes()
    assert {m: [n.name for n in nodes] for m, nodes in remote.items()} == {"laptop": ["there", "too"]}
    assert run(local_only=True).remote_nodes() == {}
    assert [n.name for n in config.nodes if run(False).is_local(n)] == ["plain", "here"]
