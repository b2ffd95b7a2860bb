"""rosmsg and rossrv end to end: the installed console scripts, run as a user would.

The first part pins kame's output byte for byte; the second runs Debian's real rosmsg/rossrv
(ros_comm 1.15.15) beside kame's on the same definitions and compares stdout.
"""

from __future__ import annotations

import os
import subprocess
import sys
from collections.abc import Callable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import pytest

BIN = Path(sys.executable).parent
KAME_SHARE = Path(__file__).resolve().parents[2] / "src" / "kame" / "share"

Result = subprocess.CompletedProcess[str]
Runner = Callable[..., Result]

TWIST = """\
geometry_msgs/Vector3 linear
  float64 x
  float64 y
  float64 z
geometry_msgs/Vector3 angular
  float64 x
  float64 y
  float64 z

"""

LOG = """\
byte DEBUG=1
byte INFO=2
byte WARN=4
byte ERROR=8
byte FATAL=16
std_msgs/Header header
  uint32 seq
  time stamp
  string frame_id
byte level
string name
string msg
string file
string function
uint32 line
string[] topics

"""

SPAWN = """\
float32 x
float32 y
float32 theta
string name
---
string name

"""

PACKAGE_XML = """\
<package format="2">
  <name>{name}</name>
  <version>0.1.0</version>
  <description>rosmsg test package</description>
  <maintainer email="dev@example.com">dev</maintainer>
  <license>BSD</license>
</package>
"""

# A user package with comments, constants (a string one keeping its '#'), a Header, a
# same-package reference and arrays; a service with comments.
THING_MSG = """\
# A thing, with comments.
uint8 RED=1   # red
string NAME=hello # not a comment

Header header  # stamp
Part[] parts
float64[3] xyz
"""
PART_MSG = "int32 id # the id\ntime t\n"
DO_THING_SRV = "# ask\nThing thing\n---\n# answer\nbool ok\n"


def write_package(root: Path, name: str, files: dict[str, str]) -> Path:
    pkg = root / name
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text(PACKAGE_XML.format(name=name))
    for rel, text in files.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text)
    return pkg


def tool_env(ros_home: Path, ros_package_path: str | None) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS")}
    env["ROS_HOME"] = str(ros_home)
    if ros_package_path is not None:
        env["ROS_PACKAGE_PATH"] = ros_package_path
    return env


def make_runner(ros_home: Path, directory: Path | None) -> Runner:
    def run(exe: str, *args: str, stdin: str = "", rpp: str | None = None) -> Result:
        path = str(directory / exe) if directory else exe
        return subprocess.run(
            [path, *args], input=stdin, capture_output=True, text=True,
            env=tool_env(ros_home, rpp), timeout=60, check=False,
        )

    return run


@pytest.fixture(scope="module")
def ros_home(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return tmp_path_factory.mktemp("ros_home")


@pytest.fixture(scope="module")
def kame(ros_home: Path) -> Runner:
    return make_runner(ros_home, BIN)


@pytest.fixture(scope="module")
def workspace(tmp_path_factory: pytest.TempPathFactory) -> Path:
    root = tmp_path_factory.mktemp("ws")
    write_package(root, "kame_cmp_msgs", {
        "msg/Thing.msg": THING_MSG, "msg/Part.msg": PART_MSG, "srv/DoThing.srv": DO_THING_SRV,
    })
    write_package(root, "broken_msgs", {
        "msg/NeedsMissing.msg": "int32 a\nMissing m\n",
        "msg/NeedsNoPackage.msg": "nopkg/Thing t\n",
        "msg/Bad.msg": "int32 a b c\n",
    })
    return root


def assert_one_line_error(result: Result, status: int = 1) -> str:
    assert result.returncode == status, result
    assert result.stdout == ""
    assert "Traceback" not in result.stderr
    assert result.stderr.endswith("\n") and result.stderr.count("\n") == 1, result.stderr
    return result.stderr[:-1]


# --- show ---------------------------------------------------------------------------------


def test_show_expands_nested_fields(kame: Runner) -> None:
    result = kame("rosmsg", "show", "geometry_msgs/Twist")
    assert (result.returncode, result.stdout, result.stderr) == (0, TWIST, "")


def test_show_constants_and_header(kame: Runner) -> None:
    assert kame("rosmsg", "show", "rosgraph_msgs/Log").stdout == LOG


def test_info_alias_and_msg_suffix(kame: Runner) -> None:
    assert kame("rosmsg", "info", "geometry_msgs/Twist").stdout == TWIST
    assert kame("rosmsg", "show", "geometry_msgs/Twist.msg").stdout == TWIST


def test_show_bare_name_searches_packages(kame: Runner) -> None:
    assert kame("rosmsg", "show", "Twist").stdout == "[geometry_msgs/Twist]:\n" + TWIST


def test_show_bare_name_several_matches(kame: Runner) -> None:
    result = kame("rossrv", "show", "Empty")
    assert result.stdout == "[roscpp/Empty]:\n---\n\n[std_srvs/Empty]:\n---\n\n"


def test_show_action_generated_message(kame: Runner) -> None:
    result = kame("rosmsg", "show", "actionlib_tutorials/FibonacciActionGoal")
    assert result.returncode == 0
    assert result.stdout.startswith("std_msgs/Header header\n  uint32 seq\n")
    assert "actionlib_tutorials/FibonacciGoal goal\n  int32 order\n\n" in result.stdout
    assert kame("rosmsg", "show", "FibonacciGoal").stdout == "[actionlib_tutorials/FibonacciGoal]:\nint32 order\n\n"


def test_rossrv_show(kame: Runner) -> None:
    assert kame("rossrv", "show", "turtlesim/Spawn").stdout == SPAWN
    assert kame("rossrv", "show", "Spawn").stdout == "[turtlesim/Spawn]:\n" + SPAWN


def test_raw_of_kame_package_is_upstreams_file(kame: Runner) -> None:
    # kame's geometry_msgs/Twist.msg is upstream's file byte for byte, comment and spacing included
    text = "# This expresses velocity in free space broken into its linear and angular parts.\n" \
           "Vector3  linear\nVector3  angular\n"
    assert kame("rosmsg", "show", "-r", "geometry_msgs/Twist").stdout == text + "\n"
    raw = kame("rosmsg", "show", "--raw", "Twist").stdout
    assert raw == "[geometry_msgs/Twist]:\n" + text + "\n"


def test_user_package_on_ros_package_path(kame: Runner, workspace: Path) -> None:
    rpp = str(workspace)
    assert kame("rosmsg", "show", "-r", "kame_cmp_msgs/Thing", rpp=rpp).stdout == THING_MSG + "\n"
    assert kame("rossrv", "show", "-r", "kame_cmp_msgs/DoThing", rpp=rpp).stdout == DO_THING_SRV + "\n"
    assert kame("rosmsg", "show", "kame_cmp_msgs/Thing", rpp=rpp).stdout == (
        "uint8 RED=1\n"
        "string NAME=hello # not a comment\n"
        "std_msgs/Header header\n  uint32 seq\n  time stamp\n  string frame_id\n"
        "kame_cmp_msgs/Part[] parts\n  int32 id\n  time t\n"
        "float64[3] xyz\n\n"
    )


def test_show_reads_type_from_stdin(kame: Runner) -> None:
    assert kame("rosmsg", "show", stdin="geometry_msgs/Twist\n").stdout == TWIST
    assert kame("rossrv", "show", stdin="\n  \nturtlesim/Spawn\n").stdout == SPAWN
    assert kame("rosmsg", "md5", stdin="std_msgs/String\n").stdout == "992ce8a1687cec8c8bd883ec73ca41d1\n"


# --- md5, list, package, packages ------------------------------------------------------------


def test_md5(kame: Runner) -> None:
    assert kame("rosmsg", "md5", "geometry_msgs/Twist").stdout == "9f195f881246fdfa2798d1d3eebca84a\n"
    assert kame("rosmsg", "md5", "Twist").stdout == "[geometry_msgs/Twist]: 9f195f881246fdfa2798d1d3eebca84a\n"
    assert kame("rosmsg", "md5", "/Header").stdout == "2176decaecbce78abc3b96ef049fabed\n"
    assert kame("rossrv", "md5", "std_srvs/SetBool").stdout == "09fb03525b03e7ea1fd3992bafd87e16\n"


def test_list(kame: Runner) -> None:
    result = kame("rosmsg", "list")
    lines = result.stdout.splitlines()
    assert result.returncode == 0 and result.stdout.endswith("\n")
    assert lines == sorted(lines, key=lambda t: tuple(t.split("/")))
    for expected in ("geometry_msgs/Twist", "std_msgs/Header", "turtlesim/Pose",
                     "actionlib_tutorials/FibonacciGoal", "actionlib_tutorials/FibonacciActionGoal"):
        assert expected in lines
    srvs = kame("rossrv", "list").stdout.splitlines()
    assert "turtlesim/Spawn" in srvs and "std_srvs/SetBool" in srvs
    # the services, not their halves (gazebo_msgs/BodyRequest and JointRequest are services of their own)
    assert "turtlesim/SpawnRequest" not in srvs and not any(s.endswith("Response") for s in srvs)
    assert "gazebo_msgs/BodyRequest" in srvs


def test_package(kame: Runner) -> None:
    assert kame("rosmsg", "package", "turtlesim").stdout == "turtlesim/Color\nturtlesim/Pose\n"  # as Noetic's
    assert kame("rossrv", "package", "-s", "turtlesim").stdout == (
        "turtlesim/Kill turtlesim/SetPen turtlesim/Spawn turtlesim/TeleportAbsolute turtlesim/TeleportRelative\n"
    )
    assert kame("rossrv", "package", "geometry_msgs").stdout == "\n"


def test_packages(kame: Runner) -> None:
    msgs = kame("rosmsg", "packages").stdout
    names = msgs.splitlines()
    assert names == sorted(names)
    assert {"std_msgs", "geometry_msgs", "turtlesim", "actionlib_tutorials"} <= set(names)
    assert kame("rosmsg", "packages", "-s").stdout == " ".join(names) + "\n"
    srv_names = kame("rossrv", "packages").stdout.splitlines()
    assert "std_srvs" in srv_names and "geometry_msgs" not in srv_names


def test_usage(kame: Runner) -> None:
    result = kame("rossrv")
    assert result.returncode == 0
    assert result.stdout.startswith(
        "rossrv is a command-line tool for displaying information about ROS Service types.\n"
    )
    assert "\trossrv package\tList services in a package\n" in result.stdout
    assert result.stdout.endswith("Type rossrv <command> -h for more detailed usage\n\n")
    assert kame("rosmsg", "frob").returncode == 64
    helped = kame("rosmsg", "show", "-h")
    assert helped.returncode == 0 and helped.stdout.startswith("Usage: rosmsg show [options] <message type>\n")


# --- errors --------------------------------------------------------------------------------


def test_unknown_package(kame: Runner) -> None:
    line = assert_one_line_error(kame("rosmsg", "show", "nope/Nope"))
    assert line.startswith(
        "Unable to load msg [nope/Nope]: Cannot locate message [Nope]: unknown package [nope] on search path [{"
    )
    assert f"'std_msgs': ['{KAME_SHARE / 'std_msgs' / 'msg'}']" in line


def test_unknown_type_in_known_package(kame: Runner) -> None:
    line = assert_one_line_error(kame("rossrv", "show", "turtlesim/Nope"))
    assert line == (
        "Unknown srv type [turtlesim/Nope]: Cannot locate message [Nope] in package [turtlesim] "
        f"with paths [['{KAME_SHARE / 'turtlesim' / 'srv'}']]"
    )


def test_bad_names(kame: Runner) -> None:
    assert assert_one_line_error(kame("rosmsg", "show", "Foo")) == "Could not find msg 'Foo'"
    assert assert_one_line_error(kame("rosmsg", "show", "a/b/c")) == "Unable to load msg [a/b/c]: invalid name [a/b/c]"
    assert assert_one_line_error(kame("rosmsg", "md5", "nope/Nope")) == "Cannot locate [nope/Nope]"
    assert assert_one_line_error(kame("rossrv", "md5", "Nope")) == "No messages matching the name [Nope]"
    assert assert_one_line_error(kame("rosmsg", "md5", "a/b/c"), 64) == "Invalid type: 'invalid name [a/b/c]'"
    assert assert_one_line_error(kame("rosmsg", "package", "nope"), 64) == "Invalid package: nope"


def test_broken_user_definitions(kame: Runner, workspace: Path) -> None:
    rpp = str(workspace)
    folder = workspace / "broken_msgs" / "msg"
    line = assert_one_line_error(kame("rosmsg", "show", "broken_msgs/NeedsMissing", rpp=rpp))
    assert line == (
        "Unable to load msg [broken_msgs/NeedsMissing]: Cannot locate message [Missing] in package "
        f"[broken_msgs] with paths [['{folder}']]"
    )
    line = assert_one_line_error(kame("rosmsg", "show", "broken_msgs/NeedsNoPackage", rpp=rpp))
    assert "Cannot locate message [Thing]: unknown package [nopkg] on search path [{" in line
    line = assert_one_line_error(kame("rosmsg", "show", "broken_msgs/Bad", rpp=rpp))
    assert line.startswith("Unable to load msg [broken_msgs/Bad]: ") and "Bad.msg:1" in line
    assert_one_line_error(kame("rosmsg", "md5", "broken_msgs/Bad", rpp=rpp))


@pytest.mark.parametrize(
    ("args", "message"),
    [
        (("show", "a", "b"), "rosmsg: error: you may only specify one message type"),
        (("show", "-x", "std_msgs/String"), "rosmsg: error: no such option: -x"),
        (("show", "std_msgs::String"), "rosmsg: error: rosmsg does not understand C++-style namespaces"),
        (("show", "std_msgs.String"), "rosmsg: error: invalid message type 'std_msgs.String'."),
        (("show",), "rosmsg: error: no message type given and none on standard input"),
    ],
)
def test_usage_errors(kame: Runner, args: tuple[str, ...], message: str) -> None:
    result = kame("rosmsg", *args)
    assert result.returncode == 2 and result.stdout == ""
    assert result.stderr.startswith("Usage: rosmsg show [options] <message type>\n\n")
    assert message in result.stderr and "Traceback" not in result.stderr


# --- the same commands against real ROS 1 -----------------------------------------------------

REAL_ROSMSG = Path("/usr/bin/rosmsg")
DEBIAN_SHARE = Path("/usr/share")
# Debian installs these without a package.xml, so rospack cannot see them; the comparison
# workspace gives them one (symlinking the definitions), for both tools alike.
UNLISTED = ("nav_msgs", "actionlib_msgs", "move_base_msgs")

needs_real_ros = pytest.mark.skipif(not REAL_ROSMSG.exists(), reason="real ROS 1 rosmsg is not installed")


SAME_STDOUT = [
    ("rosmsg", "show", "geometry_msgs/Twist"),
    ("rosmsg", "show", "sensor_msgs/Image"),
    ("rosmsg", "show", "rosgraph_msgs/Log"),
    ("rosmsg", "show", "nav_msgs/Odometry"),
    ("rosmsg", "show", "actionlib_msgs/GoalStatusArray"),
    ("rosmsg", "show", "move_base_msgs/MoveBaseActionGoal"),
    ("rosmsg", "show", "Twist"),
    ("rosmsg", "show", "kame_cmp_msgs/Thing"),
    ("rosmsg", "show", "-r", "kame_cmp_msgs/Thing"),
    ("rossrv", "show", "std_srvs/SetBool"),
    ("rossrv", "show", "nav_msgs/GetPlan"),
    ("rossrv", "show", "Empty"),
    ("rossrv", "show", "-r", "kame_cmp_msgs/DoThing"),
    ("rosmsg", "md5", "geometry_msgs/Twist"),
    ("rosmsg", "md5", "sensor_msgs/Image"),
    ("rosmsg", "md5", "nav_msgs/Odometry"),
    ("rosmsg", "md5", "Log"),
    ("rossrv", "md5", "std_srvs/SetBool"),
    ("rossrv", "md5", "nav_msgs/GetPlan"),
    ("rosmsg", "package", "geometry_msgs"),
    ("rosmsg", "package", "-s", "move_base_msgs"),
    ("rossrv", "package", "nav_msgs"),
    ("rosmsg", "show", "-h"),
    ("rossrv", "package", "-h"),
    ("rosmsg",),
]


SAME_ERRORS = [
    ("rosmsg", "show", "std_msgs/Nope"),
    ("rosmsg", "show", "Nope"),
    ("rossrv", "show", "std_srvs/Nope"),
    ("rosmsg", "show", "a/b/c"),
    ("rosmsg", "show", "a", "b"),
    ("rosmsg", "show", "a::b"),
]
LISTS = [("rosmsg", "list"), ("rossrv", "list")]

Compared = dict[tuple[str, ...], tuple[Result, Result]]


@pytest.fixture(scope="module")
def compared(tmp_path_factory: pytest.TempPathFactory, ros_home: Path) -> Compared:
    """Every command of this section run by real ROS and by kame on one package path, in parallel
    (real rosmsg takes a third of a second to start): argv -> (real result, kame result)."""
    root = tmp_path_factory.mktemp("cmp_ws")
    write_package(root, "kame_cmp_msgs", {
        "msg/Thing.msg": THING_MSG, "msg/Part.msg": PART_MSG, "srv/DoThing.srv": DO_THING_SRV,
    })
    for name in UNLISTED:
        if (DEBIAN_SHARE / name).is_dir():
            pkg = write_package(root, name, {})
            for kind in ("msg", "srv", "action"):
                if (DEBIAN_SHARE / name / kind).is_dir():
                    (pkg / kind).symlink_to(DEBIAN_SHARE / name / kind)
    real = make_runner(ros_home, None)
    kame = make_runner(ros_home, BIN)
    # Warm rospack's cache once so parallel runs do not race to write it.
    real("/usr/bin/rosmsg", "packages", rpp=f"{root}:{DEBIAN_SHARE}")
    argvs = [*SAME_STDOUT, *SAME_ERRORS, *LISTS]
    with ThreadPoolExecutor(max(4, os.cpu_count() or 1)) as pool:
        # Debian's rospack also needs /usr/share to find std_msgs and friends; kame ships them.
        theirs = [pool.submit(real, f"/usr/bin/{a[0]}", *a[1:], rpp=f"{root}:{DEBIAN_SHARE}") for a in argvs]
        ours = [pool.submit(kame, a[0], *a[1:], rpp=str(root)) for a in argvs]
        return {a: (t.result(), o.result()) for a, t, o in zip(argvs, theirs, ours, strict=True)}


@needs_real_ros
@pytest.mark.parametrize("argv", SAME_STDOUT, ids=" ".join)
def test_same_stdout_as_real_ros(compared: Compared, argv: tuple[str, ...]) -> None:
    theirs, ours = compared[argv]
    assert theirs.returncode == 0, theirs.stderr
    assert (ours.returncode, ours.stdout) == (0, theirs.stdout)


@needs_real_ros
@pytest.mark.parametrize("argv", SAME_ERRORS, ids=" ".join)
def test_same_errors_as_real_ros(compared: Compared, argv: tuple[str, ...]) -> None:
    theirs, ours = compared[argv]
    assert ours.returncode == theirs.returncode != 0
    assert ours.stdout == theirs.stdout == ""
    real_lines = [line for line in theirs.stderr.splitlines() if "rosdep" not in line]
    # Paths differ (kame's std_msgs is its own); the wording must not.
    assert [line.replace(str(DEBIAN_SHARE), "") for line in real_lines] == [
        line.replace(str(KAME_SHARE), "") for line in ours.stderr.splitlines()
    ]


@needs_real_ros
@pytest.mark.parametrize("argv", LISTS, ids=" ".join)
def test_list_agrees_on_shared_packages(compared: Compared, argv: tuple[str, ...]) -> None:
    theirs, ours = compared[argv]
    real_types = theirs.stdout.splitlines()
    our_types = ours.stdout.splitlines()
    # the packages both list (Debian's peers bring others, such as actionlib's test actions)
    shared = {t.split("/")[0] for t in real_types} & {t.split("/")[0] for t in our_types}
    assert len(shared) >= 5, shared
    # Debian's rosmsg lists a package twice when catkin also finds it under /usr/share.
    assert sorted({t for t in real_types if t.split("/")[0] in shared}) == [
        t for t in our_types if t.split("/")[0] in shared]
