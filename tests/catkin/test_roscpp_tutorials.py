"""roscpp_tutorials as the courses run it, against kame's roscore: `rosls roscpp_tutorials`,
`rosrun roscpp_tutorials talker` / `listener`, add_two_ints_server and _client, and
`roslaunch roscpp_tutorials talker_listener.launch`; both the programs built from kame's C++
sources (where roscpp is installed; built once per source version into a shared cache) and
kame's Python ports (KAME_CPP_TUTORIALS=port), whose lines must read the same."""

from __future__ import annotations

import re
import subprocess
import sys
import tempfile
from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.catkin.toolchain import Missing, find_toolchain
from kame.roscpp_tutorials.build import program
from tests.shell.shell_env import bash, clean_env, complete
from tests.support import Proc, free_port, wait_for_master
from tests.turtlesim.sim import wait_until

BIN = Path(sys.executable).parent
LINE = re.compile(r"^\[ (INFO|ERROR)\] \[\d+\.\d{9}\]: (.*)$")
ANSI = re.compile(r"\x1b\[[0-9;]*m")
# the `kind` fixture's first build compiles twelve programs with g++ (30-80 s quiet on 2 cores, minutes
# beside a second suite): pytest-timeout's 120 s counts fixture set-up
pytestmark = pytest.mark.timeout(900)
CACHE = Path(tempfile.gettempdir()) / "kame-test-cache"  # shared by runs: the programs build once per source


@pytest.fixture(scope="module")
def master(tmp_path_factory: pytest.TempPathFactory) -> Iterator[tuple[str, dict[str, str]]]:
    home = tmp_path_factory.mktemp("roscpp_tutorials")
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = clean_env(home, uri)
    env["PATH"] = f"{BIN}:{env['PATH']}"
    env["XDG_CACHE_HOME"] = str(CACHE)
    core = Proc([str(BIN / "roscore"), "-p", str(port)], env)
    try:
        wait_for_master(uri, proc=core)
        yield uri, env
    finally:
        core.stop()


@pytest.fixture(scope="module", params=["cpp", "port"])
def kind(request: pytest.FixtureRequest, master: tuple[str, dict[str, str]]) -> str:
    """Which programs run: the compiled ones (built here first) or the ports."""
    if request.param == "cpp":
        if isinstance(find_toolchain(master[1]), Missing):
            pytest.skip("no C++ toolchain or roscpp here: the ports run (tests/catkin/test_cpp_courses.py "
                        "says whether that may be)")
        assert program("talker", master[1]) is not None, f"the build failed: see {CACHE}/kame/*/build.log"
    return str(request.param)


def env_for(master: tuple[str, dict[str, str]], kind: str) -> dict[str, str]:
    return {**master[1], "KAME_CPP_TUTORIALS": kind}


def rosrun(env: dict[str, str], *args: str) -> Proc:
    """rosrun as a user types it, line-buffered (stdbuf) as on a terminal."""
    return Proc(["stdbuf", "-oL", str(BIN / "rosrun"), "roscpp_tutorials", *args], env)


def text(line: str, severity: str = "INFO") -> str:
    """The text of a roscpp console line, its format checked."""
    found = LINE.match(ANSI.sub("", line).rstrip("\n"))
    assert found and found.group(1) == severity, repr(line)
    return found.group(2)


def test_rosls_shows_what_the_course_shows(master: tuple[str, dict[str, str]]) -> None:
    out = bash("rosls roscpp_tutorials/", master[1])
    assert out.stdout.split() == ["cmake", "launch", "package.xml", "srv"], out.stderr
    out = bash("rosls roscpp_tutorials/launch; rossrv show roscpp_tutorials/TwoInts", master[1])
    assert out.stdout.splitlines() == ["talker_listener.launch", "int64 a", "int64 b", "---", "int64 sum", ""]
    assert complete(master[1], "rosrun", "roscpp_tutorials", "ta") == ["talker"]
    assert complete(master[1], "rosrun", "roscpp_tutorials", "add_two") == [
        "add_two_ints_client", "add_two_ints_server", "add_two_ints_server_class"]


def test_talker_and_listener(master: tuple[str, dict[str, str]], kind: str) -> None:
    env = env_for(master, kind)
    talker = rosrun(env, "talker")
    listener = rosrun(env, "listener")
    try:
        assert text(talker.wait_line("hello world 0")) == "hello world 0"
        assert text(talker.wait_line("hello world 1")) == "hello world 1"
        heard = text(listener.wait_line("I heard: ["))
        assert re.fullmatch(r"I heard: \[hello world \d+\]", heard), heard
    finally:
        listener.stop()
        talker.stop()


def test_add_two_ints(master: tuple[str, dict[str, str]], kind: str) -> None:
    env = env_for(master, kind)
    server = rosrun(env, "add_two_ints_server")
    try:
        # the client calls once, without waiting for the service (as the course's): it must be there
        wait_until(lambda: "/add_two_ints" in subprocess.run([str(BIN / "rosservice"), "list"], env=env, timeout=30,
                                                             capture_output=True, text=True).stdout,
                   timeout=60, what="add_two_ints to be advertised")
        client = subprocess.run(["stdbuf", "-oL", str(BIN / "rosrun"), "roscpp_tutorials", "add_two_ints_client",
                                 "3", "4"], env=env, capture_output=True, text=True, timeout=30)
        assert client.returncode == 0, client.stderr
        assert [text(line) for line in client.stdout.splitlines()] == ["Sum: 7"]
        assert text(server.wait_line("request: x=3")) == "request: x=3, y=4"
        assert text(server.wait_line("sending back")) == "  sending back response: [7]"
        usage = subprocess.run([str(BIN / "rosrun"), "roscpp_tutorials", "add_two_ints_client", "3"], env=env,
                               capture_output=True, text=True, timeout=30)
        assert usage.returncode == 1
        assert [text(line) for line in usage.stdout.splitlines()] == ["usage: add_two_ints_client X Y"]
    finally:
        server.stop()


def test_roslaunch_talker_listener(master: tuple[str, dict[str, str]], kind: str) -> None:
    env = env_for(master, kind)
    launch = Proc(["stdbuf", "-oL", str(BIN / "roslaunch"), "roscpp_tutorials", "talker_listener.launch"], env)
    try:
        heard = launch.wait_line("I heard: [hello world ", timeout=30)
        assert re.fullmatch(r"I heard: \[hello world \d+\]", text(heard))
    finally:
        launch.stop(timeout=15)


def test_node_handle_namespaces_and_listener_multiple(master: tuple[str, dict[str, str]], kind: str) -> None:
    env = env_for(master, kind)
    names = subprocess.run(["stdbuf", "-oL", str(BIN / "rosrun"), "roscpp_tutorials", "node_handle_namespaces",
                            "__ns:=/robot"], env=env, capture_output=True, text=True, timeout=30)
    assert [text(line) for line in names.stdout.splitlines()] == [
        "/robot/level1/a", "/robot/level1/level2/a", "/robot/node_handle_namespaces/a"], names.stderr
    talker = rosrun(env, "babbler", "babble:=chatter")
    listener = rosrun(env, "listener_multiple")
    try:
        heard = [text(listener.wait_line(f"chatter{n}: [hello world ")) for n in (1, 2, 3, 4)]
        assert all(re.fullmatch(rf"chatter{n}: \[hello world \d+\]", h) for n, h in zip((1, 2, 3, 4), heard,
                                                                                          strict=True)), heard
    finally:
        listener.stop()
        talker.stop()
