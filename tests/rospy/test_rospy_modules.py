"""rospy's modules file for file (issue 35): rospy.core, rospy.names, rospy.msg, rospy.service,
rospy.msproxy and rospy.impl's registration, transport, tcpros_base, tcpros, tcpros_pubsub,
tcpros_service and paramserver, on the same inputs as Debian's rospy.

modules_driver.py needs no master; modules_live_driver.py runs a node on a kame master:
registration listeners hearing the node, MasterProxy, the parameter cache, TCPROSTransport
subscribing and calling a service (directly and through init_tcpros's server), RegManager."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from ..libs import debian
from ..support import Proc, free_port, kame_command, ros_env, wait_for_master

HERE = Path(__file__).parent
DRIVER = HERE / "modules_driver.py"
LIVE_DRIVER = HERE / "modules_live_driver.py"
HAS_DEBIAN = debian.has("rospy", "std_srvs.srv", "geometry_msgs.msg")


def run(script: Path, python: str, env: dict[str, str]) -> dict[str, Any]:
    environment = {**debian.debian_env(), **env}
    result = subprocess.run([python, str(script)], capture_output=True, text=True, env=environment, timeout=90)
    assert result.returncode == 0, result.stderr
    # the answer is the last JSON line: rospy's start_node prints the shutdown request its node may get
    answer: dict[str, Any] = json.loads([line for line in result.stdout.splitlines() if line.startswith("{")][-1])
    return answer


@pytest.fixture(scope="module")
def offline() -> dict[str, Any]:
    return run(DRIVER, sys.executable, {"ROS_MASTER_URI": "http://127.0.0.1:1/"})


def test_core_names(offline: dict[str, Any]) -> None:
    assert offline["rosrpc"] == [
        ["ok", ["host", 1234]], ["ok", ["host", 1234]],
        ["ParameterInvalid", "Invalid protocol for ROS service URL: http://host:1"],
        ["ParameterInvalid", "ROS service URL is invalid: rosrpc://host"],
        ["ParameterInvalid", "ROS service URL is invalid: rosrpc://host:port"],
        ["ParameterInvalid", "ROS service URL is invalid: rosrpc://a:1:2"]]
    assert offline["same_parse"] and offline["consts"] == ["master", "rosrpc://"]
    assert offline["is_topic"] == [["ok", "/ns/chat"],
                                   ["ParameterInvalid", "ERROR: parameter [t] cannot be the global namespace"],
                                   ["ParameterInvalid", "ERROR: parameter [t] must be a non-empty string"],
                                   ["ParameterInvalid", "ERROR: parameter [t] contains illegal chars"]]
    assert offline["ros_root"] == [["ok", "/opt/x"], ["ok", None], ["ROSException", "ROS_ROOT is not set"]]
    assert offline["node_uri"] == [None, "http://here:1/", "http://here:1/"]
    assert offline["initialized"] == [False, True]
    assert offline["xmlrpcapi"] == [True, True, True, False]
    assert offline["bad_hook"][0] == "TypeError"
    assert offline["configure_logging"] == ["ns_node.log", True,
                                            ["ROSException", "invalid configure_logging parameter: /"]]
    assert offline["top_level"] == [True, "rospy.msproxy", True, True, True, True]


def test_names_tables(offline: dict[str, Any]) -> None:
    assert offline["anytype"] == ["*", "*", True, False]
    assert offline["mappings"] == [{"chatter": "/talk", "~p": "q", "__ns": "/n"},
                                   {"a": "b", "~c": "d", "__log": "/tmp/x.log"}]
    assert offline["resolved"] == [{"/ns/a": "/ns/b", "/ns/node/c": "/ns/d", "__log": "/tmp/x.log"}, "/ns/b", "/ns/d"]
    assert offline["without_node"][:2] == [["ok", "/talk"], ["ok", "/n/other"]]
    assert offline["validators"][:4] == [["ok", "/ns/rel"], ["ok", "rel"], ["ok", "/ns/node/priv"], ["ok", "~priv"]]


def test_shutdown_hooks_order_and_flags(offline: dict[str, Any]) -> None:
    # client hooks (rospy.on_shutdown's, no argument) first, then pre-shutdown hooks before
    # is_shutdown, then shutdown hooks
    assert offline["seen"] == [["client", [], False, True, False, True],
                               ["on_shutdown", [], False, True, False, True],
                               ["pre", ["driver done"], False, True, False, True],
                               ["shutdown", ["driver done"], True, True, True, True],
                               ["late", ["already shutdown"], True, True, True, True]]
    assert offline["hook_lists"] == [True, True, True] and offline["before"] == [False, False, False]
    assert offline["after"] == [True, True, True, [], [], []]


def test_message_frames(offline: dict[str, Any]) -> None:
    assert offline["frames"][0] == "06000000020000006869"
    assert offline["frames"][2] == 42  # the header's seq is the one given
    assert offline["deserialized"] == [["hi", "hi"], "0600000002", 5,
                                       ["hi"], "0600000002000000686906000000020000006869", 20]
    assert offline["bad_frame"] == "DeserializationError"


def test_param_cache_tree(offline: dict[str, Any]) -> None:
    cache = offline["cache"]
    assert [step[0] for step in cache[:-1]] == [
        "KeyError", "KeyError", "KeyError", "ok", "ok", "ok", "ok", "ok", "KeyError", "ok", "KeyError", "ok",
        "KeyError", "KeyError", "TypeError", "ok", "ok", "TypeError"]  # rospy's: a value in the way is a TypeError
    assert cache[4] == ["ok", {"b": 2}]  # the tree itself, as updated after
    assert cache[7] == ["ok", 2] and cache[16] == ["ok", {"r": 1}]
    assert cache[-1] == [["/a/b", 2]]  # the notifier hears updates only


def test_transports(offline: dict[str, Any]) -> None:
    assert offline["transport"] == [1, True, ["chat"], None, "UNKNOWN",
                                    "Closed UNKNOWN connection on port 5 to [6.7.8.9:10]", True, True, 10, "i", "chat",
                                    True]
    assert offline["protocol_handler"] == [False, [], None, True]
    assert offline["recv_buff"] == [2, "ab", 1, "c", 0, ["TransportTerminated",
                                    "unable to receive data from sender, check sender's logs for details"]]
    assert offline["exceptions"] == [True, True, True]
    assert offline["tcpros_transport"][:4] == ["TCPROS", "unknown", False, None]
    assert offline["tcpros_transport"][4:] == [
        ["TransportInitError", "TCPROS transport was not successfully initialized"],
        ["TransportException", "connection not initialized"],
        ["TransportInitError", "Unable to initialize transport: name is not set"]]
    assert offline["protocol"][:3] == [{}, "b", 65536]


def test_service_side(offline: dict[str, Any]) -> None:
    assert offline["convert"][:4] == [["ok", 'success: True\nmessage: "m"'], ["ok", 'success: True\nmessage: "d"'],
                                      ["ok", 'success: False\nmessage: "t"'], ["ok", 'success: True\nmessage: "l"']]
    assert offline["convert"][4] == ["ServiceException", "service handler returned None"]
    assert offline["convert"][6][0] == offline["convert"][7][0] == "ServiceException"
    client_fields, server_fields = offline["service_protocols"][:2]
    assert client_fields["persistent"] == "1" and client_fields["callerid"] == "/n/unnamed"
    assert server_fields["type"] == "std_srvs/SetBool"
    assert offline["service_read"] == [['success: True\nmessage: "ok"'],
                                       ["ServiceException", "service [/svc] responded with an error: b'boom'"]]
    assert offline["tcpros_handler"] == [True, [["TCPROS"]], False, None, [0, "ERROR: invalid TCPROS parameters", 0],
                                         [0, "INTERNAL ERROR: protocol id is not TCPROS: UDPROS", 0]]


def test_registration_listeners_and_service_manager(offline: dict[str, Any]) -> None:
    assert offline["bad_listener"] == "AssertionError"
    registered, services, same, missing, after, events, described = offline["service_manager"]
    assert registered == ["ServiceException", "service [/svc] already registered"]
    assert services == [["/svc", "rosrpc://h:1"]] and same and missing is None and after == []
    assert events == [["added", "/t", "std_msgs/String", "pub"], ["added", "/svc", "rosrpc://h:1", "srv"],
                      ["added", "/svc", "rosrpc://h:1", "srv"], ["removed", "/svc", "rosrpc://h:1", "srv"]]
    assert described == ["/n/svc", "SetBoolRequest", "SetBoolResponse"]
    assert offline["cleared"] == [] and offline["managers"] == ["tm", "sm"]


def test_client_names_and_clock_condition(offline: dict[str, Any]) -> None:
    assert offline["client"] == [15.0, [1, 2, 4, 8, 16], "roscpp/GetLoggers", "roscpp/Logger",
                                 "roscpp/SetLoggerLevelResponse", "rosgraph_msgs/Log", True]
    assert offline["rostime_cond"] == [True]  # _set_rostime woke the waiter


def test_apivalidate(offline: dict[str, Any]) -> None:
    assert offline["apivalidate"] == [
        [1, "fine", ["/chat", 5]], [-1, "ERROR: parameter [topic] cannot be the global namespace", 0],
        [-1, "Error: bad call arity", 0], [-1, "missing required caller_id parameter", 0],
        [-1, "caller_id must be a string", 0], [0, "Internal failure: inside", -1], "call", [0, 1, 2, True],
        ["is_publishers_list", "p"], None, None]


def test_poller_and_queued_connection(offline: dict[str, Any]) -> None:
    assert offline["poller"] == [[], True, []]  # the hang-up is seen once the peer closed
    assert offline["queued"] == [True, "collect", "o", "a", "last", False]  # its thread ends with the connection


@pytest.mark.skipif(not HAS_DEBIAN, reason="Debian's rospy is not installed")
def test_offline_answers_as_debians(offline: dict[str, Any]) -> None:
    assert run(DRIVER, str(debian.SYSTEM_PYTHON), {"ROS_MASTER_URI": "http://127.0.0.1:1/"}) == offline


@pytest.fixture(scope="module")
def master_env(tmp_path_factory: pytest.TempPathFactory) -> Iterator[dict[str, str]]:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    environment = ros_env(Path(tmp_path_factory.mktemp("modules")), uri)
    master = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), environment)
    try:
        wait_for_master(uri, proc=master)
        yield {k: v for k, v in environment.items() if k.startswith("ROS_") or k == "HOME"}
    finally:
        master.stop()


@pytest.fixture(scope="module")
def live(master_env: dict[str, str]) -> dict[str, Any]:
    return run(LIVE_DRIVER, sys.executable, master_env)


def test_registration_listener_hears_the_node(live: dict[str, Any]) -> None:
    assert live["events"] == [["added", "/latched", "std_msgs/String", "pub"],
                              ["added", "/heard", "std_msgs/String", "sub"], ["added", "/switch", "rosrpc", "srv"],
                              ["removed", "/heard", "std_msgs/String", "sub"]]


def test_master_proxy_and_param_cache(live: dict[str, Any]) -> None:
    assert live["get_master"] == [True, True, True, False]  # rospy.get_master() is a MasterProxy
    assert live["master_proxy"] == [1, True, {"a": 1}, 1, True, False, None, True, ["KeyError", "'/live/p'"],
                                    ["KeyError", "'/live/p'"], 1]
    assert live["cache"] == [5, 5, 7, 8, False]


def test_tcpros_transport_subscribes_and_calls(live: dict[str, Any]) -> None:
    subscribed = [True, "std_msgs/String", "992ce8a1687cec8c8bd883ec73ca41d1", "/modules_live", 1, True, ["kept"], True]
    assert live["direct"] == [subscribed, ['success: True\nmessage: "yes"'],
                              ["ServiceException", "service [/switch] responded with an error: "
                                                   "b'service cannot process request: asked for false'"],
                              "remote error reported: [/modules_live] is not a publisher of [/nothing]"]
    assert live["served"] == [subscribed, ['success: True\nmessage: "yes"']]


def test_reg_manager_tells_the_master(live: dict[str, Any]) -> None:
    assert live["reg_manager"] == [["/modules_live"], "std_msgs/Empty", None]


def test_statistics_published(live: dict[str, Any]) -> None:
    assert live["statistics"] == [False, 10, 64, True, ["/measured", "/modules_live", "/somebody", True, True, 0,
                                                        True, True], {}]


def test_publisher_checks_and_robust_connect(live: dict[str, Any]) -> None:
    assert live["still_publisher"] == [True, False, False]
    assert live["robust"] == [["kept"], True]


def test_logger_levels_and_rosconsole(live: dict[str, Any]) -> None:
    assert live["loggers"] == [True, True, ["debug", "info", "warn", "error", "fatal"],
                               "node '/no_such_node' doesn't exist or doesn't support query"]
    assert live["rosconsole"] == [0, True]


def test_service_manager_registers_with_the_master(live: dict[str, Any]) -> None:
    assert live["service_manager"] == [1, True, True, "service [/switch] already registered", -1, None, True, True]


def test_init_rosout_simtime_and_start_node(live: dict[str, Any]) -> None:
    assert live["init"] == [True, True, "http://localhost:11311/", 0]
    assert live["start_node"] == [1, "/ns/started"]


def test_tcpros_handler_connects_a_subscription(live: dict[str, Any]) -> None:
    assert live["create_transport"] == [1, True, ["kept"]]


@pytest.mark.skipif(not HAS_DEBIAN, reason="Debian's rospy is not installed")
def test_live_answers_as_debians(live: dict[str, Any], master_env: dict[str, str]) -> None:
    theirs = run(LIVE_DRIVER, str(debian.SYSTEM_PYTHON), master_env)
    # rospy's subscription is connected to that publisher already: whether its second connection
    # is refused as a duplicate depends on its threads' timing
    ours = {key: value for key, value in live.items() if key != "create_transport"}
    assert {key: value for key, value in theirs.items() if key != "create_transport"} == ours
