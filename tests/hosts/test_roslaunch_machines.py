"""roslaunch's <machine> tags across hosts: roslaunch on robot starts nodes on laptop over SSH.

laptop runs a real OpenSSH server (tests/support/sshd.py) that knows our key; robot's roslaunch
runs with a HOME whose .ssh holds that key and laptop's host key, as a lab's laptop would. The
env-loader on laptop names the host (ROS_HOSTNAME) and hands over to kame's env.sh. A password
login (sshd takes passwords but not for root) is made with a throwaway local user, deleted at
the end of its test.

Needs root and openssh-server (skips without them); every process is stopped by its PID.
"""

from __future__ import annotations

import os
import pwd
import secrets
import shutil
import signal
import subprocess
import sys
import sysconfig
import time
from collections.abc import Iterator
from pathlib import Path
from typing import NamedTuple

import pytest

from ..support import Proc
from ..support.hosts import BIN, Hosts
from ..support.netns import Lan
from ..support.sshd import Sshd, children

pytestmark = pytest.mark.skipif((Lan.unavailable() or Sshd.unavailable()) is not None,
                                reason=Lan.unavailable() or Sshd.unavailable() or "")

ENV_SH = Path(__file__).parents[2] / "src" / "kame" / "shell" / "env.sh"
SSH_PORT = 2222


class Lab:
    def __init__(self, hosts: Hosts) -> None:
        self.hosts = hosts
        self.client_home = hosts.home / "client-home"  # robot's user: ~/.ssh with the key and known_hosts
        self.sshd = Sshd(hosts.host("laptop"), self.client_home, SSH_PORT)
        laptop = hosts.env("laptop")
        self.loader = hosts.home / "laptop-env.sh"
        self.loader.write_text(
            "#!/bin/sh\n"
            f"export ROS_HOSTNAME=laptop ROS_HOME={laptop['ROS_HOME']} ROS_LOG_DIR={laptop['ROS_LOG_DIR']}\n"
            f'exec {ENV_SH} "$@"\n')
        self.loader.chmod(0o755)

    def launch_file(self, name: str, machine: str, nodes: str) -> Path:
        path = self.hosts.home / name
        path.write_text(f"<launch>\n  {machine}\n{nodes}</launch>\n")
        return path

    def machine(self, **attrs: str) -> str:
        """The <machine> tag for laptop; an attribute given as "" is left out."""
        values = {"name": "laptop", "address": "laptop", "ssh-port": str(SSH_PORT), "user": "root",
                  "env-loader": str(self.loader), "timeout": "30", **attrs}
        return "<machine " + " ".join(f'{k}="{v}"' for k, v in values.items() if v) + "/>"

    def roslaunch(self, path: Path, **env: str) -> subprocess.CompletedProcess[str]:
        """roslaunch run on robot to its end (for the launches that fail)."""
        return subprocess.run(self.hosts.host("robot").command([str(BIN / "roslaunch"), str(path)]),
                              env={**self.hosts.env("robot"), "HOME": str(self.client_home), **env},
                              capture_output=True, text=True, timeout=120)

    def wait_sessions_end(self) -> None:
        deadline = time.monotonic() + 20
        while sessions := self.sshd.sessions():
            assert time.monotonic() < deadline, f"processes left on laptop: {sessions}"
            time.sleep(0.05)

    def close(self) -> None:
        self.sshd.close()


@pytest.fixture(scope="module")
def lab(hosts: Hosts) -> Iterator[Lab]:
    lab = Lab(hosts)
    try:
        yield lab
    finally:
        lab.close()


def node_pid(hosts: Hosts, name: str) -> int:
    out = hosts.run("robot", [str(BIN / "python"), "-c", (
        "import sys, xmlrpc.client as x; m = x.ServerProxy('http://robot:11311/'); "
        f"uri = m.lookupNode('/t', '{name}')[2]; print(x.ServerProxy(uri).getPid('/t')[2])")], retry=True)
    return int(out)


def test_a_node_on_laptop_talks_to_one_on_robot_and_ctrl_c_stops_it(lab: Lab) -> None:
    hosts = lab.hosts
    path = lab.launch_file("two_hosts.launch", lab.machine(), (
        '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="talker" output="screen"/>\n'
        '  <node pkg="rospy_tutorials" type="listener.py" name="listener" output="screen"/>\n'))
    launch = Proc(hosts.host("robot").command([str(BIN / "roslaunch"), str(path)]),
                  {**hosts.env("robot"), "HOME": str(lab.client_home)}, cwd=hosts.home)
    try:
        launch.wait_line("remote[laptop-0]: creating ssh connection to laptop:2222, user[root]", timeout=30)
        launch.wait_line("remote[laptop-0]: ssh connection created", timeout=60)
        # data flows from laptop's talker to robot's listener
        launch.wait_line("I heard hello world", timeout=60)
        # the talker's own output (output="screen" on laptop) is brought back to robot's terminal
        deadline = time.monotonic() + 20
        while not any("hello world" in line and "I heard" not in line for line in launch.out):
            assert time.monotonic() < deadline, "".join(launch.out)
            time.sleep(0.05)
        info = hosts.run("robot", [str(BIN / "rosnode"), "info", "/talker"])
        assert "contacting node http://laptop:" in info, info
        talker = node_pid(hosts, "/talker")
        assert talker in lab.sshd.sessions()  # run by laptop's sshd session
    finally:
        out, err = launch.stop(timeout=40)  # SIGINT: Ctrl-C
    assert launch.popen.returncode == 0, out + err
    assert "[laptop-0] killing on exit" in out, out
    assert not Path(f"/proc/{talker}").exists()
    lab.wait_sessions_end()
    assert "/talker" not in hosts.run("robot", [str(BIN / "rosnode"), "list"]).split()


def test_an_unknown_host_is_refused_naming_the_ssh_command_that_adds_it(lab: Lab) -> None:
    stranger = lab.hosts.home / "stranger-home"
    (stranger / ".ssh").mkdir(parents=True, exist_ok=True)
    path = lab.launch_file("unknown.launch", lab.machine(),
                           '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="t1"/>\n')
    done = lab.roslaunch(path, HOME=str(stranger))
    assert done.returncode == 1
    assert ("laptop is not in your SSH known_hosts file.\n\nPlease manually:\n  ssh -p 2222 root@laptop\n\n"
            "then try roslaunching again.") in done.stderr, done.stderr
    assert "RLException: unable to start remote roslaunch child: laptop-0" in done.stderr
    # ROSLAUNCH_SSH_UNKNOWN=1 takes the host; then a wrong password is what fails
    path = lab.launch_file("password.launch", lab.machine(password="not-the-password"),
                           '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="t2"/>\n')
    done = lab.roslaunch(path, HOME=str(stranger), ROSLAUNCH_SSH_UNKNOWN="1")
    assert done.returncode == 1
    assert "Authentication to remote computer[root@laptop:2222] failed." in done.stderr, done.stderr


def test_a_remote_roslaunch_that_does_not_answer_in_time_fails_the_launch_and_is_stopped(lab: Lab) -> None:
    silent = lab.hosts.home / "silent-env.sh"
    silent.write_text("#!/bin/sh\nexec cat >/dev/null\n")  # never answers; ends when its input does
    silent.chmod(0o755)
    path = lab.launch_file("silent.launch", lab.machine(**{"env-loader": str(silent), "timeout": "1.5"}),
                           '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="t3"/>\n')
    done = lab.roslaunch(path)
    assert done.returncode == 1
    assert ("The following roslaunch remote processes failed to register: \n * laptop (timeout 1.5s)"
            in done.stderr), done.stderr
    lab.wait_sessions_end()


def test_the_users_ssh_config_names_the_host_the_user_and_the_key(lab: Lab) -> None:
    """As roslaunch: ~/.ssh/config's HostName, User and IdentityFile for the machine's address."""
    home = lab.hosts.home / "config-home"
    ssh_dir = home / ".ssh"
    ssh_dir.mkdir(parents=True)
    key = ssh_dir / "lab_key"
    key.write_bytes((lab.client_home / ".ssh" / "id_ed25519").read_bytes())
    key.chmod(0o600)
    (ssh_dir / "known_hosts").write_text(lab.sshd.known_hosts_line)
    (ssh_dir / "config").write_text(f"Host the-laptop\n  HostName laptop\n  User root\n  IdentityFile {key}\n")
    path = lab.launch_file("config.launch", lab.machine(address="the-laptop", user=""),
                           '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="t4"/>\n')
    launch = Proc(lab.hosts.host("robot").command([str(BIN / "roslaunch"), str(path)]),
                  {**lab.hosts.env("robot"), "HOME": str(home)}, cwd=lab.hosts.home)
    try:
        launch.wait_line("remote[the-laptop-0]: creating ssh connection to the-laptop:2222\n", timeout=60)
        launch.wait_line("remote[the-laptop-0]: ssh connection created", timeout=60)
        assert node_pid(lab.hosts, "/t4") in lab.sshd.sessions()
    finally:
        out, err = launch.stop(timeout=40)
    assert launch.popen.returncode == 0, out + err
    lab.wait_sessions_end()


def test_a_lost_connection_stops_the_remote_nodes_and_is_reported(lab: Lab) -> None:
    hosts = lab.hosts
    path = lab.launch_file("lost.launch", lab.machine(),
                           '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="t5"/>\n')
    launch = Proc(hosts.host("robot").command([str(BIN / "roslaunch"), str(path)]),
                  {**hosts.env("robot"), "HOME": str(lab.client_home)}, cwd=hosts.home)
    try:
        launch.wait_line("remote[laptop-0]: ssh connection created", timeout=60)
        talker = node_pid(hosts, "/t5")
        # laptop's sshd drops the connection (its process for this connection dies)
        [connection] = [pid for pid in lab.sshd.sessions() if pid in children(lab.sshd.proc.pid)]
        os.kill(connection, signal.SIGKILL)
        launch.wait_line("all processes on machine have died, roslaunch will exit", timeout=30)
        assert launch.popen.wait(30) == 0
    finally:
        out, err = launch.stop(timeout=40)
    assert "[laptop-0] process has died [the connection to laptop was lost]." in err, out + err
    lab.wait_sessions_end()  # the remote roslaunch saw its input end and stopped its talker
    assert not Path(f"/proc/{talker}").exists()


class User(NamedTuple):
    name: str
    password: str
    home: Path


@pytest.fixture
def throwaway_user() -> Iterator[User]:
    """A local user with a password (laptop's sshd reads this machine's /etc/shadow), deleted with
    its home at the end whatever happened; the only change to this machine's accounts."""
    if shutil.which("useradd") is None or shutil.which("chpasswd") is None:
        pytest.skip("useradd and chpasswd (passwd) are not installed")
    name = f"kame{os.getpid()}"
    subprocess.run(["useradd", "--create-home", "--shell", "/bin/sh", name], check=True, capture_output=True)
    try:
        password = secrets.token_urlsafe(16)
        subprocess.run(["chpasswd"], input=f"{name}:{password}\n", check=True, capture_output=True, text=True)
        yield User(name, password, Path(pwd.getpwnam(name).pw_dir))
    finally:
        # --force: even while a process of the user's is left (a failed test's remote node)
        subprocess.run(["userdel", "--remove", "--force", name], capture_output=True)
    with pytest.raises(KeyError):
        pwd.getpwnam(name)


def user_kame(user: User) -> Path:
    """An env-loader in the user's home running kame as the user. This test's interpreter may lie
    where the user cannot go (a home of root's), so the user gets a venv of a python3 it can run
    (of this one's version: the compiled packages are shared) that adds this venv's packages, and
    its own `roslaunch`, the one program a remote machine runs (its nodes run on the python3 first
    on PATH: the user's venv)."""
    version = f"{sys.version_info.major}.{sys.version_info.minor}"
    base = None
    for candidate in (os.path.realpath(sys.executable), "/usr/bin/python3"):
        probe = subprocess.run(["runuser", "-u", user.name, "--", candidate, "-c",
                                "import sys; print(f'{sys.version_info.major}.{sys.version_info.minor}')"],
                               capture_output=True, text=True)
        if probe.returncode == 0 and probe.stdout.strip() == version:
            base = candidate
            break
    if base is None:
        pytest.skip(f"no python{version} that user {user.name} may run")
    venv = user.home / "venv"
    subprocess.run([base, "-m", "venv", "--without-pip", str(venv)], check=True, capture_output=True)
    (venv / "lib" / f"python{version}" / "site-packages" / "kame-test.pth").write_text(
        f"import site; site.addsitedir({sysconfig.get_paths()['purelib']!r})\n")
    ours = (Path(sys.executable).parent / "roslaunch").read_text().split("\n", 1)[1]
    (venv / "bin" / "roslaunch").write_text(f"#!{venv / 'bin' / 'python'}\n{ours}")
    (venv / "bin" / "roslaunch").chmod(0o755)
    loader = user.home / "env.sh"
    loader.write_text("#!/bin/sh\n"
                      f"export ROS_HOSTNAME=laptop ROS_HOME={user.home / '.ros'} ROS_LOG_DIR={user.home / 'log'} "
                      f"KAME_PYTHON={venv / 'bin' / 'python'}\n"
                      f'exec {ENV_SH} "$@"\n')
    loader.chmod(0o755)
    subprocess.run(["chown", "-R", f"{user.name}:", str(user.home)], check=True, capture_output=True)
    return loader


def test_a_machine_with_a_password_logs_in_with_it_and_runs_the_node_as_that_user(lab: Lab,
                                                                                   throwaway_user: User) -> None:
    hosts, user = lab.hosts, throwaway_user
    loader = user_kame(user)
    path = lab.launch_file("password-ok.launch",
                           lab.machine(user=user.name, password=user.password, **{"env-loader": str(loader)}),
                           '  <node machine="laptop" pkg="rospy_tutorials" type="talker.py" name="t6"/>\n'
                           '  <node pkg="rospy_tutorials" type="listener.py" name="l6" output="screen"/>\n')
    launch = Proc(hosts.host("robot").command([str(BIN / "roslaunch"), str(path)]),
                  {**hosts.env("robot"), "HOME": str(lab.client_home)}, cwd=hosts.home)
    try:
        launch.wait_line(f"remote[laptop-0]: creating ssh connection to laptop:2222, user[{user.name}]", timeout=30)
        launch.wait_line("remote[laptop-0]: ssh connection created", timeout=60)
        launch.wait_line("I heard hello world", timeout=60)
        talker = node_pid(hosts, "/t6")
        assert talker in lab.sshd.sessions()
        assert os.stat(f"/proc/{talker}").st_uid == pwd.getpwnam(user.name).pw_uid  # run as the user logged in
    finally:
        out, err = launch.stop(timeout=40)
    assert launch.popen.returncode == 0, out + err
    # with a password, no key is offered (the client's HOME has one sshd takes): sshd took the password
    assert any(f"Accepted password for {user.name} " in line for line in lab.sshd.proc.err), "".join(lab.sshd.proc.err)
    lab.wait_sessions_end()
    assert not Path(f"/proc/{talker}").exists()
