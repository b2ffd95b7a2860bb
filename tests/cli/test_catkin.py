"""Workspaces as the ROS tutorials build them: catkin_create_pkg, catkin_make, catkin build,
the devel space's setup.bash, and a talker/listener package with its own msg and srv run
through rosrun against a kame roscore (every process stopped by its PID)."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import textwrap
from pathlib import Path

import pytest

from kame.catkin.toolchain import Missing, find_toolchain
from tests.shell.shell_env import bash, clean_env
from tests.support import SYSTEM_PYTHON, Proc, free_port, wait_for_master

BIN = Path(sys.executable).parent

TALKER = '''#!/usr/bin/env python
import rospy
from beginner_tutorials.msg import Num

def talker():
    pub = rospy.Publisher('chatter', Num, queue_size=10)
    rospy.init_node('talker', anonymous=True)
    rate = rospy.Rate(20)
    n = 0
    while not rospy.is_shutdown():
        n += 1
        rospy.loginfo("num %s", n)
        pub.publish(Num(num=n))
        rate.sleep()

if __name__ == '__main__':
    try:
        talker()
    except rospy.ROSInterruptException:
        pass
'''

LISTENER = '''#!/usr/bin/env python
import rospy
from beginner_tutorials.msg import Num
from beginner_tutorials.srv import AddTwoInts, AddTwoIntsResponse

def callback(data):
    print(rospy.get_caller_id() + " I heard %d" % data.num, flush=True)

def add(req):
    return AddTwoIntsResponse(req.a + req.b)

rospy.init_node('listener', anonymous=True)
rospy.Subscriber('chatter', Num, callback)
rospy.Service('add_two_ints', AddTwoInts, add)
print("ready", flush=True)
rospy.spin()
'''


def run(cmd: list[str], cwd: Path, env: dict[str, str]) -> subprocess.CompletedProcess[str]:
    return subprocess.run(cmd, cwd=cwd, env=env, capture_output=True, text=True, timeout=60)


def user_env(home: Path, master: str | None = None) -> dict[str, str]:
    """After `source setup.bash` from kame: ROS_DISTRO set, the tools on PATH."""
    env = clean_env(home, master)
    env["ROS_DISTRO"] = "noetic"
    env["PATH"] = f"{BIN}:{env['PATH']}"
    return env


def make_workspace(tmp_path: Path) -> tuple[Path, dict[str, str]]:
    ws = tmp_path / "catkin_ws"
    (ws / "src").mkdir(parents=True)
    return ws, user_env(tmp_path)


def create_beginner_tutorials(ws: Path, env: dict[str, str]) -> Path:
    result = run(["catkin_create_pkg", "beginner_tutorials", "std_msgs", "rospy", "roscpp"], ws / "src", env)
    assert result.returncode == 0, result.stderr
    pkg = ws / "src" / "beginner_tutorials"
    (pkg / "msg").mkdir()
    (pkg / "msg" / "Num.msg").write_text("int64 num\n")
    (pkg / "srv").mkdir()
    (pkg / "srv" / "AddTwoInts.srv").write_text("int64 a\nint64 b\n---\nint64 sum\n")
    (pkg / "scripts").mkdir()
    for name, text in (("talker.py", TALKER), ("listener.py", LISTENER)):
        (pkg / "scripts" / name).write_text(text)
        (pkg / "scripts" / name).chmod(0o755)
    return pkg


def test_catkin_create_pkg_writes_what_ros_writes(tmp_path: Path) -> None:
    env = user_env(tmp_path)
    result = run(["catkin_create_pkg", "beginner_tutorials", "std_msgs", "rospy", "roscpp", "-D", "My tutorials",
                  "-V", "1.2.3", "-l", "BSD", "-a", "Jane Doe"], tmp_path, env)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines() == [
        "Created file beginner_tutorials/package.xml",
        "Created file beginner_tutorials/CMakeLists.txt",
        "Created folder beginner_tutorials/include/beginner_tutorials",
        "Created folder beginner_tutorials/src",
        f"Successfully created files in {tmp_path}/beginner_tutorials. Please adjust the values in package.xml.",
    ]
    xml = (tmp_path / "beginner_tutorials" / "package.xml").read_text()
    assert '<package format="2">' in xml
    assert "<version>1.2.3</version>" in xml and "<description>My tutorials</description>" in xml
    assert "<license>BSD</license>" in xml and "<author>Jane Doe</author>" in xml.replace("<author >", "<author>")
    for dep in ("roscpp", "rospy", "std_msgs"):
        for tag in ("build_depend", "build_export_depend", "exec_depend"):
            assert f"<{tag}>{dep}</{tag}>" in xml
    cmake = (tmp_path / "beginner_tutorials" / "CMakeLists.txt").read_text()
    assert "project(beginner_tutorials)" in cmake
    assert "find_package(catkin REQUIRED COMPONENTS\n  roscpp\n  rospy\n  std_msgs\n)" in cmake
    if Path("/usr/bin/catkin_create_pkg").exists() and Path(SYSTEM_PYTHON).exists():
        real = tmp_path / "real"
        real.mkdir()
        run([SYSTEM_PYTHON, "/usr/bin/catkin_create_pkg", "beginner_tutorials", "std_msgs", "rospy", "roscpp", "-D",
             "My tutorials", "-V", "1.2.3", "-l", "BSD", "-a", "Jane Doe"], real, env)
        for name in ("package.xml", "CMakeLists.txt"):
            ours = (tmp_path / "beginner_tutorials" / name).read_text()
            assert (real / "beginner_tutorials" / name).read_text() == ours


def test_empty_workspace(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    result = run(["catkin_make"], ws, env)
    assert result.returncode == 0, result.stderr
    assert result.stdout.splitlines()[:5] == [f"Base path: {ws}", f"Source space: {ws}/src", f"Build space: {ws}/build",
                                              f"Devel space: {ws}/devel", f"Install space: {ws}/install"]
    assert "-- ~~  traversing 0 packages in topological order:" in result.stdout
    for name in ("setup.bash", "setup.sh", "setup.zsh", ".catkin"):
        assert (ws / "devel" / name).is_file()
    assert (ws / "build").is_dir() and (ws / ".catkin_workspace").is_file()
    out = bash(f"source {ws}/devel/setup.bash && echo $ROS_PACKAGE_PATH && echo $CMAKE_PREFIX_PATH && "
               f"echo $ROS_DISTRO && roscd && pwd", env)
    lines = out.stdout.splitlines()
    assert lines[0].split(":")[0] == f"{ws}/src"
    assert lines[1:] == [f"{ws}/devel", "noetic", f"{ws}/devel"]


def test_catkin_make_errors(tmp_path: Path) -> None:
    env = user_env(tmp_path)
    result = run(["catkin_make"], tmp_path, env)
    assert result.returncode == 1
    assert f'The specified source space "{tmp_path}/src" does not exist' in result.stderr
    assert "Traceback" not in result.stderr


def test_python_package_with_msg_srv_setup_py_and_scripts(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    pkg = create_beginner_tutorials(ws, env)
    (pkg / "src" / "beginner_tutorials").mkdir(parents=True)
    (pkg / "src" / "beginner_tutorials" / "__init__.py").write_text("VALUE = 42\n")
    (pkg / "src" / "beginner_tutorials" / "helper.py").write_text("def f():\n    return 'helped'\n")
    (pkg / "setup.py").write_text(textwrap.dedent("""\
        from setuptools import setup
        from catkin_pkg.python_setup import generate_distutils_setup

        setup(**generate_distutils_setup(packages=['beginner_tutorials'], package_dir={'': 'src'}))
        """))
    cmake = pkg / "CMakeLists.txt"
    cmake.write_text(cmake.read_text().replace("# catkin_python_setup()", "catkin_python_setup()")
                     + "catkin_install_python(PROGRAMS scripts/talker.py\n"
                     "  DESTINATION ${CATKIN_PACKAGE_BIN_DESTINATION})\n")
    result = run(["catkin_make"], ws, env)
    assert result.returncode == 0, result.stdout + result.stderr
    assert "-- +++ processing catkin package: 'beginner_tutorials'" in result.stdout
    assert "[100%] Built target beginner_tutorials" in result.stdout
    assert (ws / "devel" / "lib" / "beginner_tutorials" / "talker.py").is_file()
    check = ("from beginner_tutorials.msg import Num; from beginner_tutorials.srv import AddTwoInts; "
             "import beginner_tutorials, beginner_tutorials.helper as h; "
             "print(Num(num=5).num, AddTwoInts._type, beginner_tutorials.VALUE, h.f())")
    out = bash(f"source {ws}/devel/setup.bash && echo $PYTHONPATH && python -c '{check}' && "
               "roscd beginner_tutorials && pwd", env, cwd=tmp_path)
    assert out.returncode == 0, out.stderr
    assert out.stdout.splitlines() == [f"{ws}/devel/lib/python3/dist-packages",
                                       "5 beginner_tutorials/AddTwoInts 42 helped", f"{pkg}"]


def test_cpp_package_without_a_toolchain_says_what_to_install_and_others_build(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    create_beginner_tutorials(ws, env)
    run(["catkin_create_pkg", "cpp_tutorials", "roscpp"], ws / "src", env)
    cmake = ws / "src" / "cpp_tutorials" / "CMakeLists.txt"
    cmake.write_text(cmake.read_text() + "add_executable(talker src/talker.cpp)\n"
                     "target_link_libraries(talker ${catkin_LIBRARIES})\n")
    bare = {**env, "PATH": str(BIN)}  # no cmake, make or compiler on PATH
    result = run(["catkin_make", "--no-color"], ws, bare)
    assert result.returncode == 1
    assert "Traceback" not in result.stderr
    assert "kame: package 'cpp_tutorials' needs a C++ build (targets: talker)" in result.stderr
    assert "The C++ packages need cmake, make, c++, which this machine lacks." in result.stderr
    if "debian" in Path("/etc/os-release").read_text().lower():
        assert "  sudo apt-get install cmake make g++\n" in result.stderr
    assert "Built target beginner_tutorials" in result.stdout
    assert (ws / "devel" / "setup.bash").is_file()

    build = run(["catkin", "build"], ws, bare)
    assert build.returncode == 1
    assert "Finished  <<< beginner_tutorials" in build.stdout
    assert "Failed     << cpp_tutorials" in build.stdout
    assert "[build] Summary: 1 of 2 packages succeeded." in build.stdout
    assert "needs a C++ build (targets: talker)" in build.stderr and "Traceback" not in build.stderr


def test_cpp_package_with_a_missing_source_fails_in_cmake_as_catkin(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    run(["catkin_create_pkg", "cpp_tutorials", "roscpp"], ws / "src", env)
    cmake = ws / "src" / "cpp_tutorials" / "CMakeLists.txt"
    cmake.write_text(cmake.read_text() + "add_executable(talker src/talker.cpp)\n")
    if isinstance(find_toolchain(env), Missing):
        pytest.skip("no C++ toolchain or roscpp here: tests/catkin's fixture says whether that may be")
    result = run(["catkin_make", "--no-color"], ws, env)
    assert result.returncode == 1
    assert "Cannot find source file:\n\n    src/talker.cpp" in result.stderr
    assert result.stderr.endswith('Invoking "cmake" failed\n')


def test_whitelist_is_remembered_until_cleared(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    for name in ("pkg_a", "pkg_b", "pkg_c"):
        run(["catkin_create_pkg", name, "rospy"], ws / "src", env)

    def built(*args: str) -> list[str]:
        result = run(["catkin_make", *args], ws, env)
        assert result.returncode == 0, result.stderr
        return [line[len("-- ~~  - "):] for line in result.stdout.splitlines() if line.startswith("-- ~~  - ")]

    assert built('-DCATKIN_WHITELIST_PACKAGES=pkg_a;pkg_c') == ["pkg_a", "pkg_c"]
    assert built() == ["pkg_a", "pkg_c"]
    assert built("-DCATKIN_WHITELIST_PACKAGES=") == ["pkg_a", "pkg_b", "pkg_c"]
    assert built("-DCATKIN_BLACKLIST_PACKAGES=pkg_b") == ["pkg_a", "pkg_c"]
    assert built("-DCATKIN_BLACKLIST_PACKAGES=", "--only-pkg-with-deps", "pkg_b") == ["pkg_b"]


def test_catkin_build_and_clean(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    create_beginner_tutorials(ws, env)
    result = run(["catkin", "build"], ws, env)
    assert result.returncode == 0, result.stderr
    assert "[build] Summary: All 1 packages succeeded!" in result.stdout
    out = bash(f"source {ws}/devel/setup.bash && roscd beginner_tutorials && pwd", env)
    assert out.stdout.strip() == str(ws / "src" / "beginner_tutorials")
    listed = run(["catkin", "list"], ws / "src" / "beginner_tutorials", env)
    assert listed.stdout == "- beginner_tutorials\n"
    clean = run(["catkin", "clean", "-y"], ws, env)
    assert clean.returncode == 0 and not (ws / "devel").exists() and not (ws / "build").exists()


def test_overlay_sourcing_replaces_the_previous_workspace(tmp_path: Path) -> None:
    env = user_env(tmp_path)
    for name in ("ws1", "ws2"):
        (tmp_path / name / "src").mkdir(parents=True)
        assert run(["catkin_make"], tmp_path / name, env).returncode == 0
    out = bash(f"source {tmp_path}/ws1/devel/setup.bash; source {tmp_path}/ws2/devel/setup.bash; "
               "echo $ROS_PACKAGE_PATH; echo $CMAKE_PREFIX_PATH", env)
    rpp, cpp = out.stdout.splitlines()
    assert rpp.split(":")[0] == f"{tmp_path}/ws2/src" and f"{tmp_path}/ws1/src" not in rpp
    assert cpp == f"{tmp_path}/ws2/devel"


def test_tutorial_flow_talker_listener_through_rosrun(tmp_path: Path) -> None:
    """The wiki flow: create the package, add msg/srv and scripts, catkin_make, source, rosrun."""
    ws, env = make_workspace(tmp_path)
    create_beginner_tutorials(ws, env)
    assert run(["catkin_make"], ws, env).returncode == 0
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = user_env(tmp_path, uri)
    core = Proc([str(BIN / "roscore"), "-p", str(port)], env)
    procs = [core]
    try:
        wait_for_master(uri, proc=core)
        setup = f"source {ws}/devel/setup.bash && export ROS_MASTER_URI={uri} && exec "
        # rosrun as the tutorial types it; the script itself where kame's rosrun is not installed
        scripts = ws / "src" / "beginner_tutorials" / "scripts"
        runner = "rosrun beginner_tutorials " if (BIN / "rosrun").exists() else f"{scripts}/"
        listener = Proc(["bash", "-c", setup + runner + "listener.py"], env)
        procs.append(listener)
        listener.wait_line("ready")
        talker = Proc(["bash", "-c", setup + runner + "talker.py"], env)
        procs.append(talker)
        line = listener.wait_line(" I heard ")
        assert line.startswith("/listener_")
        call = bash(f"source {ws}/devel/setup.bash && export ROS_MASTER_URI={uri} && "
                    "rosservice call /add_two_ints 2 3 && rostopic type /chatter", env)
        assert call.stdout.splitlines() == ["sum: 5", "beginner_tutorials/Num"], call.stderr
        talker_out = talker.wait_line("num ")
        assert "[INFO]" in talker_out
    finally:
        for proc in reversed(procs):
            proc.stop()
    assert os.path.isdir(ws / "devel")


def test_unknown_dependencies_fail_as_in_catkin(tmp_path: Path) -> None:
    """`catkin_create_pkg my_first_pkg DEP1 DEP2` then `catkin_make`: CMake stops at find_package."""
    ws, env = make_workspace(tmp_path)
    assert run(["catkin_create_pkg", "my_first_pkg", "DEP1", "DEP2"], ws / "src", env).returncode == 0
    bare = run(["catkin_make", "--no-color"], ws, {**env, "PATH": str(BIN)})  # no toolchain: kame says it
    assert bare.returncode == 1
    assert bare.stderr == ('Package "my_first_pkg" needs DEP1, DEP2, which neither the workspace, kame nor this '
                           "system has: CMake would stop at its find_package(catkin REQUIRED COMPONENTS ...).\n")
    tools_ws = tmp_path / "tools_ws"  # catkin build marks its build space as its own
    shutil.copytree(ws / "src", tools_ws / "src", symlinks=True)
    tools = run(["catkin", "build"], tools_ws, {**env, "PATH": str(BIN)})
    assert tools.returncode == 1 and "Failed     << my_first_pkg" in tools.stdout
    assert "kame: package 'my_first_pkg' needs DEP1, DEP2, which neither the workspace, kame nor" in tools.stderr
    if isinstance(find_toolchain(env), Missing):
        pytest.skip("no C++ toolchain or roscpp here: tests/catkin's fixture says whether that may be")
    result = run(["catkin_make", "--no-color"], ws, env)
    assert result.returncode == 1
    assert "-- Could not find the required component 'DEP1'." in result.stdout
    assert ('Could not find a package configuration file provided by "DEP1" with any of\n  the following names:'
            in result.stderr)
    assert result.stderr.endswith('Invoking "cmake" failed\n')


def test_catkin_create_pkg_as_catkin_tools(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    src = ws / "src"
    assert run(["catkin", "create", "pkg", "pkg_a"], src, env).returncode == 0
    created = run(["catkin", "create", "pkg", "pkg_c", "--catkin-deps", "pkg_a"], src, env)
    assert created.returncode == 0, created.stderr
    assert created.stdout.splitlines() == [f'Creating package "pkg_c" in "{src}"...', "Created file pkg_c/package.xml",
                                           "Created file pkg_c/CMakeLists.txt",
                                           f"Successfully created package files in {src}/pkg_c."]
    xml = (src / "pkg_c" / "package.xml").read_text()
    assert "  <build_depend>pkg_a</build_depend>\n" in xml and "  <exec_depend>pkg_a</exec_depend>\n" in xml
    assert "find_package(catkin REQUIRED COMPONENTS\n  pkg_a\n)" in (src / "pkg_c" / "CMakeLists.txt").read_text()
    built = run(["catkin", "build"], ws, env)
    assert built.returncode == 0, built.stderr
    assert built.stdout.index("Finished  <<< pkg_a") < built.stdout.index("Finished  <<< pkg_c")


def test_devel_env_sh_and_setup_util_of_a_python_workspace(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    create_beginner_tutorials(ws, env)
    assert run(["catkin_make"], ws, env).returncode == 0
    inside = run([str(ws / "devel" / "env.sh"), "sh", "-c", "echo $ROS_PACKAGE_PATH; echo $CMAKE_PREFIX_PATH"], ws,
                 env)
    assert inside.stdout.splitlines()[0].split(":")[0] == str(ws / "src")
    assert inside.stdout.splitlines()[1] == str(ws / "devel")
    bare = run([str(ws / "devel" / "env.sh")], ws, env)
    assert bare.returncode == 1 and bare.stdout.startswith("Usage: env.sh COMMANDS\n")
    lines = run([str(ws / "devel" / "_setup_util.py"), "--local"], ws, env).stdout.splitlines()
    assert f"export CMAKE_PREFIX_PATH={ws}/devel" in lines


def test_compiler_errors_show_as_in_catkin(tmp_path: Path) -> None:
    ws, env = make_workspace(tmp_path)
    if isinstance(find_toolchain(env), Missing):
        pytest.skip("no C++ toolchain or roscpp here: tests/catkin's fixture says whether that may be")
    run(["catkin_create_pkg", "broken", "roscpp"], ws / "src", env)
    pkg = ws / "src" / "broken"
    (pkg / "src" / "broken.cpp").write_text("int main() { return undeclared_thing; }\n")
    cmake = pkg / "CMakeLists.txt"
    cmake.write_text(cmake.read_text() + "add_executable(broken src/broken.cpp)\n")
    result = run(["catkin_make", "--no-color", "-j1"], ws, env)
    assert result.returncode == 1
    # (gcc's quotes follow the locale: \u2018\u2019 in UTF-8 ones, '' in C)
    assert re.search(r"src/broken\.cpp:1:21: error: .undeclared_thing. was not declared in this scope", result.stderr)
    assert "[ 50%] Building CXX object broken/CMakeFiles/broken.dir/src/broken.cpp.o" in result.stdout
    assert result.stderr.endswith('Invoking "make -j1" failed\n')
