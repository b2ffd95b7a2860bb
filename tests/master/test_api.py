"""The pure master core: spec facts, and the same call sequences run through Debian's rosmaster."""

import json
import os
import random
import subprocess
from pathlib import Path
from typing import Any

import pytest

from kame.master import MasterApi, ParamUpdate, PublisherUpdate, ShutdownNode
from kame.protocol.xmlrpc import Fault

URI = "http://127.0.0.1:11311/"
A, B, C = "http://h:1/", "http://h:2/", "http://h:3/"


def master() -> MasterApi:
    return MasterApi(URI, 4242)


def call(m: MasterApi, method: str, *params: Any) -> Any:
    return m.call(method, list(params)).value


def test_argument_checks() -> None:
    m = master()
    assert call(m, "getSystemState") == [-1, "missing required caller_id parameter", [[], [], []]]
    assert call(m, "getPid", "/n", 1) == [-1, "Error: bad call arity", -1]
    assert call(m, "getParam", 5, "k") == [-1, "caller_id must be a string", 0]
    assert call(m, "getParam", "/n", "") == [-1, "ERROR: parameter [key] must be specified and non-empty", 0]
    assert call(m, "getParam", "/n", 3) == [-1, "ERROR: parameter [key] must be a string", 0]
    assert call(m, "registerPublisher", "/n", "a b", "p/T", A) == [
        -1, "ERROR: parameter [topic] contains illegal chars", []]
    assert call(m, "registerPublisher", "/n", "/", "p/T", A) == [
        -1, "ERROR: parameter [topic] cannot be the global namespace", []]
    assert call(m, "registerSubscriber", "/n", "/t", "T", A) == [
        -1, "ERROR: parameter [topic_type] is not a valid package resource name", []]
    assert call(m, "registerService", "/n", "/s", "tcp://h:1", A) == [
        -1, "ERROR: parameter [service_api] is not an RPC URI", 0]
    assert call(m, "registerService", "/n", "/s", "rosrpc://h:1", 7) == [
        -1, "ERROR: parameter [caller_api] is not an XMLRPC URI", 0]
    assert call(m, "lookupNode", "/n", "x:y") == [-1, "ERROR: parameter [node] contains illegal chars", ""]
    assert call(m, "shutdown", "/n") == [-1, "Error: bad call arity", 0]


def test_unknown_and_private_methods_are_faults() -> None:
    m = master()
    for name in ("getBusInfo", "_shutdown", "system.listMethods"):
        with pytest.raises(Fault) as e:
            m.call(name, ["/n"])
        assert (e.value.code, e.value.message) == (1, f"<class 'Exception'>:method \"{name}\" is not supported")


def test_multicall() -> None:
    m = master()
    calls = [{"methodName": "setParam", "params": ["/n", "k", 1]},
             {"methodName": "getParam", "params": ["/n", "k"]},
             {"methodName": "nope", "params": []}]
    assert call(m, "system.multicall", calls) == [
        [[1, "parameter /k set", 0]], [[1, "Parameter [/k]", 1]],
        {"faultCode": 1, "faultString": "<class 'Exception'>:method \"nope\" is not supported"}]
    with pytest.raises(Fault):
        m.call("system.multicall", [[{"params": []}]])
    with pytest.raises(Fault):
        m.call("system.multicall", ["x"])


def test_names_resolved_against_caller() -> None:
    m = master()
    assert call(m, "setParam", "/ns1/node", "~priv", 5) == [1, "parameter /ns1/node/priv set", 0]
    assert call(m, "registerPublisher", "/ns1/node", "rel", "p/T", A)[0] == 1
    assert call(m, "getSystemState", "/x")[2][0] == [["/ns1/rel", ["/ns1/node"]]]
    assert call(m, "hasParam", "/ns1/other", "node/priv") == [1, "/ns1/node/priv", True]


def test_publisher_update_always_carries_the_full_list() -> None:
    m = master()
    assert call(m, "registerSubscriber", "/s", "/t", "p/T", C) == [1, "Subscribed to [/t]", []]
    r = m.call("registerPublisher", ["/p1", "/t", "p/T", A])
    assert r.value == [1, "Registered [/p1] as publisher of [/t]", [C]]
    assert r.notifications == (PublisherUpdate(C, "/t", (A,)),)
    r = m.call("registerPublisher", ["/p2", "/t", "p/T", B])
    assert r.notifications == (PublisherUpdate(C, "/t", (A, B)),)
    r = m.call("unregisterPublisher", ["/p1", "/t", A])
    assert r.value == [1, "Unregistered [/p1] as provider of [/t]", 1]
    assert r.notifications == (PublisherUpdate(C, "/t", (B,)),)
    r = m.call("unregisterPublisher", ["/p2", "/t", B])
    assert r.notifications == (PublisherUpdate(C, "/t", ()),)
    assert call(m, "registerSubscriber", "/s", "/t", "p/T", C) == [1, "Subscribed to [/t]", []]


def test_unregister_unknown_is_not_an_error() -> None:
    m = master()
    assert call(m, "unregisterSubscriber", "/n", "/t", A) == [1, "[/n] is not a registered node", 0]
    call(m, "registerSubscriber", "/n", "/t", "p/T", A)
    assert call(m, "unregisterSubscriber", "/n", "/u", A) == [1, "[/n] is not a known provider of [/u]", 0]
    assert call(m, "unregisterSubscriber", "/n", "/t", B) == [1, "[/n] is not a known provider of [/t]", 0]


def test_node_known_while_it_has_registrations() -> None:
    m = master()
    assert call(m, "lookupNode", "/q", "/n") == [-1, "unknown node [/n]", ""]
    call(m, "subscribeParam", "/n", A, "k")
    assert call(m, "lookupNode", "/q", "n") == [1, "node api", A]
    assert call(m, "unsubscribeParam", "/n", A, "k") == [1, "Unsubscribe to parameter [/k]", 1]
    assert call(m, "lookupNode", "/q", "/n")[0] == -1


def test_duplicate_node_name() -> None:
    m = master()
    call(m, "registerSubscriber", "/sub", "/t", "p/T", C)
    call(m, "registerPublisher", "/dup", "/t", "p/T", A)
    call(m, "registerService", "/dup", "/srv", "rosrpc://h:9", A)
    call(m, "subscribeParam", "/dup", A, "k")
    r = m.call("registerPublisher", ["/dup", "/other", "p/T", B])
    # the old node is told to go; its /t publication vanishes without a publisherUpdate
    assert r.notifications == (ShutdownNode(A, "[/dup] Reason: new node registered with same name"),)
    pubs, subs, srvs = call(m, "getSystemState", "/q")[2]
    assert pubs == [["/other", ["/dup"]]]
    assert subs == [["/t", ["/sub"]]]
    assert srvs == []
    assert call(m, "lookupNode", "/q", "/dup")[2] == B
    assert m.call("setParam", ["/q", "k", 1]).notifications == ()


def test_services() -> None:
    m = master()
    assert call(m, "registerService", "/a", "s", "rosrpc://h:1", A) == [1, "Registered [/a] as provider of [/s]", 1]
    assert call(m, "registerService", "/b", "/s", "rosrpc://h:2", B)[0] == 1
    assert call(m, "lookupService", "/q", "/s") == [1, "rosrpc URI: [rosrpc://h:2]", "rosrpc://h:2"]
    assert call(m, "getSystemState", "/q")[2][2] == [["/s", ["/b"]]]
    assert call(m, "unregisterService", "/a", "/s", "rosrpc://h:1") == [
        1, "[rosrpc://h:1] is no longer the current service api handle for [/s]", 0]
    # rosmaster keeps the replaced service in the old node's list, so /a stays known
    assert call(m, "lookupNode", "/q", "/a")[2] == A
    assert call(m, "unregisterService", "/b", "/s", "rosrpc://h:2") == [1, "Unregistered [/b] as provider of [/s]", 1]
    assert call(m, "lookupService", "/q", "/s") == [-1, "no provider", ""]
    assert call(m, "lookupNode", "/q", "/b")[0] == -1


def test_published_topics_and_types() -> None:
    m = master()
    call(m, "registerPublisher", "/n", "/t", "p/T", A)
    call(m, "registerPublisher", "/n", "/t/sub", "p/U", A)
    call(m, "registerSubscriber", "/n", "/only_sub", "p/V", A)
    call(m, "registerSubscriber", "/n", "/any", "*", A)
    assert call(m, "getPublishedTopics", "/n", "") == [1, "current topics", [["/t", "p/T"], ["/t/sub", "p/U"]]]
    assert call(m, "getPublishedTopics", "/n", "/t") == [1, "current topics", [["/t/sub", "p/U"]]]
    call(m, "unregisterSubscriber", "/n", "/only_sub", A)
    assert call(m, "getTopicTypes", "/n")[2] == [["/t", "p/T"], ["/t/sub", "p/U"], ["/only_sub", "p/V"]]
    call(m, "registerPublisher", "/n", "/t", "*", A)
    assert call(m, "getTopicTypes", "/n")[2][0] == ["/t", "p/T"]


def test_param_tree() -> None:
    m = master()
    call(m, "setParam", "/n", "/a", {"b": 1, "c": {"d": "x"}})
    assert call(m, "getParam", "/n", "/a/c/d") == [1, "Parameter [/a/c/d]", "x"]
    assert call(m, "getParam", "/n", "/") == [1, "Parameter [/]", {"a": {"b": 1, "c": {"d": "x"}}}]
    call(m, "setParam", "/n", "/a", {"e": 2})  # replaces, no merge
    assert call(m, "getParam", "/n", "/a")[2] == {"e": 2}
    call(m, "setParam", "/n", "/a/e/f", 3)  # scalar becomes a dict
    assert call(m, "getParam", "/n", "/a")[2] == {"e": {"f": 3}}
    call(m, "setParam", "/n", "/empty", {})
    assert call(m, "hasParam", "/n", "/empty")[2] is True
    assert call(m, "getParamNames", "/n") == [1, "Parameter names", ["/a/e/f"]]
    assert call(m, "setParam", "/n", "/", 1) == [
        -1, "Error: invalid arguments: cannot set root of parameter tree to non-dictionary", 0]
    assert call(m, "deleteParam", "/n", "/a/e") == [1, "parameter /a/e deleted", 0]
    assert call(m, "deleteParam", "/n", "/a/e") == [-1, "parameter [/a/e] is not set", 0]
    assert call(m, "deleteParam", "/n", "/") == [-1, "parameter [/] is not set", 0]
    assert call(m, "getParam", "/n", "/zz") == [-1, "Parameter [/zz] is not set", 0]


def test_search_param() -> None:
    m = master()
    call(m, "setParam", "/q", "/ns1/rel", 1)
    call(m, "setParam", "/q", "/ns1/node/priv", 1)
    call(m, "setParam", "/q", "/a/c", 1)
    assert call(m, "searchParam", "/ns1/node", "rel") == [1, "Found [/ns1/rel]", "/ns1/rel"]
    assert call(m, "searchParam", "/ns1/node", "priv") == [1, "Found [/ns1/node/priv]", "/ns1/node/priv"]
    assert call(m, "searchParam", "/ns1/sub/node", "a/c") == [1, "Found [/a/c]", "/a/c"]
    assert call(m, "searchParam", "/ns1/node", "rel/missing")[2] == "/ns1/rel/missing"
    assert call(m, "searchParam", "/x", "nope") == [-1, "Cannot find parameter [nope] in an upwards search", ""]
    assert call(m, "searchParam", "/x", "/a/c")[2] == "/a/c"
    assert call(m, "searchParam", "/x", "~p") == [0, "Internal failure: invalid key", 0]


def test_param_subscriptions() -> None:
    m = master()
    assert call(m, "subscribeParam", "/w", A, "/watched") == [1, "Subscribed to parameter [/watched]", {}]
    assert call(m, "subscribeParam", "/w2", B, "/watched/x") == [1, "Subscribed to parameter [/watched/x]", {}]
    r = m.call("setParam", ["/other", "/watched/x", 1])
    assert r.notifications == (ParamUpdate(A, "/watched/x/", 1), ParamUpdate(B, "/watched/x/", 1))
    # the caller is not told about its own change...
    assert m.call("setParam", ["/w", "/watched/x", 2]).notifications == (ParamUpdate(B, "/watched/x/", 2),)
    # ...but a dict over the namespace reaches subscribers below, and vanished keys get {}
    r = m.call("setParam", ["/w", "/watched", {"y": 1}])
    assert r.notifications == (ParamUpdate(B, "/watched/x/", {}),)
    r = m.call("setParam", ["/q", "/watched", {"x": {"z": 5}}])
    assert r.notifications == (ParamUpdate(A, "/watched/", {"x": {"z": 5}}), ParamUpdate(B, "/watched/x/", {"z": 5}))
    # a deletion is {} and reaches the deleting node too (rosmaster passes no caller there)
    r = m.call("deleteParam", ["/w", "/watched"])
    assert r.notifications == (ParamUpdate(A, "/watched/", {}), ParamUpdate(B, "/watched/x/", {}))
    assert m.call("setParam", ["/q", "/watchedness", 1]).notifications == ()


def test_shutdown() -> None:
    m = master()
    r = m.call("shutdown", ["/n", "bye"])
    assert r.value == [1, "shutdown", 0]
    assert r.shutdown == "external shutdown request from [/n]: bye"
    assert call(m, "getUri", "/n") == [1, "", URI]
    assert call(m, "getPid", "/n") == [1, "", 4242]


# ------------------------------------------------------------------ differential vs rosmaster

ORACLE = Path(__file__).with_name("rosmaster_oracle.py")
HAVE_ROSMASTER = os.path.isdir("/usr/lib/python3/dist-packages/rosmaster")


def _as_oracle(r: Any) -> list[Any]:
    notes = []
    for n in r.notifications:
        method, args = n.call
        notes.append([method, n.node_api, *args[1:]])
    return json.loads(json.dumps([r.value, notes]))


def _run_both(calls: list[tuple[str, list[Any]]]) -> None:
    out = subprocess.run(["/usr/bin/python3", str(ORACLE)], input=json.dumps(calls), capture_output=True,
                         text=True, timeout=60, check=True)
    want = json.loads(out.stdout.splitlines()[-1])  # rosmaster prints "shutdown request" lines
    m = master()
    for i, ((method, params), expected) in enumerate(zip(calls, want, strict=True)):
        try:
            got = _as_oracle(m.call(method, json.loads(json.dumps(params))))
        except Fault as f:
            got = [["fault", f.code, f.message], []]
        assert got == expected, f"call {i}: {method}{params}"


SCENARIO: list[tuple[str, list[Any]]] = [
    ("getSystemState", []), ("getSystemState", [1]), ("getParam", ["/n"]), ("getParam", ["/n", "k", 1]),
    ("getParam", ["/n", 0]), ("getParam", ["/n", [1]]), ("setParam", ["/n", "", 1]),
    ("registerPublisher", ["/n", "//", "p/T", A]), ("registerPublisher", ["/n", "a:b", "p/T", A]),
    ("registerPublisher", ["/n", 5, "p/T", A]), ("registerPublisher", ["/n", "t", "p/T/x", A]),
    ("registerPublisher", ["/n", "t", "", A]), ("registerPublisher", ["/n", "t", 3, A]),
    ("registerPublisher", ["/n", "t", "p/T", "ftp://x"]), ("registerPublisher", ["/n", "t", "p/T", ""]),
    ("registerService", ["/n", "/", "rosrpc://h:1", A]), ("lookupService", ["/n", "nothing"]),
    ("lookupNode", ["/n", ""]), ("lookupNode", ["/n", 3]), ("getPublishedTopics", ["/n", 3]),
    ("getPublishedTopics", ["/n", "rel"]), ("searchParam", ["rel", "x"]), ("searchParam", ["/n", "~x"]),
    ("subscribeParam", ["/n", "nope", "k"]), ("subscribeParam", ["/n", A, ""]),
    ("setParam", ["/n", "/", {"a": 1, "b": {"c": [1, "x", {"d": 2}]}}]), ("getParam", ["/n", "/b/c"]),
    ("getParam", ["/n", "/b//c/"]), ("getParam", ["/n", "/a/x"]), ("subscribeParam", ["/s", A, "/"]),
    ("setParam", ["/n", "/b", {"e": {"f": 1}}]), ("deleteParam", ["/s", "/b/e"]), ("getParamNames", ["/n"]),
    ("getUri", ["/n"]), ("nonexistent", ["/n"]), ("_notify", ["/n"]),
    ("unsubscribeParam", ["/s", B, "/"]), ("unsubscribeParam", ["/s", A, "/"]),
    ("registerSubscriber", ["/ns/node", "~sub", "*", A]), ("getTopicTypes", ["/n"]),
    ("registerPublisher", ["/ns/node", "/ns/node/sub", "*", A]), ("getTopicTypes", ["/n"]),
    ("shutdown", ["/n", ""]),  # last: rosmaster sends no notifications after it
]


@pytest.mark.skipif(not HAVE_ROSMASTER, reason="Debian rosmaster not installed")
def test_scenario_matches_rosmaster() -> None:
    _run_both(SCENARIO)


@pytest.mark.skipif(not HAVE_ROSMASTER, reason="Debian rosmaster not installed")
@pytest.mark.parametrize("seed", [1, 2, 3, 4])
def test_random_calls_match_rosmaster(seed: int) -> None:
    rng = random.Random(seed)
    nodes = ["/a", "/ns/b", "/ns/c", "/ns/sub/d"]
    apis = [A, B, C]
    topics = ["t", "/t", "/t/u", "~p", "ns/t", "/ns/t"]
    types = ["p/T", "p/U", "*"]
    services = ["s", "/s", "~srv"]
    srv_apis = ["rosrpc://h:1", "rosrpc://h:2"]
    keys = ["k", "/k", "/k/x", "/k/x/y", "~p", "/ns/k", "ns", "/"]
    values = [1, "s", 2.5, True, [1, 2], {}, {"x": 1}, {"x": {"y": 2}, "z": 3}, {"k": {"x": {"y": 1}}}]

    def gen() -> tuple[str, list[Any]]:
        n, api = rng.choice(nodes), rng.choice(apis)
        choices: list[tuple[str, list[Any]]] = [
            ("registerPublisher", [n, rng.choice(topics), rng.choice(types), api]),
            ("registerSubscriber", [n, rng.choice(topics), rng.choice(types), api]),
            ("unregisterPublisher", [n, rng.choice(topics), api]),
            ("unregisterSubscriber", [n, rng.choice(topics), api]),
            ("registerService", [n, rng.choice(services), rng.choice(srv_apis), api]),
            ("unregisterService", [n, rng.choice(services), rng.choice(srv_apis)]),
            ("lookupService", [n, rng.choice(services)]),
            ("lookupNode", [n, rng.choice(nodes)]),
            ("getSystemState", [n]), ("getTopicTypes", [n]),
            ("getPublishedTopics", [n, rng.choice(["", "/", "/t", "ns", "/ns"])]),
            ("setParam", [n, rng.choice(keys), rng.choice(values)]),
            ("getParam", [n, rng.choice(keys)]), ("hasParam", [n, rng.choice(keys)]),
            ("deleteParam", [n, rng.choice(keys)]), ("getParamNames", [n]),
            ("searchParam", [n, rng.choice(keys)]),
            ("subscribeParam", [n, api, rng.choice(keys)]),
            ("unsubscribeParam", [n, api, rng.choice(keys)]),
        ]
        return rng.choice(choices)

    _run_both([gen() for _ in range(1500)])


def test_set_param_refuses_what_get_param_could_not_send_back() -> None:
    # A 64-bit integer used to be stored, after which getParam('/') faulted for everyone.
    m = master()
    assert call(m, "setParam", "/n", "/big", 2**32) == [
        -1, "cannot set parameter [/big]: 4294967296 does not fit a 32-bit signed integer "
            "(int exceeds XML-RPC limits)", 0]
    assert call(m, "setParam", "/n", "/ns", {"ok": 1, "deep": [[-2**31 - 1]]})[0] == -1
    deep: Any = 1
    for _ in range(70):
        deep = [deep]
    assert "nest more than 64 levels" in call(m, "setParam", "/n", "/deep", deep)[1]
    assert call(m, "setParam", "/n", "/fine", [2**31 - 1, -2**31, {"x": [1.5]}])[0] == 1
    code, _, tree = call(m, "getParam", "/n", "/")
    assert code == 1 and tree == {"fine": [2**31 - 1, -2**31, {"x": [1.5]}]}
