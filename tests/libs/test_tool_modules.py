"""rostopic, rosservice, rosnode, rosparam and rosmsg as modules: against a live kame node, and
against Debian's real modules where they run (the same calls, the same answers)."""

from __future__ import annotations

import json
import random
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

import rosgraph
import rosmsg
import rosnode
import rosparam
import rosservice
import rostopic

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master
from . import debian
from .stats_driver import run as run_stats

NODE = Path(__file__).with_name("tools_node.py")
STATS = Path(__file__).with_name("stats_driver.py")


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(Path(tmp_path_factory.mktemp("tools")), uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    node = None
    try:
        wait_for_master(uri, proc=master)
        node = Proc([sys.executable, str(NODE)], env)
        node.wait_line("ready")
        yield env
    finally:
        if node is not None:
            node.stop()
        master.stop()


@pytest.fixture
def on_graph(graph: dict[str, str], monkeypatch: pytest.MonkeyPatch) -> dict[str, str]:
    monkeypatch.setenv("ROS_MASTER_URI", graph["ROS_MASTER_URI"])
    monkeypatch.delenv("ROS_NAMESPACE", raising=False)
    monkeypatch.setattr("sys.argv", ["test"])
    return graph


def test_rostopic_types_and_classes(on_graph: dict[str, str]) -> None:
    from geometry_msgs.msg import PoseStamped

    assert rostopic.get_topic_type("/chatter") == ("std_msgs/String", "/chatter", None)
    topic_type, real_topic, msg_eval = rostopic.get_topic_type("/pose/pose/position/x")
    assert (topic_type, real_topic) == ("geometry_msgs/PoseStamped", "/pose")
    msg = PoseStamped()
    msg.pose.position.x = 2.5
    assert msg_eval is not None and msg_eval(msg) == 2.5
    assert rostopic.get_topic_class("/pose")[:2] == (PoseStamped, "/pose")
    assert rostopic.get_topic_type("/nothing") == (None, None, None)
    assert rostopic.get_topic_class("/nothing") == (None, None, None)
    pubs, subs = rostopic.get_topic_list()
    assert sorted(pubs) == [("/chatter", "std_msgs/String", ["/tools_node"]),
                            ("/pose", "geometry_msgs/PoseStamped", ["/tools_node"]),
                            ("/rosout", "rosgraph_msgs/Log", ["/tools_node"])]
    assert subs == []  # no rosout node on this master
    assert rostopic.get_topic_list(master=rosgraph.Master("/test")) == (pubs, subs)
    assert "Publishers: \n * /tools_node (" in rostopic.get_info_text("/chatter")
    with pytest.raises(rostopic.ROSTopicException, match="Unknown topic /nothing"):
        rostopic.get_info_text("/nothing")


def test_rostopic_without_master_raises_io_exception(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("ROS_MASTER_URI", f"http://127.0.0.1:{free_port()}/")
    with pytest.raises(rostopic.ROSTopicIOException):
        rostopic.get_topic_type("/chatter")
    with pytest.raises(rosnode.ROSNodeIOException):
        rosnode.get_node_names()


def test_rosservice_type_call_and_listing(on_graph: dict[str, str]) -> None:
    from rospy_tutorials.srv import AddTwoInts

    assert rosservice.get_service_type("/add_two_ints") == "rospy_tutorials/AddTwoInts"
    assert rosservice.get_service_type("/nothing") is None
    assert rosservice.get_service_class_by_name("/add_two_ints") is AddTwoInts
    assert "/add_two_ints" in rosservice.get_service_list()
    assert rosservice.get_service_list(node="/tools_node") == ["/add_two_ints", "/tools_node/get_loggers",
                                                                "/tools_node/set_logger_level"]
    assert rosservice.get_service_list(node="/tools_node", include_nodes=True) == [
        ("/add_two_ints", ["/tools_node"]), ("/tools_node/get_loggers", ["/tools_node"]),
        ("/tools_node/set_logger_level", ["/tools_node"])]
    assert ("/add_two_ints", ["/tools_node"]) in rosservice.get_service_list(include_nodes=True)
    assert rosservice.get_service_node("/add_two_ints") == "/tools_node"
    assert str(rosservice.get_service_uri("/add_two_ints")).startswith("rosrpc://")
    request, response = rosservice.call_service("/add_two_ints", [3, 4])
    assert (request.a, request.b, response.sum) == (3, 4, 7)
    _, response = rosservice.call_service("/add_two_ints", [{"a": 10, "b": -2}], service_class=AddTwoInts)
    assert response.sum == 8
    with pytest.raises(rosservice.ROSServiceException, match="Incompatible arguments to call service"):
        rosservice.call_service("/add_two_ints", [1, 2, 3])
    with pytest.raises(rosservice.ROSServiceException, match=r"Service \[/nothing\] is not available"):
        rosservice.call_service("/nothing", [])


def test_rosnode_names_ping_and_kill(on_graph: dict[str, str], capsys: Any) -> None:
    assert "/tools_node" in rosnode.get_node_names()
    assert rosnode.get_node_names("/other") == []
    assert rosnode.rosnode_ping("/tools_node", max_count=1)
    assert not rosnode.rosnode_ping("/ghost", max_count=1)
    assert "cannot ping [/ghost]: unknown node" in capsys.readouterr().err
    assert rosnode.kill_nodes(["/ghost"]) == ([], ["/ghost"])
    assert rosnode.get_api_uri(None, "/tools_node") is not None


def test_rosparam_load_upload_get_set(on_graph: dict[str, str], tmp_path: Path) -> None:
    path = tmp_path / "params.yaml"
    path.write_text("a: 1\nangle: !degrees 180\nnested: {b: [1, 2], c: text}\n---\n_ns: sub\nd: true\n")
    documents = rosparam.load_file(str(path), default_namespace="/cfg")
    assert documents[1] == ({"d": True}, "/cfg/sub")
    for values, ns in documents:
        rosparam.upload_params(ns, values)
    assert rosparam.get_param("/cfg/nested") == {"b": [1, 2], "c": "text"}
    assert rosparam.get_param("/cfg/angle") == pytest.approx(3.14159265)
    assert rosparam.get_param("/cfg/sub/d") is True
    rosparam.set_param("/cfg/nested", "{e: 2.5}")
    assert rosparam.get_param("/cfg/nested") == {"b": [1, 2], "c": "text", "e": 2.5}  # merged
    assert "/cfg/sub/d" in rosparam.list_params("/cfg")
    rosparam.delete_param("/cfg/sub")
    with pytest.raises(rosgraph.MasterError):
        rosparam.get_param("/cfg/sub/d")
    with pytest.raises(rosparam.RosParamException, match="does not exist"):
        rosparam.load_file(str(tmp_path / "missing.yaml"))
    with pytest.raises(rosparam.RosParamException, match="global / can only be set to a dictionary"):
        rosparam.upload_params("/", 3)


def test_rosmsg_texts() -> None:
    assert rosmsg.get_msg_text("geometry_msgs/Point") == "float64 x\nfloat64 y\nfloat64 z\n"
    assert rosmsg.get_srv_text("std_srvs/SetBool") == "bool data\n---\nbool success\nstring message\n"
    with pytest.raises(rosmsg.ROSMsgException, match=r"Unable to load msg \[nope/Nope\]"):
        rosmsg.get_msg_text("nope/Nope")


def stats_request() -> dict[str, Any]:
    rng = random.Random(7)
    hz_cases = []
    for window in (-1, 3, 10):
        at, arrivals = 100.0, []
        for _ in range(60):
            at += rng.choice([0.01, 0.02, 0.1, 0.5])
            arrivals.append([rng.choice(["/a", "/b"]), round(at, 3)])
        arrivals.insert(30, ["/a", 0.0])  # a clock reset
        arrivals.insert(40, ["/b", 50.0])  # time going back: starts over
        for topics in (["/a"], ["/a", "/b"]):
            hz_cases.append({"window": window, "arrivals": arrivals, "topics": topics})
    bw_cases = []
    for window in (0, 4, 100):
        at, arrivals = 10.0, []
        for _ in range(40):
            at += rng.choice([0.001, 0.01, 0.3])
            arrivals.append([round(at, 3), rng.choice([10, 900, 5000, 2_000_000])])
        bw_cases.append({"window": window, "arrivals": arrivals})
    delay_cases = []
    for window in (-1, 2, 8):
        at, arrivals = 200.0, []
        for _ in range(50):
            at += rng.choice([0.01, 0.1, 0.3])
            arrivals.append([round(at, 3), round(at - rng.choice([0.0, 0.002, 0.05, 1.5]), 3)])
        arrivals.insert(10, [at, -1.0])  # a message without a header
        arrivals.insert(20, [0.0, 1.0])  # a clock reset
        arrivals.insert(30, [50.0, 49.0])  # time going back: starts over
        delay_cases.append({"window": window, "arrivals": arrivals})
    return {"hz": hz_cases, "bw": bw_cases, "delay": delay_cases}


@pytest.mark.skipif(not debian.has("rostopic"), reason="Debian's rostopic is not installed")
def test_hz_bw_and_delay_report_as_debians_rostopic() -> None:
    request = stats_request()
    theirs = debian.run(STATS, request)
    original = rostopic.time  # type: ignore[attr-defined]
    try:
        ours = run_stats(request)
    finally:
        rostopic.time = original  # type: ignore[attr-defined]
    assert "average rate" in theirs[0][1] and "average: " in theirs[-4]
    assert "average delay: " in theirs[-1][1] and "time has reset" in theirs[-1][1]
    assert "no new messages" in theirs[-1][1]
    assert ours == theirs


@pytest.mark.skipif(not debian.has("rostopic", "rosservice", "rosnode"), reason="Debian's ROS tools are not installed")
def test_debians_modules_see_the_kame_graph_as_kames_do(on_graph: dict[str, str], tmp_path: Path) -> None:
    script = tmp_path / "ask.py"
    script.write_text(
        "import json, sys, rostopic, rosservice, rosnode\n"
        "t = rostopic.get_topic_type('/pose/pose/position')\n"
        "print(json.dumps([t[0], t[1], rostopic.get_topic_type('/chatter')[:2],"
        " rosservice.get_service_type('/add_two_ints'), rosservice.get_service_node('/add_two_ints'),"
        " '/tools_node' in rosnode.get_node_names(), [sorted(side) for side in rostopic.get_topic_list()],"
        " sorted(rosservice.get_service_list(include_nodes=True))]))\n")
    theirs = _run_with_env(script, on_graph)
    t = rostopic.get_topic_type("/pose/pose/position")
    ours = [t[0], t[1], list(rostopic.get_topic_type("/chatter")[:2]), rosservice.get_service_type("/add_two_ints"),
            rosservice.get_service_node("/add_two_ints"), "/tools_node" in rosnode.get_node_names(),
            [sorted(side) for side in rostopic.get_topic_list()], rosservice.get_service_list(include_nodes=True)]
    assert json.loads(json.dumps(ours)) == theirs  # tuples as JSON lists, as theirs come


def _run_with_env(script: Path, env: dict[str, str]) -> Any:
    import subprocess

    result = subprocess.run([str(debian.SYSTEM_PYTHON), str(script)], capture_output=True, text=True, timeout=60,
                            env=env)
    assert result.returncode == 0, result.stderr
    return json.loads(result.stdout)


DEBIAN_NODE = """
import rospy
from geometry_msgs.msg import PoseStamped
from std_srvs.srv import SetBool, SetBoolResponse
rospy.init_node("debian_node")
pose = rospy.Publisher("pose", PoseStamped, queue_size=10)
rospy.Service("switch", SetBool, lambda req: SetBoolResponse(req.data, "on" if req.data else "off"))
print("ready", flush=True)
rate = rospy.Rate(50)
while not rospy.is_shutdown():
    pose.publish(PoseStamped())
    rate.sleep()
"""


@pytest.mark.skipif(not debian.has("rospy", "std_srvs.srv", "geometry_msgs.msg"),
                    reason="Debian's rospy is not installed")
def test_kames_modules_on_a_debian_rospy_node(tmp_path: Path, monkeypatch: pytest.MonkeyPatch) -> None:
    # the other way round: a node of Debian's real rospy, asked and killed through kame's modules
    from geometry_msgs.msg import PoseStamped

    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path, uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), env)
    node = None
    try:
        wait_for_master(uri, proc=master)
        node = Proc([str(debian.SYSTEM_PYTHON), "-c", DEBIAN_NODE], {**debian.debian_env(), **env})
        node.wait_line("ready")
        monkeypatch.setenv("ROS_MASTER_URI", uri)
        monkeypatch.setattr("sys.argv", ["test"])
        # a process that is no node keeps its first master for service calls, as rospy does: this one is new
        monkeypatch.setattr("kame.client.services._anonymous_master", None)
        assert rostopic.get_topic_class("/pose")[:2] == (PoseStamped, "/pose")
        assert rosservice.get_service_type("/switch") == "std_srvs/SetBool"
        request, response = rosservice.call_service("/switch", [True])
        assert request.data is True and (response.success, response.message) == (True, "on")
        assert rosnode.rosnode_ping("/debian_node", max_count=1)
        assert rosnode.kill_nodes(["/debian_node"]) == (["/debian_node"], [])
        node.popen.wait(30)  # the real rospy node shut down on kame's kill
    finally:
        if node is not None:
            node.stop()
        master.stop()


def test_the_tools_command_parts(on_graph: dict[str, str], capsys: Any) -> None:
    """The command-side names of rostopic, rosservice and rosnode that ROS code also calls."""
    from rospy_tutorials.srv import AddTwoInts

    assert rostopic.find_by_type("std_msgs/String") == ["/chatter"]
    assert rostopic.get_api(rosgraph.Master("/test"), "/tools_node").startswith("http://")
    assert rosservice.rosservice_find("rospy_tutorials/AddTwoInts") == ["/add_two_ints"]
    assert rosservice.has_service_args("/add_two_ints") and rosservice.get_service_args("/add_two_ints") == "a b"
    headers = rosservice.get_service_headers("/add_two_ints", str(rosservice.get_service_uri("/add_two_ints")))
    assert (headers["type"], headers["md5sum"]) == ("rospy_tutorials/AddTwoInts", AddTwoInts._md5sum)
    with pytest.raises(rosservice.ROSServiceException, match="invalid RPC URI"):
        rosservice.get_service_headers("/x", "http://nowhere")
    assert "Publications: \n * /chatter [std_msgs/String]" in rosnode.get_node_info_description("/tools_node")
    capsys.readouterr()
    rosnode.rosnode_listnodes()
    assert capsys.readouterr().out == "/tools_node\n"
    rosnode.rosnode_listnodes(list_all=True)
    assert capsys.readouterr().out.endswith(" \t/tools_node\n")


def test_rosparam_yaml_hooks_and_printing(capsys: Any) -> None:
    import yaml

    class Loader(yaml.SafeLoader):
        pass

    Loader.add_constructor("!radians", rosparam.construct_angle_radians)
    Loader.add_constructor("!degrees", rosparam.construct_angle_degrees)
    Loader.add_constructor("tag:yaml.org,2002:binary", rosparam.construct_yaml_binary)
    loaded = yaml.load("a: !radians pi/2\nb: !degrees 180\nc: !!binary aGk=\n", Loader=Loader)
    assert loaded["a"] == pytest.approx(1.5707963) and loaded["b"] == pytest.approx(3.14159265)
    assert isinstance(loaded["c"], rosparam.Binary) and loaded["c"].data == b"hi"
    with pytest.raises(rosparam.RosParamException, match="invalid radian expression"):
        yaml.load("a: !radians __import__('os')\n", Loader=Loader)
    assert rosparam.pattern.match("rad(pi)") and not rosparam.pattern.match("deg(90)")
    rosparam.print_params({"a": 1, "n": {"b": "x"}}, "/ns")
    assert capsys.readouterr().out == "/ns/a=1\n/ns/n/b=x\n"


def test_rosnode_machines_and_connections(on_graph: dict[str, str]) -> None:
    master = rosgraph.Master("/test")
    assert rosnode.get_machines_by_nodes() == ["127.0.0.1"]
    assert rosnode.get_nodes_by_machine("127.0.0.1") == ["/tools_node"]
    assert rosnode.get_nodes_by_machine("localhost") == ["/tools_node"]
    with pytest.raises(rosnode.ROSNodeException, match="cannot resolve machine name"):
        rosnode.get_nodes_by_machine("no-such-host.invalid")
    uri = str(master.lookupNode("/tools_node"))
    state = master.getSystemState()
    assert rosnode.lookup_uri(master, state, "/chatter", uri) == f"/tools_node ({uri})"
    assert rosnode.lookup_uri(master, state, "/chatter", "http://elsewhere:1/") == "http://elsewhere:1/"
    assert rosnode.get_node_connection_info_description(uri, master).startswith("Pid: ")
    with pytest.raises(rosnode.ROSNodeIOException, match="Communication with node"):
        rosnode.get_node_connection_info_description(f"http://127.0.0.1:{free_port()}/", master)


def test_rosnode_cleanup_lists_leave_the_listed_alone(on_graph: dict[str, str], capsys: Any) -> None:
    master = rosgraph.Master("/test")
    before = master.getSystemState()
    rosnode.cleanup_master_blacklist(master, ["/ghost"])
    assert capsys.readouterr().out == "Unregistering /ghost\n"
    rosnode.cleanup_master_whitelist(master, ["/tools_node"])
    assert master.getSystemState() == before


def test_rostopic_publishing_functions(graph: dict[str, str], tmp_path: Path) -> None:
    documents = tmp_path / "docs.yaml"
    documents.write_text("data: one\n---\ndata: two\n")
    publisher = Proc([sys.executable, str(Path(__file__).with_name("rostopic_pub_driver.py")), str(documents)], graph)
    try:
        publisher.wait_line("published")
        echo = subprocess.run(kame_command("kame.cli.rostopic", "echo", "-n", "1", "/facade_out"), env=graph,
                              capture_output=True, text=True, timeout=60)
        assert echo.stdout == 'data: "hi"\n---\n', echo.stderr
        assert publisher.wait_line("subscriber came:", timeout=60) == "subscriber came: True\n"
        out = "".join(publisher.out)
        assert "bad type: invalid message type: std_msgs/Nope." in out
        assert "class: std_msgs/String /facade_out" in out
        assert "bad args: Too many arguments:" in out
        assert "file: [[{'data': 'one'}], [{'data': 'two'}]]" in out
        assert "no param: parameter does not exist: /no_such_param" in out
    finally:
        publisher.stop()


def test_rostopic_param_publish(graph: dict[str, str]) -> None:
    publisher = Proc([sys.executable, str(Path(__file__).with_name("rostopic_param_driver.py"))], graph)
    try:
        assert publisher.wait_line("heard") == "heard p1\n"
        done = subprocess.run(kame_command("kame.cli.rosparam", "set", "/facade_msg/data", "p2"), env=graph,
                              capture_output=True, text=True, timeout=60)
        assert done.returncode == 0, done.stderr
        assert publisher.wait_line("heard p2") == "heard p2\n"
        assert publisher.wait_line("stopped") == "stopped True\n"
    finally:
        publisher.stop()
