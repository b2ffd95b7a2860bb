"""The C++ half of the courses, built by kame's catkin_make with the system's CMake, catkin and
roscpp, and run with rosrun against kame's roscore: hello, the publisher driving kame's
turtlesim, the subscriber printing its pose (turtlesim/Pose.h: headers kame makes, Debian
has none), a talker/listener pair, and a C++ package's own message read by a rospy node in a
Python package that depends on it (a mixed workspace, built in dependency order), a C++
dynamic_reconfigure server (the .cfg run by the system's generator in the same CMake build)
reconfigured with kame's dynparam, and a program building action goals from the headers of
kame's actions the system lacks (actionlib_tutorials' Fibonacci, nav_msgs' GetMap).

The workspace (tests/catkin/course_ws) is built once for the module, and one roscore serves
every test; every process is stopped by its PID."""

from __future__ import annotations

import re
import shutil
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path

import pytest

from kame.catkin.toolchain import Missing, find_toolchain
from tests.shell.shell_env import clean_env
from tests.support import Proc, free_port, wait_for_master

# the module's workspace fixture compiles the course packages with g++ (cold, minutes on a 2-core
# machine beside a second suite): pytest-timeout's 120 s counts a test's fixture set-up, and ran
# out under that load before any test began
pytestmark = pytest.mark.timeout(900)

BIN = Path(sys.executable).parent
COURSE = Path(__file__).resolve().parent / "course_ws"
CONSOLE_LINE = re.compile(r"^\[ INFO\] \[\d+\.\d{9}\]: (.*)$")
ANSI = re.compile(r"\x1b\[[0-9;]*m")


def _platform_has_roscpp() -> bool:
    """Whether this platform packages roscpp at all (then the C++ tests must run, not skip)."""
    if shutil.which("apt-cache") is None:
        return False
    shown = subprocess.run(["apt-cache", "show", "libroscpp-dev"], capture_output=True, text=True)
    return shown.returncode == 0 and "Package: libroscpp-dev" in shown.stdout


def user_env(home: Path, master: str | None = None) -> dict[str, str]:
    env = clean_env(home, master)
    env["ROS_DISTRO"] = "noetic"
    env["PATH"] = f"{BIN}:{env['PATH']}"
    return env


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> tuple[Path, subprocess.CompletedProcess[str]]:
    toolchain = find_toolchain(user_env(tmp_path_factory.mktemp("probe")))
    if isinstance(toolchain, Missing):
        if not _platform_has_roscpp():
            pytest.skip("this platform has no roscpp package (no libroscpp-dev): the C++ courses cannot be built")
        pytest.fail(f"roscpp's packages exist here but are not installed ({', '.join(toolchain.pieces)}): "
                    "run scripts/install-ros-peers.sh")
    home = tmp_path_factory.mktemp("cpp_courses")
    ws = home / "catkin_ws"
    shutil.copytree(COURSE, ws / "src")
    result = subprocess.run(["catkin_make", "--no-color"], cwd=ws, env=user_env(home), capture_output=True,
                            text=True, timeout=600)
    return ws, result


@pytest.fixture(scope="module")
def master(workspace: tuple[Path, subprocess.CompletedProcess[str]]) -> Iterator[tuple[str, dict[str, str]]]:
    ws, _ = workspace
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = user_env(ws.parent, uri)
    core = Proc([str(BIN / "roscore"), "-p", str(port)], env)
    try:
        wait_for_master(uri, proc=core)
        yield uri, env
    finally:
        core.stop()


def rosrun(ws: Path, env: dict[str, str], *args: str) -> Proc:
    """`source devel/setup.bash && rosrun ...` as the course types it; C++ nodes line-buffered
    (stdbuf), as on a terminal, so their lines reach the test as they are printed."""
    line = " ".join(args)
    return Proc(["bash", "-c", f"source {ws}/devel/setup.bash && exec stdbuf -oL rosrun {line}"], env)


def info(line: str) -> str:
    """The text of a roscpp INFO line, checking its format: `[ INFO] [secs.nsecs]: text`."""
    found = CONSOLE_LINE.match(ANSI.sub("", line).rstrip("\n"))
    assert found, line
    return found.group(1)


def test_catkin_make_builds_the_course_workspace(workspace: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    ws, result = workspace
    assert result.returncode == 0, result.stdout[-3000:] + result.stderr[-3000:]
    out = result.stdout
    assert f'Creating symlink "{ws}/src/CMakeLists.txt" pointing to "' in out
    assert (ws / "src" / "CMakeLists.txt").resolve().name == "toplevel.cmake"
    assert (f'#### Running command: "cmake {ws}/src -DCATKIN_DEVEL_PREFIX={ws}/devel '
            f'-DCMAKE_INSTALL_PREFIX={ws}/install -G Unix Makefiles" in "{ws}/build"') in out
    assert re.search(r'#### Running command: "make -j\d+ -l\d+" in "', out)
    assert "-- ~~  - cpp_msgs_demo" in out and "-- ==> add_subdirectory(hello)" in out
    for package, program in (("hello", "hello"), ("publisher", "publisher"), ("subscriber", "subscriber"),
                             ("cpp_chatter", "talker"), ("cpp_chatter", "listener"),
                             ("cpp_msgs_demo", "reading_pub"), ("action_goals", "fibonacci_goal")):
        assert f"Linking CXX executable {ws}/devel/lib/{package}/{program}" in out
        assert (ws / "devel" / "lib" / package / program).is_file()
    # the mixed workspace: the Python package that depends on the C++ one comes after it
    assert out.index("Built target reading_pub") < out.index("[100%] Built target py_reader")
    assert (ws / "devel" / "include" / "cpp_msgs_demo" / "Reading.h").is_file()
    assert "struct Reading_" in (ws / "devel" / "include" / "cpp_msgs_demo" / "Reading.h").read_text()
    assert (ws / "devel" / "include" / "reconfigure_server" / "SpeedConfig.h").is_file()
    for name in ("env.sh", "_setup_util.py", "setup.bash", ".catkin"):
        assert (ws / "devel" / name).is_file(), name
    assert (ws / "devel" / "lib" / "py_reader" / "reader.py").is_file()


def test_pkg_makes_one_package_with_nothing_reconfigured(
        workspace: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    ws, _ = workspace
    (ws / "src" / "hello" / "hello.cpp").touch()
    result = subprocess.run(["catkin_make", "--no-color", "--pkg", "hello"], cwd=ws, env=user_env(ws.parent),
                            capture_output=True, text=True, timeout=300)
    assert result.returncode == 0, result.stderr
    assert f'#### Running command: "make cmake_check_build_system" in "{ws}/build"' in result.stdout
    assert re.search(rf'#### Running command: "make -j\d+ -l\d+" in "{ws}/build/hello"', result.stdout)
    assert f"Linking CXX executable {ws}/devel/lib/hello/hello" in result.stdout
    assert result.stdout.count("Linking CXX executable") == 1
    assert "kame: Python packages" not in result.stdout


def test_devel_setup_gives_catkins_environment(workspace: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    ws, _ = workspace
    out = subprocess.run(["bash", "-c", f"source {ws}/devel/setup.bash && echo $CMAKE_PREFIX_PATH && "
                          "echo $LD_LIBRARY_PATH && echo $PKG_CONFIG_PATH && pkg-config --modversion hello && "
                          "echo $ROSLISP_PACKAGE_DIRECTORIES"],
                         env=user_env(ws.parent), capture_output=True, text=True, timeout=60)
    prefix, libraries, pkg_config, version, lisp = out.stdout.splitlines()
    assert prefix.split(":")[0] == f"{ws}/devel"
    assert libraries.split(":")[0] == f"{ws}/devel/lib"
    assert pkg_config.split(":")[0] == f"{ws}/devel/lib/pkgconfig"
    assert version == "0.0.1", out.stderr
    assert lisp == f"{ws}/devel/share/common-lisp"


def test_action_headers_kame_makes_carry_the_messages_md5sums(
        workspace: tuple[Path, subprocess.CompletedProcess[str]]) -> None:
    ws, _ = workspace
    env = user_env(ws.parent)
    goals = subprocess.run([str(ws / "devel" / "lib" / "action_goals" / "fibonacci_goal")], env=env,
                           capture_output=True, text=True, timeout=30)
    assert goals.returncode == 0, goals.stderr
    md5 = [subprocess.run([str(BIN / "rosmsg"), "md5", name], env=env, capture_output=True, text=True,
                          timeout=30).stdout.strip() for name in ("actionlib_tutorials/FibonacciAction",
                                                                  "nav_msgs/GetMapAction")]
    assert goals.stdout.splitlines() == ["actionlib_tutorials/FibonacciActionGoal 20", md5[0],
                                         "nav_msgs/GetMapActionGoal", md5[1]]
    generated = ws / "build" / "kame_msgs" / "share" / "actionlib_tutorials" / "msg"
    assert sorted(p.name for p in generated.glob("Fibonacci*.msg")) == sorted(
        f"Fibonacci{part}.msg" for part in ("Action", "ActionGoal", "ActionResult", "ActionFeedback", "Goal",
                                            "Result", "Feedback"))


def test_hello(workspace: tuple[Path, subprocess.CompletedProcess[str]], master: tuple[str, dict[str, str]]) -> None:
    ws, _ = workspace
    hello = rosrun(ws, master[1], "hello", "hello")
    try:
        assert hello.popen.wait(30) == 0
    finally:
        out, err = hello.stop()
    assert [info(line) for line in out.splitlines()] == ["Hello, ROS!"], err


def test_publisher_drives_turtlesim_and_subscriber_prints_its_pose(
        workspace: tuple[Path, subprocess.CompletedProcess[str]], master: tuple[str, dict[str, str]]) -> None:
    ws, env = workspace[0], master[1]
    procs = [rosrun(ws, env, "turtlesim", "turtlesim_node", "--headless")]
    try:
        procs[0].wait_line("runs without a window")
        procs.append(rosrun(ws, env, "subscriber", "subscriber"))
        assert info(procs[1].wait_line("position=(5.54,5.54) direction=0.00")) == \
            "position=(5.54,5.54) direction=0.00"
        procs.append(rosrun(ws, env, "publisher", "publisher"))
        assert info(procs[2].wait_line("Sending velocity command")) == \
            "Sending velocity command: linear=1 angular=0.5"
        moved = procs[1].wait_line("direction=0.1", timeout=20)  # turning at 0.5 rad/s, going forward
        x, y = re.fullmatch(r"position=\(([\d.]+),([\d.]+)\) direction=0\.1\d", info(moved)).groups()  # type: ignore[union-attr]
        assert float(x) > 5.54 and float(y) >= 5.54, moved
    finally:
        for proc in reversed(procs):
            proc.stop()


def test_talker_and_listener(workspace: tuple[Path, subprocess.CompletedProcess[str]],
                             master: tuple[str, dict[str, str]]) -> None:
    ws, env = workspace[0], master[1]
    listener = rosrun(ws, env, "cpp_chatter", "listener")
    talker = rosrun(ws, env, "cpp_chatter", "talker", "_rate:=20")
    try:
        said = info(talker.wait_line("hello world 0"))
        assert said == "hello world 0"
        heard = info(listener.wait_line("I heard: [hello world "))
        assert re.fullmatch(r"I heard: \[hello world \d+\]", heard)
    finally:
        talker.stop()
        listener.stop()


def test_roslaunch_runs_the_workspace_programs(workspace: tuple[Path, subprocess.CompletedProcess[str]],
                                               master: tuple[str, dict[str, str]]) -> None:
    ws, env = workspace[0], master[1]
    launch = Proc(["bash", "-c", f"source {ws}/devel/setup.bash && exec stdbuf -oL roslaunch cpp_chatter "
                   "chatter.launch"], env)
    try:
        heard = info(launch.wait_line("I heard: [hello world ", timeout=30))
        assert re.fullmatch(r"I heard: \[hello world \d+\]", heard)
    finally:
        launch.stop(timeout=15)


def test_own_message_of_a_cpp_package_read_by_rospy(workspace: tuple[Path, subprocess.CompletedProcess[str]],
                                                     master: tuple[str, dict[str, str]]) -> None:
    ws, env = workspace[0], master[1]
    reader = Proc(["bash", "-c", f"source {ws}/devel/setup.bash && exec rosrun py_reader reader.py"], env)
    publisher = rosrun(ws, env, "cpp_msgs_demo", "reading_pub")
    try:
        reader.wait_line("ready")
        line = reader.wait_line("thermo ")
        n = int(float(line.split()[1]) - 20.5)
        assert line.strip() == f"thermo {20.5 + n:.1f} {[n, 2 * n, 3 * n]}"
    finally:
        publisher.stop()
        reader.stop()


def test_catkin_build_builds_a_cpp_package_as_catkin_tools(tmp_path: Path) -> None:
    if isinstance(find_toolchain(user_env(tmp_path)), Missing):
        pytest.skip("no C++ toolchain or roscpp here (the module's fixture says whether that may be)")
    ws = tmp_path / "ws"
    (ws / "src").mkdir(parents=True)
    shutil.copytree(COURSE / "hello", ws / "src" / "hello")
    result = subprocess.run(["catkin", "build"], cwd=ws, env=user_env(tmp_path), capture_output=True, text=True,
                            timeout=300)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "Starting  >>> hello" in result.stdout and "Finished  <<< hello" in result.stdout
    assert "[build] Summary: All 1 packages succeeded!" in result.stdout
    assert (ws / "devel" / "lib" / "hello" / "hello").is_file()
    assert "Linking CXX executable" in (ws / "logs" / "hello" / "build.log").read_text()


def test_cpp_dynamic_reconfigure_server(workspace: tuple[Path, subprocess.CompletedProcess[str]],
                                        master: tuple[str, dict[str, str]]) -> None:
    ws, env = workspace[0], master[1]
    server = rosrun(ws, env, "reconfigure_server", "server")
    try:
        assert info(server.wait_line("speed=1.0")) == "Reconfigure request: speed=1.0 who=turtle"
        done = subprocess.run(["bash", "-c", f"source {ws}/devel/setup.bash && "
                               "rosrun dynamic_reconfigure dynparam set /speed_server speed 2.5"],
                              env=env, capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr
        assert info(server.wait_line("speed=2.5")) == "Reconfigure request: speed=2.5 who=turtle"
    finally:
        server.stop()
