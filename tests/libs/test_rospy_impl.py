"""rospy.impl and rospy's internals that programs and upstream's tests reach for (the TCPROS
names and headers, tcpros_pubsub's TCPROSHandler, masterslave's ROSHandler (the node's slave
API), rosout's RosOutHandler and load_rosout_handlers, rospy.impl.tcpros_service's
ServiceProxy, the topic manager, validators, simtime,
rospy.rostime's switch_to_wallclock and _set_rostime, rospy.client.load_command_line_node_params):
the same answers as Debian's real rospy, from a node on a kame master."""

from __future__ import annotations

import json
import subprocess
import sys
import textwrap
from collections.abc import Iterator
from pathlib import Path

import pytest

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master
from . import debian

SCRIPT = textwrap.dedent("""
    import json, time
    import rospy, rospy.client, rospy.names, rospy.rostime
    import rospy.impl.simtime
    from rospy.impl import registration, tcpros, tcpros_base, transport, validators
    from rospy.impl.tcpros_service import Service, ServiceProxy, wait_for_service
    from rospy.impl.init import DEFAULT_MASTER_PORT, DEFAULT_NODE_PORT
    from std_msgs.msg import Int32, String
    from std_srvs.srv import Trigger, TriggerResponse

    out = {"consts": [tcpros_base.DEFAULT_BUFF_SIZE, tcpros_base.TCPROS, tcpros.DEFAULT_BUFF_SIZE, transport.INBOUND,
                      transport.OUTBOUND, transport.BIDIRECTIONAL, registration.Registration.PUB,
                      registration.Registration.SUB, registration.Registration.SRV, DEFAULT_MASTER_PORT,
                      DEFAULT_NODE_PORT, rospy.impl.simtime._USE_SIMTIME, rospy.impl.simtime._ROSCLOCK],
           "same_exception": rospy.names.ParameterInvalid is validators.ParameterInvalid,
           "same_proxy": [ServiceProxy is rospy.ServiceProxy, Service is rospy.Service]}
    try:
        validators.non_empty("topic")("", None)
    except validators.ParameterInvalid as exc:
        out["non_empty"] = str(exc)
    params = []
    for argv in (["p", "_rate:=10", "_name:=[a, b]", "__ns:=/x", "chatter:=/c", "_flag:=true", "_:=1"],
                 ["p", "_bad:=[unclosed"]):
        try:
            params.append(rospy.client.load_command_line_node_params(argv))
        except rospy.ROSInitException as exc:
            params.append(type(exc).__name__)
    out["params"] = params
    rospy.init_node("impl_driver")
    rospy.Publisher("chat", String, queue_size=1)
    rospy.Subscriber("heard", Int32, lambda m: None)
    Service("~trigger", Trigger, lambda req: TriggerResponse(True, "fired"))
    wait_for_service("~trigger", 10)
    out["called"] = ServiceProxy("~trigger", Trigger)().message
    manager = registration.get_topic_manager()
    out["pubs"] = sorted(t for t in manager.get_publications() if t[0] != "/rosout")
    out["subs"] = manager.get_subscriptions()
    out["has"] = [manager.has_publication("/chat"), manager.has_subscription("/chat"),
                  manager.has_subscription("/heard")]
    out["use_simtime"] = rospy.impl.simtime._is_use_simtime()
    from rospy.impl import masterslave, rosout, tcpros_pubsub
    import logging, os, threading, rosgraph
    from rosgraph_msgs.msg import Log
    sub_side = tcpros_pubsub.TCPROSSub("/chat", String, tcp_nodelay=True)
    pub_side = tcpros_pubsub.TCPROSPub("/chat", String, is_latch=True, headers={"extra": "1", "type": "mine"})
    out["headers"] = [sub_side.get_header_fields(), pub_side.get_header_fields(), sub_side.direction,
                      pub_side.direction]
    try:
        tcpros_pubsub.TCPROSSub("/chat", dict)
    except rospy.exceptions.TransportInitError as exc:
        out["bad_class"] = str(exc)
    tcpros = tcpros_pubsub.TCPROSHandler()
    code, msg, where = tcpros.init_publisher("/chat", ["TCPROS"])
    handler = masterslave.ROSHandler(rospy.get_name(), rosgraph.get_master_uri())
    caller = "/tester"
    requested = handler.requestTopic(caller, "/chat", [["UDPROS"], ["TCPROS"]])
    out["tcpros"] = [tcpros.supports("TCPROS"), tcpros.supports("UDPROS"), tcpros.get_supported(), code,
                     msg == "ready on %s:%s" % (where[1], where[2]), where[0], list(requested[2]) == where,
                     tcpros.init_publisher("/chat", ["UDPROS"])[0]]
    pid = handler.getPid(caller)
    out["slave"] = [[pid[0], pid[2] == os.getpid()], handler.getName(caller), handler.getMasterUri(caller),
                    sorted(handler.getPublications(caller)[2]), handler.getSubscriptions(caller),
                    requested[0], handler.requestTopic(caller, "/nope", [["TCPROS"]])[0],
                    handler.requestTopic(caller, "/chat", [["UDPROS"]])[0], handler.getBusInfo(caller),
                    handler.getBusStats(caller)[0], handler.publisherUpdate(caller, "/heard", [])[0],
                    handler.paramUpdate(caller, "/not_subscribed", 1)[0]]
    logged, linked, done = [], threading.Event(), threading.Event()
    def heard_log(m):
        if m.msg == "probe":
            linked.set()
        if m.msg.startswith("impl:"):
            logged.append([m.level, m.msg, m.name, m.file, m.function])
            if m.msg == "impl: user warning":
                done.set()
    rospy.Subscriber("/rosout", Log, heard_log)
    user = logging.getLogger("impl_user")
    user.addHandler(rosout.RosOutHandler())
    user.propagate = False
    deadline = time.time() + 30
    while not linked.wait(0.1) and time.time() < deadline:
        user.warning("probe")  # until our own /rosout reaches us: then nothing published is lost
    rosout.load_rosout_handlers(Log.ERROR)
    rospy.logwarn("impl: below the level")
    rospy.logerr("impl: error")
    user.warning("impl: user warning")
    done.wait(30)
    out["rosout"] = logged
    rospy.rostime._set_rostime(rospy.Time(5, 6))
    out["set"] = [rospy.get_rostime().secs, rospy.get_rostime().nsecs, rospy.rostime.is_wallclock()]
    rospy.rostime.switch_to_wallclock()
    out["wall"] = [abs(rospy.get_time() - time.time()) < 60, rospy.rostime.is_wallclock()]
    print(json.dumps(out))
""")


@pytest.fixture(scope="module")
def master_env(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(Path(tmp_path_factory.mktemp("impl")), uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield environment
    finally:
        master.stop()


def run(python: str, env: dict[str, str]) -> dict[str, object]:
    environment = {**debian.debian_env(), **{k: v for k, v in env.items() if k.startswith("ROS_") or k == "HOME"}}
    result = subprocess.run([python, "-c", SCRIPT], capture_output=True, text=True, env=environment, timeout=90)
    assert result.returncode == 0, result.stderr
    answer: dict[str, object] = json.loads(result.stdout.splitlines()[-1])
    return answer


def test_rospy_impl_answers(master_env: dict[str, str]) -> None:
    ours = run(sys.executable, master_env)
    assert ours["consts"] == [65536, "TCPROS", 65536, "i", "o", "b", "pub", "sub", "srv", 11311, 0,
                              "/use_sim_time", "/clock"]
    assert ours["same_exception"] and ours["same_proxy"] == [True, True] and ours["called"] == "fired"
    assert ours["non_empty"] == "ERROR: parameter [topic] must be specified and non-empty"
    assert ours["params"] == [{"rate": 10, "name": ["a", "b"], "flag": True}, "ROSInitException"]
    assert ours["pubs"] == [["/chat", "std_msgs/String"]] and ours["subs"] == [["/heard", "std_msgs/Int32"]]
    assert ours["has"] == [True, False, True] and ours["use_simtime"] is False
    assert ours["set"] == [5, 6, False] and ours["wall"] == [True, True]
    sub_fields, pub_fields, sub_direction, pub_direction = ours["headers"]  # type: ignore[misc]
    assert sub_fields["tcp_nodelay"] == "1" and sub_fields["callerid"] == "/impl_driver" and sub_direction == "i"
    assert (pub_fields["latching"], pub_fields["type"], pub_fields["extra"], pub_direction) == ("1", "mine", "1", "o")
    assert ours["bad_class"] == "Unable to initialize transport: data class is not a message data class"
    assert ours["tcpros"] == [True, False, [["TCPROS"]], 1, True, "TCPROS", True, 0]
    assert ours["slave"][:2] == [[1, True], [1, "", "/impl_driver"]]  # type: ignore[index]
    assert ours["slave"][5:10] == [1, -1, 0, [1, "bus info", []], 1]  # type: ignore[index]
    assert ours["rosout"] == [[8, "impl: error", "/impl_driver", "<string>", "<module>"],
                              [4, "impl: user warning", "/impl_driver", "<string>", "<module>"]]


@pytest.mark.skipif(not debian.has("rospy", "std_srvs.srv"), reason="Debian's rospy is not installed")
def test_rospy_impl_answers_as_debians_rospy(master_env: dict[str, str]) -> None:
    ours, theirs = run(sys.executable, master_env), run(str(debian.SYSTEM_PYTHON), master_env)
    # rospy's load_rosout_handlers adds a second handler to a logger that has one: each line of
    # rospy's own then reaches /rosout twice; kame's publishes it once
    theirs["rosout"] = [line for i, line in enumerate(theirs["rosout"])  # type: ignore[arg-type]
                        if i == 0 or line != theirs["rosout"][i - 1]]  # type: ignore[index]
    assert ours == theirs
