"""rostopic end to end: the installed command, run as a user would, against a live kame graph.

A kame master (rosmaster --core) and a kame rospy node (topic_peer.py) make the graph; each
test runs `rostopic ...` and checks its output against the formats of ros1-user-behaviour §4
with node names, ports and times masked. The last part runs Debian's real rostopic beside
kame's against the same graph and compares what they print (skipped without Debian's ROS).
"""

from __future__ import annotations

import re
import subprocess
import sys
import time
from collections.abc import Callable, Iterator
from concurrent.futures import ThreadPoolExecutor
from dataclasses import dataclass
from pathlib import Path

import pytest

from ..support import SYSTEM_PYTHON, Proc, free_port, have_debian_ros, kame_command, ros_env, wait_for_master

BIN = Path(sys.executable).parent
PEER = Path(__file__).with_name("topic_peer.py")
Result = subprocess.CompletedProcess[str]

THING_MSG = "# a type only the publisher knows\nstring name\nint32[] sizes\ngeometry_msgs/Point where\n"
PACKAGE_XML = """<package format="2"><name>kametest</name><version>0.0.1</version><description>t</description>
<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>
"""


@dataclass
class Graph:
    uri: str
    env: dict[str, str]
    peer: Proc
    home: Path

    def run(self, *args: str, timeout: float = 20.0, stdin: str | None = None,
            env: dict[str, str] | None = None) -> Result:
        return subprocess.run([str(BIN / "rostopic"), *args], env=env or self.env, capture_output=True, text=True,
                              timeout=timeout, input=stdin if stdin is not None else "")

    def start(self, *args: str) -> Proc:
        return Proc([str(BIN / "rostopic"), *args], self.env)

    def debian(self, *args: str, timeout: float = 20.0) -> Result:
        return subprocess.run([SYSTEM_PYTHON, "/usr/bin/rostopic", *args], env=self.env, capture_output=True,
                              text=True, timeout=timeout, input="")


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Graph]:
    home = tmp_path_factory.mktemp("rostopic")
    package = home / "ws" / "kametest"
    (package / "msg").mkdir(parents=True)
    (package / "package.xml").write_text(PACKAGE_XML)
    (package / "msg" / "Thing.msg").write_text(THING_MSG)
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(home / "tool", uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    peer: Proc | None = None
    try:
        wait_for_master(uri, proc=master)
        peer_env = dict(ros_env(home / "peer", uri), ROS_PACKAGE_PATH=str(home / "ws"))
        peer = Proc([sys.executable, str(PEER), "--custom"], peer_env)
        peer.wait_line("ready")
        yield Graph(uri, env, peer, home)
    finally:
        if peer is not None:
            peer.stop()
        master.stop()


def mask(text: str) -> str:
    text = re.sub(r"/rostopic_\d+_\d+", "/rostopic_X", text)
    text = re.sub(r"http://[^:/]+:\d+/", "http://HOST:PORT/", text)
    return text


def ok(result: Result) -> str:
    assert result.returncode == 0, f"exit {result.returncode}\n{result.stdout}\n{result.stderr}"
    assert "Traceback" not in result.stderr, result.stderr
    return result.stdout


def one_error(result: Result, status: int = 1) -> str:
    assert result.returncode == status, f"exit {result.returncode}\n{result.stdout}\n{result.stderr}"
    assert "Traceback" not in result.stderr, result.stderr
    return result.stderr


def parallel(*calls: Callable[[], Result]) -> list[Result]:
    with ThreadPoolExecutor(len(calls)) as pool:
        return list(pool.map(lambda call: call(), calls))


# ---------------------------------------------------------------- list, info, type, find


PUBLISHED = ["/bytes", "/custom", "/js", "/pose2d", "/poses", "/rosout", "/stamped", "/turtle1/pose"]


def test_list_plain_namespace_and_filters(graph: Graph) -> None:
    plain, ns, pubs, subs = parallel(lambda: graph.run("list"), lambda: graph.run("list", "/turtle1"),
                                     lambda: graph.run("list", "-p"), lambda: graph.run("list", "-s"))
    assert ok(plain).splitlines() == sorted([*PUBLISHED, "/chatter", "/turtle1/cmd_vel"])
    assert ok(ns) == "/turtle1/cmd_vel\n/turtle1/pose\n"
    assert ok(pubs).splitlines() == PUBLISHED
    assert ok(subs) == "/chatter\n/turtle1/cmd_vel\n"


def test_list_verbose(graph: Graph) -> None:
    out = ok(graph.run("list", "-v"))
    assert out.startswith("\nPublished topics:\n")
    assert out.endswith("\n\n")
    assert " * /turtle1/pose [turtlesim/Pose] 1 publisher\n" in out
    assert " * /js [sensor_msgs/JointState] 1 publisher\n" in out
    assert "\n\nSubscribed topics:\n" in out
    assert " * /turtle1/cmd_vel [geometry_msgs/Twist] 1 subscriber\n" in out
    assert " * /chatter [std_msgs/String] 1 subscriber\n" in out


def test_list_bag_is_refused_clearly(graph: Graph) -> None:
    assert one_error(graph.run("list", "-b", "nope.bag")) == "ERROR: bag file [nope.bag] does not exist\n"
    bag = graph.home / "x.bag"
    bag.write_bytes(b"#ROSBAG V2.0\n")
    err = one_error(graph.run("list", "-b", str(bag)))
    assert err.startswith("ERROR: unable to use bag file: ") and err.count("\n") == 1


def test_info(graph: Graph) -> None:
    out = mask(ok(graph.run("info", "/turtle1/cmd_vel")))
    assert out == ("Type: geometry_msgs/Twist\n\nPublishers: None\n\n"
                   "Subscribers: \n * /topic_peer (http://HOST:PORT/)\n\n\n")
    out = mask(ok(graph.run("info", "js")))
    assert out == ("Type: sensor_msgs/JointState\n\nPublishers: \n * /topic_peer (http://HOST:PORT/)\n\n"
                   "Subscribers: None\n\n\n")
    assert one_error(graph.run("info", "/nope")) == "ERROR: Unknown topic /nope\n"


def test_type_of_topics_and_fields(graph: Graph) -> None:
    results = parallel(lambda: graph.run("type", "/turtle1/cmd_vel"), lambda: graph.run("type", "/turtle1/pose/x"),
                       lambda: graph.run("type", "/js/header/stamp"), lambda: graph.run("type", "/js/position"),
                       lambda: graph.run("type", "/poses/poses[1]/position"), lambda: graph.run("type", "/nope"))
    assert [r.stdout for r in results[:5]] == [
        "geometry_msgs/Twist\n", "turtlesim/Pose x float32\n", "sensor_msgs/JointState header/stamp time\n",
        "sensor_msgs/JointState position float64[]\n",
        "geometry_msgs/PoseArray poses[1]/position geometry_msgs/Point\n"]
    assert one_error(results[5]) == "unknown topic type [/nope]\n"


def test_type_pipes_into_rosmsg_show(graph: Graph) -> None:
    typed = ok(graph.run("type", "/turtle1/cmd_vel"))
    shown = subprocess.run([str(BIN / "rosmsg"), "show"], input=typed, capture_output=True, text=True,
                           env=graph.env, timeout=20)
    assert shown.stdout.startswith("geometry_msgs/Vector3 linear\n  float64 x\n")


def test_find(graph: Graph) -> None:
    assert ok(graph.run("find", "sensor_msgs/JointState")) == "/js\n"
    assert ok(graph.run("find", "std_msgs/Nothing")) == "\n"


# ---------------------------------------------------------------- echo

JS = ("header: \n  seq: 1\n  stamp: \n    secs: 1795311367\n    nsecs: 122221231\n  frame_id: \"base\"\n"
      "name: \n  - a\n  - b\nposition: [1.0, 2.5]\nvelocity: []\neffort: []\n---\n")


def test_echo_formats(graph: Graph) -> None:
    results = parallel(
        lambda: graph.run("echo", "-n", "1", "/js"),
        lambda: graph.run("echo", "-n", "1", "/js/header"),
        lambda: graph.run("echo", "-n", "1", "/js/position[1]"),
        lambda: graph.run("echo", "-n", "1", "--noarr", "/js"),
        lambda: graph.run("echo", "-n", "1", "--nostr", "/js"),
        lambda: graph.run("echo", "-n", "1", "/turtle1/pose/x"),
        lambda: graph.run("echo", "-n", "1", "-w", "4", "/turtle1/pose"),
        lambda: graph.run("echo", "-n", "1", "/bytes"),
        lambda: graph.run("echo", "-n", "1", "/poses"),
    )
    js, header, element, noarr, nostr, field, width, raw, poses = (ok(r) for r in results)
    assert js == JS
    assert header == 'seq: 1\nstamp: \n  secs: 1795311367\n  nsecs: 122221231\nframe_id: "base"\n---\n'
    assert element == "2.5\n---\n"
    assert 'name: "<array type: string, length: 2>"\nposition: "<array type: float64, length: 2>"\n' in noarr
    assert '  frame_id: "<string length: 4>"\nname: "<array type: string, length: 2>"\nposition: [1.0, 2.5]\n' in nostr
    assert field == "5.544444561004639\n---\n"
    assert width == "x: 5.54\ny: 5.54\ntheta: 0.00\nlinear_velocity: 0.00\nangular_velocity: 0.00\n---\n"
    assert "data: [1, 2, 255]\n---\n" in raw
    assert poses.startswith('header: \n  seq: 1\n')
    assert "poses: \n  - \n    position: \n      x: 1.0\n      y: 0.0\n      z: 0.0\n    orientation: \n" in poses
    assert "  - \n    position: \n      x: 2.0\n      y: 3.0\n      z: 0.5\n" in poses


def test_echo_csv(graph: Graph) -> None:
    js, pose, field = parallel(lambda: graph.run("echo", "-n", "1", "-p", "/js"),
                               lambda: graph.run("echo", "-n", "2", "-p", "/turtle1/pose"),
                               lambda: graph.run("echo", "-n", "1", "-p", "/js/position"))
    assert ok(js) == ("%time,field.header.seq,field.header.stamp,field.header.frame_id,field.name0,field.name1,"
                      "field.position0,field.position1\n1795311367122221231,1,1795311367122221231,base,a,b,1.0,2.5\n")
    lines = ok(pose).splitlines()
    assert lines[0] == "%time,field.x,field.y,field.theta,field.linear_velocity,field.angular_velocity"
    assert len(lines) == 3
    for line in lines[1:]:
        assert re.fullmatch(r"\d{19},5\.544444561004639,5\.544444561004639,0\.0,0\.0,0\.0", line), line
    assert re.fullmatch(r"%time,field0,field1\n\d{19},1\.0,2\.5\n", ok(field))


def test_echo_filter_offset_and_clear(graph: Graph) -> None:
    matching, offset, clear = parallel(
        lambda: graph.run("echo", "-n", "2", "--filter", "m.x > 1 and topic == '/pose2d'", "/pose2d"),
        lambda: graph.run("echo", "-n", "1", "--offset", "/js/header/stamp"),
        lambda: graph.run("echo", "-n", "1", "-c", "/pose2d/theta"))
    assert ok(matching) == "x: 1.5\ny: 2.0\ntheta: 0.25\n---\n" * 2
    secs = int(re.fullmatch(r"\nsecs: (-?\d+)\nnsecs: +\d+\n---\n", ok(offset)).group(1))  # type: ignore[union-attr]
    assert -2 * 10**9 < secs < 0  # the stamp lies in the past: an offset from now is negative
    assert ok(clear) == "\033[2J\033[;H0.25\n---\n"


def test_echo_type_kame_does_not_have(graph: Graph) -> None:
    whole, field = parallel(lambda: graph.run("echo", "-n", "1", "/custom"),
                            lambda: graph.run("echo", "-n", "1", "/custom/where/y"))
    assert ok(whole) == 'name: "widget"\nsizes: [3, 4]\nwhere: \n  x: 1.0\n  y: 2.0\n  z: 3.0\n---\n'
    assert ok(field) == "2.0\n---\n"


def test_echo_waits_for_a_topic_not_yet_published(graph: Graph) -> None:
    echo = graph.start("echo", "-n", "1", "/later")
    try:
        deadline = time.monotonic() + 10
        while not echo.err and time.monotonic() < deadline:
            time.sleep(0.05)
        assert echo.err == ["WARNING: topic [/later] does not appear to be published yet\n"]
        pub = graph.run("pub", "-1", "/later", "std_msgs/String", "hi")
        assert ok(pub) == "publishing and latching message for 3.0 seconds\n"
        assert echo.popen.wait(10) == 0
    finally:
        out, _ = echo.stop()
    assert out == 'data: "hi"\n---\n'


# ---------------------------------------------------------------- hz, bw, delay


def run_until(graph: Graph, done: Callable[[str], bool], *args: str, timeout: float = 30.0) -> tuple[str, str]:
    """Run `rostopic *args` until its output satisfies `done` (or `timeout` passes), then Ctrl-C it.

    Not a fixed run time: the tool's start-up (a second or more on a loaded machine) would eat
    into the reports a fixed time leaves room for."""
    proc = graph.start(*args)
    deadline = time.monotonic() + timeout
    while not done("".join(proc.out)) and proc.popen.poll() is None and time.monotonic() < deadline:
        time.sleep(0.05)
    out, err = proc.stop()
    assert proc.popen.returncode == 0, err
    assert "Traceback" not in err, err
    return out, err


HZ_REPORT = (r"average rate: ([\d.]+)\n\tmin: \d+\.\d{3}s max: \d+\.\d{3}s std dev: \d+\.\d{5}s "
             r"window: (\d+)\n")
BW_REPORT = r"average: ([\d.]+)B/s\n\tmean: 24\.00B min: 24\.00B max: 24\.00B window: (\d+)\n"
DELAY_REPORT = (r"average delay: \d+\.\d{3}\n\tmin: -?\d+\.\d{3}s max: \d+\.\d{3}s std dev: \d+\.\d{5}s "
                r"window: \d+\n")
MULTI_TABLE = (r"    topic        rate +min_delta +max_delta +std_dev +window\n=+\n"
               r"/turtle1/pose   \S+ .*\n/pose2d         \S+ .* 5 +\n\n")


def test_hz_bw_delay(graph: Graph) -> None:
    with ThreadPoolExecutor(4) as pool:
        hz_f = pool.submit(run_until, graph, lambda out: len(re.findall(HZ_REPORT, out)) >= 2,
                           "hz", "/turtle1/pose")
        bw_f = pool.submit(run_until, graph, lambda out: len(re.findall(BW_REPORT, out)) >= 2,
                           "bw", "-w", "10", "/pose2d")
        delay_f = pool.submit(run_until, graph, lambda out: re.search(DELAY_REPORT, out) is not None,
                              "delay", "/stamped")
        multi_f = pool.submit(run_until, graph, lambda out: re.search(MULTI_TABLE, out) is not None,
                              "hz", "-w", "5", "/turtle1/pose", "/pose2d")
    hz, _ = hz_f.result()
    lines = hz.splitlines()
    assert lines[0] == "subscribed to [/turtle1/pose]"
    reports = re.findall(HZ_REPORT, hz)
    assert len(reports) >= 2, hz
    assert all(15 < float(rate) < 25 for rate, _ in reports), hz
    bw, _ = bw_f.result()
    assert bw.startswith("subscribed to [/pose2d]\n")
    found = re.findall(BW_REPORT, bw)
    assert len(found) >= 2 and all(int(w) <= 10 for _, w in found), bw
    delay, _ = delay_f.result()
    assert delay.startswith("subscribed to [/stamped]\n")
    assert re.search(DELAY_REPORT, delay), delay
    multi, _ = multi_f.result()
    assert multi.startswith("subscribed to [/turtle1/pose]\nsubscribed to [/pose2d]\n")
    assert re.search(MULTI_TABLE, multi), multi


def test_hz_filter(graph: Graph) -> None:
    out, _ = run_until(graph, lambda out: out.count("no new messages\n") >= 2, "hz", "--filter", "m.x > 100",
                       "/pose2d")
    # a report a second, and every one says nothing got through the filter
    lines = out.splitlines()
    assert lines[0] == "subscribed to [/pose2d]" and len(lines) >= 3, out
    assert set(lines[1:]) == {"no new messages"}, out


# ---------------------------------------------------------------- pub


def received(graph: Graph, prefix: str, count: int = 1, timeout: float = 10.0) -> list[str]:
    deadline = time.monotonic() + timeout
    while time.monotonic() < deadline:
        lines = [line.strip() for line in graph.peer.out if line.startswith(prefix)]
        if len(lines) >= count:
            return lines
        time.sleep(0.05)
    return [line.strip() for line in graph.peer.out if line.startswith(prefix)]


def test_pub_once_positional_with_negatives(graph: Graph) -> None:
    graph.peer.out.clear()
    t0 = time.monotonic()
    result = graph.run("pub", "-1", "/turtle1/cmd_vel", "geometry_msgs/Twist", "--", "[2,0,0]", "[0,0,-2]")
    took = time.monotonic() - t0
    assert ok(result) == "publishing and latching message for 3.0 seconds\n"
    assert took >= 3.0  # latched for 3 s; start-up on top of that grows with the machine's load
    assert received(graph, "cmd_vel") == ["cmd_vel 2.0 0.0 0.0 0.0 0.0 -2.0"]


def test_pub_yaml_dict_verbose_and_single_field(graph: Graph) -> None:
    graph.peer.out.clear()
    twist, chatter = parallel(
        lambda: graph.run("pub", "-1", "-v", "/turtle1/cmd_vel", "geometry_msgs/Twist",
                          "linear: {x: 2.0}\nangular: {z: 1.8}"),
        lambda: graph.run("pub", "-1", "/chatter", "std_msgs/String", "hello"))
    assert ok(twist) == ("publishing and latching [linear: \n  x: 2.0\n  y: 0.0\n  z: 0.0\nangular: \n  x: 0.0\n"
                         "  y: 0.0\n  z: 1.8] for 3.0 seconds\n")
    assert ok(chatter) == "publishing and latching message for 3.0 seconds\n"
    assert received(graph, "cmd_vel") == ["cmd_vel 2.0 0.0 0.0 0.0 0.0 1.8"]
    assert received(graph, "chatter") == ["chatter hello"]


def test_pub_rate_and_latch(graph: Graph) -> None:
    graph.peer.out.clear()
    proc = graph.start("pub", "-r", "10", "/chatter", "std_msgs/String", "data: tick")
    try:
        lines = received(graph, "chatter", count=5)
    finally:
        out, err = proc.stop()
    assert len(lines) >= 5 and set(lines) == {"chatter tick"}
    assert out == "" and "Traceback" not in err


def test_pub_latches_until_ctrl_c(graph: Graph) -> None:
    pub = graph.start("pub", "/latched", "std_msgs/String", "hi")
    try:
        pub.wait_line("publishing and latching message. Press ctrl-C to terminate")
        assert ok(graph.run("echo", "-n", "1", "/latched")) == 'data: "hi"\n---\n'
    finally:
        out, err = pub.stop()
    assert pub.popen.returncode == 0 and "Traceback" not in err
    assert out == "publishing and latching message. Press ctrl-C to terminate\n"


def test_pub_header_auto_and_now_with_substitution(graph: Graph) -> None:
    echo = graph.start("echo", "-n", "2", "-p", "/stamped_pub")
    try:
        time.sleep(0.5)
        before = time.time_ns()
        pub = graph.start("pub", "-s", "-r", "5", "/stamped_pub", "geometry_msgs/PointStamped",
                          "{header: auto, point: {x: 1}}")
        assert echo.popen.wait(10) == 0
        pub.stop()
    finally:
        out, _ = echo.stop()
    lines = out.splitlines()
    assert lines[0] == "%time,field.header.seq,field.header.stamp,field.header.frame_id,field.point.x,field.point.y," \
                       "field.point.z"
    stamps = [int(line.split(",")[0]) for line in lines[1:]]
    assert len(stamps) == 2 and before < stamps[0] < stamps[1] < time.time_ns()
    seqs = [int(line.split(",")[1]) for line in lines[1:]]
    assert seqs[1] == seqs[0] + 1  # header.seq counts up, and -s stamps each message anew


def test_pub_from_file(graph: Graph) -> None:
    graph.peer.out.clear()
    data = graph.home / "msgs.yaml"
    data.write_text("data: one\n---\ndata: two\n")
    result = graph.run("pub", "-f", str(data), "/chatter", "std_msgs/String")
    assert ok(result) == "publishing and latching message for 3.0 seconds\n" * 2
    assert received(graph, "chatter", count=2) == ["chatter one", "chatter two"]


# ---------------------------------------------------------------- bad input


def test_pub_errors(graph: Graph) -> None:
    results = parallel(
        lambda: graph.run("pub", "-1", "/x", "std_msgs/Foo", "1"),
        lambda: graph.run("pub", "-1", "/x", "geometry_msgs/Twist", "{linear: {q: 1}}"),
        lambda: graph.run("pub", "-1", "/x", "geometry_msgs/Twist", "[1, 2]"),
        lambda: graph.run("pub", "-1", "/x", "geometry_msgs/Twist", "[1,2,3]", "[1,2,3]", "[4]"),
        lambda: graph.run("pub", "-1", "/x", "std_msgs/Int32", "hello"),
        lambda: graph.run("pub", "-1", "/x", "geometry_msgs/Twist", "{linear: 3}"),
        lambda: graph.run("pub", "-1", "-r", "3", "/x", "std_msgs/Int32", "1"),
        lambda: graph.run("pub", "-1", "/x", "geometry_msgs/Twist", "[1,2"),
    )
    args_are = "\n\nArgs are: [linear.x linear.y linear.z angular.x angular.y angular.z]\n"
    assert one_error(results[0]) == ("ERROR: invalid message type: std_msgs/Foo.\n"
                                     "If this is a valid message type, perhaps you need to type 'rosmake std_msgs'\n")
    assert one_error(results[1]) == "ERROR: No field name [linear.q]" + args_are
    assert one_error(results[2]) == ("ERROR: Not enough arguments:\n * Given: [[1, 2]]\n"
                                     " * Expected: ['linear', 'angular']" + args_are)
    assert one_error(results[3]).startswith("ERROR: Too many arguments:\n * Given: [[1, 2, 3], [1, 2, 3], [4]]\n")
    assert one_error(results[4]) == ("ERROR: Unable to publish message. One of the fields has an incorrect type:\n"
                                     "  field data must be an integer type (int32), got str 'hello'\n\n"
                                     "msg file:\nint32 data\n")  # Int32.msg has no final newline
    assert one_error(results[5]).startswith("ERROR: Field [linear] is a message")
    assert one_error(results[6], 2).endswith("rostopic: error: You cannot select both -r and -1 (--once)\n")
    assert "rostopic: error: Argument error: while parsing a flow sequence" in one_error(results[7], 2)
    assert "/x" not in ok(graph.run("list"))  # nothing registered for bad input


def test_usage(graph: Graph) -> None:
    bare = graph.run()
    assert bare.returncode == 64
    assert bare.stdout.startswith("rostopic is a command-line tool for printing information about ROS Topics.\n")
    assert "\trostopic hz\tdisplay publishing rate of topic    \n" in bare.stdout
    assert one_error(graph.run("echo"), 2) == ("Usage: rostopic echo [options] /topic\n\n"
                                               "rostopic: error: topic must be specified\n")
    assert one_error(graph.run("echo", "-n", "x", "/js"), 2).endswith("rostopic: error: COUNT must be an integer\n")


def test_no_master(graph: Graph, tmp_path: Path) -> None:
    env = ros_env(tmp_path, f"http://127.0.0.1:{free_port()}/")
    commands = [("list",), ("info", "/x"), ("type", "/x"), ("find", "std_msgs/String"), ("echo", "/x"),
                ("hz", "/x"), ("bw", "/x"), ("delay", "/x"), ("pub", "/x", "std_msgs/Int32", "1")]
    results = parallel(*[(lambda c=c: graph.run(*c, env=env)) for c in commands])
    for command, result in zip(commands, results, strict=True):
        assert one_error(result) == "ERROR: Unable to communicate with master!\n", command
        assert result.stdout == "", command


# ---------------------------------------------------------------- the same commands from Debian's rostopic

debian = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rostopic) is not installed")

SAME = [
    ("list",), ("list", "-v"), ("list", "-p"), ("list", "-s"), ("list", "/turtle1"),
    ("info", "/turtle1/cmd_vel"), ("info", "/js"), ("info", "/nope"),
    ("type", "/turtle1/cmd_vel"), ("type", "/pose2d/theta"), ("type", "/js/header/stamp"), ("type", "/nope"),
    ("find", "sensor_msgs/JointState"), ("find", "std_msgs/Nothing"),
    ("echo", "-n", "1", "/js"), ("echo", "-n", "1", "/js/header"), ("echo", "-n", "1", "/js/position[1]"),
    ("echo", "-n", "1", "--noarr", "/js"), ("echo", "-n", "1", "--nostr", "/js"), ("echo", "-n", "1", "/poses"),
    ("echo", "-n", "1", "-p", "/js"), ("echo", "-n", "1", "-w", "3", "/pose2d"), ("echo", "-n", "1", "/js/name"),
    ("echo", "-n", "2", "--filter", "m.theta > 0.2", "/pose2d"), ("echo", "-n", "1", "/bytes"),
    ("echo", "-n", "1", "-p", "--noarr", "/poses"),
    ("pub", "-1", "/x", "std_msgs/Foo", "1"), ("pub", "-1", "/x", "geometry_msgs/Twist", "{linear: {q: 1}}"),
    ("pub", "-1", "/x", "geometry_msgs/Twist", "[1, 2]"), ("pub", "-1", "-r", "1", "/x", "std_msgs/Int32", "1"),
    ("echo",), ("pub",), ("bogus",),
]


def normalise(text: str) -> str:
    text = mask(text)
    return "\n".join(line for line in text.splitlines()
                     if "rosdep" not in line)  # Debian's rospkg complains about an empty rosdep view


@debian
@pytest.mark.parametrize("command", SAME, ids=" ".join)
def test_same_output_as_debian_rostopic(graph: Graph, command: tuple[str, ...]) -> None:
    if command[0] in ("list", "info"):  # these look at registrations, which a running tool changes
        real, ours = graph.debian(*command), graph.run(*command)
    else:
        real, ours = parallel(lambda: graph.debian(*command), lambda: graph.run(*command))
    assert (normalise(ours.stdout), ours.returncode) == (normalise(real.stdout), real.returncode)
    assert normalise(ours.stderr) == normalise(real.stderr)


def wait_for_waiting(echo: Proc, topic: str, timeout: float = 30.0) -> None:
    """Until `echo` is up and polling the master for `topic`: a `pub -1` latches for 3 s only, and
    an echo still starting (Debian's rospy takes a second or two on a loaded machine) missed it."""
    warning = f"WARNING: topic [{topic}] does not appear to be published yet\n"
    deadline = time.monotonic() + timeout
    while warning not in echo.err:
        assert echo.popen.poll() is None and time.monotonic() < deadline, "".join(echo.out + echo.err)
        time.sleep(0.05)


@debian
def test_debian_echo_sees_kame_pub(graph: Graph) -> None:
    echo = Proc([SYSTEM_PYTHON, "/usr/bin/rostopic", "echo", "-n", "1", "/from_kame"], graph.env)
    try:
        wait_for_waiting(echo, "/from_kame")
        pub = graph.run("pub", "-1", "/from_kame", "geometry_msgs/Twist", "--", "[2,0,0]", "[0,0,-2]")
        assert ok(pub) == "publishing and latching message for 3.0 seconds\n"
        assert echo.popen.wait(10) == 0
    finally:
        out, _ = echo.stop()
    assert out == ("linear: \n  x: 2.0\n  y: 0.0\n  z: 0.0\nangular: \n  x: 0.0\n  y: 0.0\n  z: -2.0\n---\n")


@debian
def test_kame_echo_of_debian_pub(graph: Graph) -> None:
    echo = graph.start("echo", "-n", "1", "/from_debian")
    try:
        wait_for_waiting(echo, "/from_debian")
        pub = graph.debian("pub", "-1", "/from_debian", "sensor_msgs/JointState",
                           "{header: {stamp: {secs: 7, nsecs: 5}, frame_id: base}, name: [a, b], position: [1, 2.5]}")
        assert pub.returncode == 0, pub.stderr
        assert echo.popen.wait(10) == 0
    finally:
        out, _ = echo.stop()
    assert out == JS.replace("1795311367", "7").replace("122221231", "        5")
