"""rosbridge_websocket.launch with real clients from Python: roslibpy (what Python users of
rosbridge run), the websockets library's client for frames no well-behaved client sends, a kame
rospy node calling a service roslibpy provides, and Debian's rospy publishing what roslibpy sees."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
import threading
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import cbor2
import pytest
from websockets.sync.client import connect

from tests.support import SYSTEM_PYTHON, Proc, have_debian_ros
from tests.web.rosbridge_graph import Graph, bridge_graph

roslibpy = pytest.importorskip("roslibpy")

pytestmark = pytest.mark.timeout(180)


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Graph]:
    with bridge_graph(tmp_path_factory.mktemp("rosbridge")) as live:
        yield live


@pytest.fixture(scope="module")
def ros(graph: Graph) -> Iterator[Any]:
    client = roslibpy.Ros(host="127.0.0.1", port=graph.port)
    client.run(timeout=20)
    yield client
    client.terminate()  # Twisted's reactor stops for good: one connection for the whole module


class Inbox:
    def __init__(self, wanted: int = 1) -> None:
        self.items: list[Any] = []
        self.wanted = wanted
        self.done = threading.Event()

    def __call__(self, item: Any) -> None:
        self.items.append(item)
        if len(self.items) >= self.wanted:
            self.done.set()

    def wait(self, timeout: float = 20.0) -> list[Any]:
        assert self.done.wait(timeout), f"got {len(self.items)} of {self.wanted}"
        return self.items


def test_pose_cmd_vel_spawn_and_parameters(ros: Any) -> None:
    poses = Inbox()
    moved = Inbox()
    start: list[dict[str, Any]] = []

    def watch(msg: dict[str, Any]) -> None:
        poses(msg)
        start[:] = start or [msg]
        if msg["x"] > start[0]["x"] + 0.5:
            moved(msg)

    pose = roslibpy.Topic(ros, "/turtle1/pose", "turtlesim/Pose")
    pose.subscribe(watch)
    assert poses.wait()[0]["x"] == pytest.approx(5.544445, abs=1e-4)
    cmd_vel = roslibpy.Topic(ros, "/turtle1/cmd_vel", "geometry_msgs/Twist")
    cmd_vel.advertise()
    for _ in range(50):
        cmd_vel.publish(roslibpy.Message({"linear": {"x": 2.0}, "angular": {"z": 0.0}}))
        if moved.done.wait(0.2):
            break
    moved.wait()
    pose.unsubscribe()
    cmd_vel.unadvertise()

    spawn = roslibpy.Service(ros, "/spawn", "turtlesim/Spawn")
    assert spawn.call(roslibpy.ServiceRequest({"x": 2.0, "y": 2.0, "theta": 0.5, "name": "roslibpy"}),
                      timeout=20) == {"name": "roslibpy"}
    assert "/roslibpy/pose" in ros.get_topics()

    assert roslibpy.Param(ros, "/turtlesim/background_b").get(timeout=20) == 255
    param = roslibpy.Param(ros, "/web/answer")
    param.set({"a": [1, 2.5, "x"]}, timeout=20)
    assert param.get(timeout=20) == {"a": [1, 2.5, "x"]}


def test_rosapi_answers_what_roslibpy_asks(ros: Any) -> None:
    topics = ros.get_topics()
    assert {"/turtle1/pose", "/turtle1/cmd_vel", "/rosout"} <= set(topics)
    assert ros.get_topic_type("/turtle1/pose") == "turtlesim/Pose"
    assert "/turtle1/pose" in ros.get_topics_for_type("turtlesim/Pose")
    services = ros.get_services()
    assert {"/spawn", "/rosapi/topics", "/clear"} <= set(services)
    assert ros.get_service_type("/spawn") == "turtlesim/Spawn"
    nodes = ros.get_nodes()
    assert {"/turtlesim", "/rosbridge_websocket", "/rosapi"} <= set(nodes)
    details = ros.get_node_details("/turtlesim")
    assert "/turtle1/pose" in details["publishing"] and "/spawn" in details["services"]
    typedefs = ros.get_message_details("turtlesim/Pose")["typedefs"]
    assert typedefs[0]["type"] == "turtlesim/Pose"
    assert typedefs[0]["fieldnames"] == ["x", "y", "theta", "linear_velocity", "angular_velocity"]
    request = ros.get_service_request_details("turtlesim/Spawn")["typedefs"][0]
    assert request["fieldnames"] == ["x", "y", "theta", "name"]
    assert "/turtlesim/background_r" in ros.get_params()
    assert ros.get_time()["secs"] > 0


def test_a_service_roslibpy_provides_is_called_by_a_kame_rospy_node(ros: Any, graph: Graph) -> None:
    calls = Inbox()

    def add(request: dict[str, Any], response: dict[str, Any]) -> bool:
        calls(request)
        response["sum"] = request["a"] + request["b"]
        return True

    service = roslibpy.Service(ros, "/web_add", "rospy_tutorials/AddTwoInts")
    service.advertise(add)
    caller = textwrap.dedent("""
        import rospy
        from rospy_tutorials.srv import AddTwoInts
        rospy.init_node("web_caller")
        rospy.wait_for_service("/web_add", timeout=20)
        print("sum", rospy.ServiceProxy("/web_add", AddTwoInts)(40, 2).sum, flush=True)
    """)
    try:
        done = subprocess.run([sys.executable, "-c", caller], env=graph.env, capture_output=True, text=True,
                              timeout=60)
        assert done.stdout.strip() == "sum 42", done.stderr
        assert calls.wait() == [{"a": 40, "b": 2}]
    finally:
        service.unadvertise()


def test_debian_rospy_publishes_what_roslibpy_sees(ros: Any, graph: Graph, tmp_path: Path) -> None:
    if not have_debian_ros():
        pytest.skip("Debian's rospy is not installed (scripts/install-ros-peers.sh)")
    talker = tmp_path / "talker.py"
    talker.write_text(textwrap.dedent("""
        import rospy
        from std_msgs.msg import String
        rospy.init_node("debian_talker")
        pub = rospy.Publisher("/chatter", String, queue_size=10)
        rate = rospy.Rate(20)
        n = 0
        while not rospy.is_shutdown():
            pub.publish(String("hello from debian %d" % n))
            n += 1
            rate.sleep()
    """))
    proc = Proc([SYSTEM_PYTHON, str(talker)], graph.env)
    heard = Inbox(wanted=3)
    chatter = roslibpy.Topic(ros, "/chatter", "std_msgs/String")
    try:
        chatter.subscribe(heard)
        assert all(m["data"].startswith("hello from debian ") for m in heard.wait(30))
    finally:
        chatter.unsubscribe()
        proc.stop()


def _status(ws: Any) -> dict[str, Any]:
    while True:
        frame = ws.recv(timeout=20)
        op = json.loads(frame) if isinstance(frame, str) else cbor2.loads(frame)
        if op["op"] in ("status", "service_response"):
            return dict(op)


@pytest.mark.parametrize("frame,words", [
    ("{not json", "malformed JSON"),
    (b"\xa2\x62op", "malformed CBOR"),
    ('{"op": "teleport", "id": "t1"}', "Unknown operation: teleport"),
    ('{"op": "subscribe", "topic": 42, "id": "s1"}', "Expected field 'topic' to be a string"),
    ('{"op": "subscribe", "topic": "/turtle1/pose", "throttle_rate": "fast"}', "throttle_rate"),
    ('{"op": "advertise", "topic": "/nothing", "type": "no_such_pkg/Nothing", "id": "a1"}', "no such type"),
    ('{"op": "publish", "topic": "/turtle1/cmd_vel", "msg": {"linear": {"x": "fast"}}}', "linear.x"),
    ('{"op": "publish", "topic": "/never/advertised", "msg": {}}', "Cannot infer topic type"),
    ('{"op": "subscribe", "topic": "/turtle1/pose", "compression": "zip"}', "unknown compression"),
    ('{"op": "call_service", "service": "/no_such_service", "id": "c1"}', "does not exist"),
])
def test_bad_ops_get_a_status_error_and_the_bridge_serves_on(graph: Graph, ros: Any, frame: str | bytes,
                                                             words: str) -> None:
    with connect(graph.url, open_timeout=20) as ws:
        ws.send(frame)
        answer = _status(ws)
        text = answer.get("msg") or answer.get("values")
        assert words in str(text), answer
        if answer["op"] == "status":
            assert answer["level"] == "error"
        ws.send(json.dumps({"op": "subscribe", "topic": "/turtle1/pose", "type": "turtlesim/Pose"}))
        publish = json.loads(ws.recv(timeout=20))
        if publish["op"] == "status":  # a failed call_service has its status after its service_response
            publish = json.loads(ws.recv(timeout=20))
        assert publish["op"] == "publish" and "x" in publish["msg"]
    assert ros.get_topic_type("/turtle1/pose") == "turtlesim/Pose"  # the other client too


def test_set_level_and_fragments_from_a_client(graph: Graph) -> None:
    with connect(graph.url, open_timeout=20) as ws:
        ws.send(json.dumps({"op": "set_level", "level": "loud", "id": "l1"}))
        assert "unknown level" in _status(ws)["msg"]
        ws.send(json.dumps({"op": "set_level", "level": "none"}))
        ws.send('{"op": "teleport"}')  # silenced: the next frame is the subscription's
        whole = json.dumps({"op": "subscribe", "topic": "/turtle1/pose", "type": "turtlesim/Pose"})
        parts = [whole[i:i + 20] for i in range(0, len(whole), 20)]
        for num, part in enumerate(parts):
            ws.send(json.dumps({"op": "fragment", "id": "f1", "data": part, "num": num, "total": len(parts)}))
        assert json.loads(ws.recv(timeout=20))["op"] == "publish"


def test_fragment_size_cuts_what_the_bridge_sends(graph: Graph) -> None:
    with connect(graph.url, open_timeout=20) as ws:
        ws.send(json.dumps({"op": "subscribe", "topic": "/turtle1/pose", "type": "turtlesim/Pose",
                            "fragment_size": 20}))
        first = json.loads(ws.recv(timeout=20))
        assert first["op"] == "fragment" and first["num"] == 0 and first["total"] > 1
        parts = [first] + [json.loads(ws.recv(timeout=20)) for _ in range(first["total"] - 1)]
        assert [p["num"] for p in parts] == list(range(first["total"]))
        assert all(len(p["data"]) <= 20 and p["id"] == first["id"] for p in parts)
        whole = json.loads("".join(p["data"] for p in parts))
        assert whole["op"] == "publish" and whole["topic"] == "/turtle1/pose"


def test_a_clients_calls_in_progress_are_bounded(graph: Graph) -> None:
    from kame.rosbridge.session import MAX_CALLS_IN_PROGRESS

    def ops(ws: Any, timeout: float) -> Iterator[dict[str, Any]]:
        while True:
            try:
                yield json.loads(ws.recv(timeout=timeout))
            except TimeoutError:
                return

    with connect(graph.url, open_timeout=20) as provider, connect(graph.url, open_timeout=20) as caller:
        provider.send(json.dumps({"op": "advertise_service", "service": "/never_answers",
                                  "type": "std_srvs/Empty"}))
        waiting = None  # the first call that reached the provider: the service is up
        for attempt in range(100):
            caller.send(json.dumps({"op": "call_service", "service": "/never_answers", "id": f"probe{attempt}"}))
            asked = next(ops(provider, 0.2), None)
            if asked is not None:
                waiting = f"probe{attempt}"
                break
        assert waiting is not None, "the provider's service never came up"
        for n in range(MAX_CALLS_IN_PROGRESS - 1):
            caller.send(json.dumps({"op": "call_service", "service": "/never_answers", "id": f"c{n}"}))
        caller.send(json.dumps({"op": "call_service", "service": "/never_answers", "id": "one too many"}))
        refused = next(op for op in ops(caller, 20) if op.get("id") == "one too many")
        assert refused["op"] == "status" and "already in progress" in refused["msg"]
        provider.close()  # its service goes, and every call waiting on it fails
        wanted = {waiting, *(f"c{n}" for n in range(MAX_CALLS_IN_PROGRESS - 1))}
        answered = set()
        for op in ops(caller, 30):
            if op["op"] == "service_response" and op["id"] in wanted:
                assert op["result"] is False
                answered.add(op["id"])
                if answered == wanted:
                    break
        assert answered == wanted


def test_debians_tools_hear_and_call_what_roslibpy_provides(ros: Any, graph: Graph) -> None:
    if not have_debian_ros():
        pytest.skip("Debian's ROS tools are not installed (scripts/install-ros-peers.sh)")
    talk = roslibpy.Topic(ros, "/web_says", "std_msgs/String")
    talk.advertise()
    echo = subprocess.Popen([SYSTEM_PYTHON, "/usr/bin/rostopic", "echo", "-n", "1", "/web_says"], env=graph.env,
                            stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
    try:
        for _ in range(300):
            talk.publish(roslibpy.Message({"data": "from the web"}))
            try:
                out, err = echo.communicate(timeout=0.1)
                break
            except subprocess.TimeoutExpired:
                continue
        else:
            raise AssertionError("Debian's rostopic echo heard nothing")
        assert "data: \"from the web\"" in out, err
    finally:
        if echo.poll() is None:
            echo.kill()
            echo.wait()
        talk.unadvertise()

    def flag(request: dict[str, Any], response: dict[str, Any]) -> bool:
        response.update(success=request["data"], message="set from the web")
        return True

    service = roslibpy.Service(ros, "/web_flag", "std_srvs/SetBool")
    service.advertise(flag)
    try:
        for _ in range(100):
            called = subprocess.run([SYSTEM_PYTHON, "/usr/bin/rosservice", "call", "/web_flag", "true"],
                                    env=graph.env, capture_output=True, text=True, timeout=60)
            if called.returncode == 0 or "not available" not in called.stderr:
                break
        assert called.stdout.split() == ["success:", "True", "message:", '"set', "from", "the", 'web"'], called.stderr
    finally:
        service.unadvertise()


@pytest.mark.parametrize("param,words", [("_bson_only_mode:=true", "BSON")])
def test_what_the_bridge_cannot_do_it_refuses_to_start_with(graph: Graph, param: str, words: str) -> None:
    done = subprocess.run([sys.executable, "-m", "kame.cli.rosrun", "rosbridge_server", "rosbridge_websocket",
                           f"__name:=refused_{words.lower()}", "_port:=0", param], env=graph.env, capture_output=True,
                          text=True, timeout=60)
    assert done.returncode == 1
    assert words in done.stderr + done.stdout
