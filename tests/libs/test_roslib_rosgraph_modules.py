"""roslib's gentools, srvs, msgs and message helpers, and rosgraph's masterapi, xmlrpc and
roslogging, as ROS 1's: each driver runs under kame's interpreter and Debian's /usr/bin/python3
(its real roslib and rosgraph), on the same inputs and Debian's .msg files."""

from __future__ import annotations

import json
import subprocess
import sys
from pathlib import Path
from typing import Any

import pytest

from . import debian

HERE = Path(__file__).parent
SHARE = Path("/usr/share")
DEBIAN_PACKAGES = [SHARE / "std_msgs", SHARE / "geometry_msgs", SHARE / "std_srvs"]
needs_debian_messages = pytest.mark.skipif(not all((p / "package.xml").exists() for p in DEBIAN_PACKAGES),
                                           reason="Debian's ros-std-msgs, geometry-msgs and std-srvs are not installed")


def run(python: str | Path, driver: str, env: dict[str, str | None] | None = None) -> Any:
    """`driver`'s answer under `python`, with `env` over the environment (None: unset)."""
    merged = {**debian.debian_env(), "ROS_ROOT": "/usr/share/ros",
              "ROS_PACKAGE_PATH": ":".join(str(p) for p in DEBIAN_PACKAGES), **(env or {})}
    full_env = {key: value for key, value in merged.items() if value is not None}
    done = subprocess.run([str(python), str(HERE / driver)], capture_output=True, text=True, env=full_env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def roslib_kame() -> Any:
    return run(sys.executable, "roslib_modules_driver.py")


@pytest.fixture(scope="module")
def roslib_ros() -> Any:
    if not debian.has("roslib.gentools"):
        pytest.skip("Debian's python3-roslib is not installed")
    return run(debian.SYSTEM_PYTHON, "roslib_modules_driver.py")


@needs_debian_messages
def test_roslib_gentools(roslib_kame: Any, roslib_ros: Any) -> None:
    pose = roslib_kame["gentools"]["geometry_msgs/msg/PoseStamped.msg"]
    assert pose["md5"] == "d3812c3cbc69362b77dc0b19b345f8f5" and pose["uniquedeps"][0] == "std_msgs/Header"
    assert roslib_kame["gentools"]["std_srvs/srv/SetBool.srv"]["md5"] == "09fb03525b03e7ea1fd3992bafd87e16"
    assert roslib_kame["gentools"]["spec_to_str"][0].startswith("Header header\n  uint32 seq\n  time stamp\n")
    assert roslib_kame["gentools"] == roslib_ros["gentools"]


@needs_debian_messages
def test_roslib_srvs(roslib_kame: Any, roslib_ros: Any) -> None:
    assert roslib_kame["srvs"]["list"] == ["Empty", "SetBool", "Trigger"]
    assert roslib_kame["srvs"] == roslib_ros["srvs"]


@needs_debian_messages
def test_roslib_msgs_helpers(roslib_kame: Any, roslib_ros: Any) -> None:
    assert roslib_kame["msgs"]["parsed"][0] == ["raised", "MsgSpecException", "Invalid array dimension: []"]
    assert roslib_kame["msgs"]["verbose"] == [False, False, True, True]
    assert roslib_kame["msgs"] == roslib_ros["msgs"]


@needs_debian_messages
def test_roslib_small_modules(roslib_kame: Any, roslib_ros: Any) -> None:
    """rosenv, resources, scriptutil, the names' patterns and set_interactive."""
    assert roslib_kame["small"]["resources"] == ["Empty.srv", "SetBool.srv", "Trigger.srv"]
    assert roslib_kame["small"] == roslib_ros["small"]


@needs_debian_messages
def test_roslib_message_classes(roslib_kame: Any, roslib_ros: Any) -> None:
    assert roslib_kame["message"]["messages"][0] == [
        "raised", "ValueError", "message type is missing package name: String"]
    assert roslib_kame["message"] == roslib_ros["message"]


ROS_LOGGING_CONF = Path("/usr/share/rosgraph/conf")


def rosgraph_answers(python: str | Path, folder: Path, etc_dir: Path) -> Any:
    for sub in ("log", "home"):
        (folder / sub).mkdir(parents=True)
    return run(python, "rosgraph_modules_driver.py", {
        "ROS_IP": "127.0.0.1", "ROS_LOG_DIR": str(folder / "log"), "ROS_HOME": str(folder / "home"),
        "ROS_ETC_DIR": str(etc_dir), "ROS_PYTHON_LOG_CONFIG_FILE": None, "ROSCONSOLE_FORMAT": None})


@pytest.fixture(scope="module")
def rosgraph_kame(tmp_path_factory: pytest.TempPathFactory) -> Any:
    return rosgraph_answers(sys.executable, tmp_path_factory.mktemp("rosgraph"), ROS_LOGGING_CONF)


@pytest.fixture(scope="module")
def rosgraph_ros(tmp_path_factory: pytest.TempPathFactory) -> Any:
    if not (debian.has("rosgraph.xmlrpc") and (ROS_LOGGING_CONF / "python_logging.conf").exists()):
        pytest.skip("Debian's python3-rosgraph is not installed")
    return rosgraph_answers(debian.SYSTEM_PYTHON, tmp_path_factory.mktemp("rosgraph"), ROS_LOGGING_CONF)


def test_master_calls_go_through_a_substitutable_handle(rosgraph_kame: Any, rosgraph_ros: Any) -> None:
    assert rosgraph_kame["master"]["calls"][0] == ["getPid", "/probe"]
    assert rosgraph_kame["master"]["param"] == ["raised", "MasterError", "no such param"]
    assert rosgraph_kame["master"] == rosgraph_ros["master"]


def test_handshake_headers_and_name_patterns(rosgraph_kame: Any, rosgraph_ros: Any) -> None:
    assert rosgraph_kame["network"]["header"] == {"callerid": "/me", "topic": "/t"}
    assert rosgraph_kame["network"]["left"] == "020000006869"
    assert rosgraph_kame["network"] == rosgraph_ros["network"]


def test_xmlrpc_node_serves_a_handler(rosgraph_kame: Any, rosgraph_ros: Any) -> None:
    assert rosgraph_kame["xmlrpc"]["add"] == 5 and rosgraph_kame["xmlrpc"]["events"] == ["ready", "shutdown done"]
    assert rosgraph_kame["xmlrpc"] == rosgraph_ros["xmlrpc"]


def test_the_standard_library_servers(rosgraph_kame: Any, rosgraph_ros: Any) -> None:
    assert rosgraph_kame["servers"]["product"] == 42
    assert rosgraph_kame["servers"] == rosgraph_ros["servers"]


def test_configure_logging_installs_the_rosout_handlers(rosgraph_kame: Any, rosgraph_ros: Any) -> None:
    assert rosgraph_kame["logging"]["rosout"] == ["INFO", True, [["RosStreamHandler", "DEBUG"]]]
    assert rosgraph_kame["logging"] == rosgraph_ros["logging"]


def test_ros_stream_handler_and_rospy_logger(rosgraph_kame: Any, rosgraph_ros: Any) -> None:
    assert rosgraph_kame["stream"]["stderr"][0].startswith("[WARN] probe.stream /unnamed ")
    assert rosgraph_kame["stream"] == rosgraph_ros["stream"]


def test_without_a_configuration_file_kame_uses_ros_default(tmp_path: Path, rosgraph_kame: Any) -> None:
    """No python_logging.conf anywhere: kame's built-in copy of ROS's gives the same loggers."""
    empty = tmp_path / "etc"
    empty.mkdir()
    assert rosgraph_answers(sys.executable, tmp_path / "run", empty)["logging"] == rosgraph_kame["logging"]


def rosbuild_tree(root: Path) -> Path:
    """A stack `mystack` (stack.xml) holding a package `mypkg` (manifest.xml, and package.xml for rospkg)."""
    package = root / "mystack" / "mypkg"
    package.mkdir(parents=True)
    (root / "mystack" / "stack.xml").write_text(
        '<stack>\n  <description brief="A stack">The <b>stack</b></description>\n  <author>Ann</author>'
        '<license url="http://l">BSD</license>\n  <version>1.2.3</version>\n  <depend stack="ros"/>\n</stack>\n')
    (package / "manifest.xml").write_text(
        '<package>\n  <description brief="brief one">Some <em>XHTML</em> text</description>\n'
        '  <author>Bob, Carol</author>\n  <license url="http://bsd">BSD</license>\n'
        '  <review status="experimental" notes="none yet"/>\n  <url>http://wiki</url>\n  <logo>logo.png</logo>\n'
        '  <depend package="roscpp"/><depend package="std_msgs"/><depend thirdparty="boost"/>\n'
        '  <rosdep name="eigen"/>\n  <platform os="ubuntu" version="20.04" notes="lts"/>\n'
        '  <export><cpp cflags="-I${prefix}/include" lflags="-lx"/><python path="src"/></export>\n'
        '  <versioncontrol type="git" url="http://repo"/>\n  <unknowntag/>\n</package>\n')
    (package / "package.xml").write_text(
        '<package format="2"><name>mypkg</name><version>0.0.1</version><description>x</description>'
        '<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>\n')
    return root


def manifest_answers(python: str | Path, root: Path) -> Any:
    env = {**debian.debian_env(), "ROS_ROOT": "/usr/share/ros", "ROS_PACKAGE_PATH": str(root)}
    done = subprocess.run([str(python), str(HERE / "roslib_manifest_driver.py")], input=json.dumps({"root": str(root)}),
                          capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_roslib_rosbuild_manifests(tmp_path: Path) -> None:
    root = rosbuild_tree(tmp_path / "tree")
    ours = manifest_answers(sys.executable, root)
    assert ours["manifest"]["depends"] == ["roscpp", "std_msgs"] and ours["manifest"]["cpp_flags"] == [
        "-I${prefix}/include"]
    assert ours["stack_version"] == ["1.2.3", None] and ours["stack_of"] == "mystack"
    assert ours["version_in_manifest"][:2] == ["raised", "ManifestException"]
    if debian.has("roslib.manifestlib"):
        assert ours == manifest_answers(debian.SYSTEM_PYTHON, root)


def catkin_find_answers(python: str | Path, root: Path) -> Any:
    env = {**debian.debian_env(), "CMAKE_PREFIX_PATH": str(root / "devel")}
    done = subprocess.run([str(python), str(HERE / "catkin_find_driver.py")], input=json.dumps({"root": str(root)}),
                          capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


def test_catkin_find_in_workspaces(tmp_path: Path) -> None:
    """A devel space whose .catkin names a source space: a package found in either."""
    (tmp_path / "src" / "pkg_src").mkdir(parents=True)
    (tmp_path / "src" / "pkg_src" / "package.xml").write_text(
        '<package format="2"><name>pkg_src</name><version>0.0.1</version><description>x</description>'
        '<maintainer email="me@example.com">a</maintainer><license>BSD</license></package>\n')
    (tmp_path / "devel" / "share" / "pkg_devel" / "msg").mkdir(parents=True)
    (tmp_path / "devel" / ".catkin").write_text(str(tmp_path / "src"))
    ours = catkin_find_answers(sys.executable, tmp_path)
    assert ours["cases"][0] == ["ROOT/src/pkg_src"] and ours["cases"][1] == ["ROOT/devel/share/pkg_devel/msg"]
    if debian.has("catkin.find_in_workspaces", "rosmsg"):
        assert ours == catkin_find_answers(debian.SYSTEM_PYTHON, tmp_path)
