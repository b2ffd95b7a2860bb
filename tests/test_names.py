import json
import os
import subprocess

import pytest

from kame import names

CANONICAL = [
    ("", ""),
    ("/", "/"),
    ("a//b/", "a/b"),
    ("//a/", "/a"),
    ("/a/b", "/a/b"),
    ("~x//y/", "~x/y"),
]


@pytest.mark.parametrize(("name", "want"), CANONICAL)
def test_canonicalize(name: str, want: str) -> None:
    assert names.canonicalize(name) == want


RESOLVE = [
    # (name, caller, want): spec §1.1 and the master examples
    ("/x/y", "/ns/node", "/x/y"),
    ("x/y", "/ns/node", "/ns/x/y"),
    ("~x", "/ns/node", "/ns/node/x"),
    ("", "/ns/node", "/ns/"),
    ("~priv", "/ns1/node", "/ns1/node/priv"),
    ("rel", "/ns1/node", "/ns1/rel"),
    ("a//b/", "/node", "/a/b"),
    ("/", "/node", "/"),
    ("x", "", "/x"),
    # a relative caller_id is not fixed up: rosmaster gives these results too
    ("x", "a/b", "a/x"),
    ("~x", "node", "node/x"),
]


@pytest.mark.parametrize(("name", "caller", "want"), RESOLVE)
def test_resolve(name: str, caller: str, want: str) -> None:
    assert names.resolve(name, caller) == want


def test_resolve_applies_remappings_after_canonicalising() -> None:
    table = names.resolve_remappings({"chatter": "talk", "~priv/x": "remapped"}, "/robot1/node")
    assert table == {"/robot1/chatter": "/robot1/talk", "/robot1/node/priv/x": "/robot1/remapped"}
    assert names.resolve("chatter//", "/robot1/node", table) == "/robot1/talk"
    assert names.resolve("~priv/x", "/robot1/node", table) == "/robot1/remapped"
    # exact match only, no prefix remapping
    assert names.resolve("chatter/sub", "/robot1/node", table) == "/robot1/chatter/sub"


def test_namespace_and_join() -> None:
    assert names.namespace("/ns/node") == "/ns/"
    assert names.namespace("/ns/") == "/"
    assert names.namespace("node") == "/"
    assert names.namespace("") == "/"
    assert names.ns_join("/ns", "x") == "/ns/x"
    assert names.ns_join("/ns/", "x") == "/ns/x"
    assert names.ns_join("/ns", "/g") == "/g"
    assert names.ns_join("/ns", "~p") == "~p"
    assert names.ns_join("~", "p") == "~p"
    assert names.ns_join("", "p") == "p"
    assert names.make_global_ns("envns") == "/envns/"
    assert names.make_global_ns("/a/") == "/a/"
    with pytest.raises(ValueError):
        names.make_global_ns("~x")


@pytest.mark.parametrize(
    ("name", "legal"),
    [("", True), ("/a/b_1", True), ("~p", True), ("a", True), ("1a", False), ("a//b", False),
     ("a b", False), ("a:b", False), ("a-b", False), ("_a", False)],
)
def test_is_legal_name(name: str, legal: bool) -> None:
    assert names.is_legal_name(name) is legal


@pytest.mark.parametrize(
    ("name", "legal"), [("node", True), ("n_1", True), ("/node", False), ("1n", False), ("", False)]
)
def test_is_legal_base_name(name: str, legal: bool) -> None:
    assert names.is_legal_base_name(name) is legal


def test_global_private() -> None:
    assert names.is_global("/a") and not names.is_global("a") and not names.is_global("")
    assert names.is_private("~a") and not names.is_private("/a") and not names.is_private("")


def test_parse_args() -> None:
    argv = ["prog", "chatter:=talk", "~p:=/q", "__name:=n", "__ns:=/r", "__master:=http://h:1/",
            "__ip:=1.2.3.4", "__hostname:=h", "__log:=/tmp/x.log", "__unknown:=z", "_rate:=10",
            "_list:=[1, 2]", "plain", "a=b", "1x:=y", "--flag", "empty:="]
    ros = names.parse_args(argv)
    assert ros.remappings == {"chatter": "talk", "~p": "/q"}
    assert ros.params == {"~rate": "10", "~list": "[1, 2]"}
    assert ros.special == {"name": "n", "ns": "/r", "master": "http://h:1/", "ip": "1.2.3.4",
                           "hostname": "h", "log": "/tmp/x.log"}
    # `1x:=y` is not a name, so rospy leaves it to the program
    assert ros.argv == ["prog", "plain", "a=b", "1x:=y", "--flag"]


def test_later_argument_wins() -> None:
    assert names.parse_args(["a:=b", "a:=c"]).remappings == {"a": "c"}


ROSGRAPH_CHECK = """
import json, sys
import rosgraph.names as n
cases = json.loads(sys.stdin.read())
print(json.dumps([[n.resolve_name(a, c), n.canonicalize_name(a), n.is_legal_name(a)] for a, c in cases]))
"""


@pytest.mark.skipif(not os.path.exists("/usr/lib/python3/dist-packages/rosgraph"), reason="no rosgraph")
def test_matches_rosgraph() -> None:
    raw = ["", "/", "a", "/a", "~a", "a/b//c/", "//x//", "~/x", "~x/y/", "a b", "/a:b", "x_1/y"]
    callers = ["/", "/node", "/ns/node", "/a/b/c/", "node", "a/b", ""]
    cases = [[a, c] for a in raw for c in callers]
    out = subprocess.run(["/usr/bin/python3", "-c", ROSGRAPH_CHECK], input=json.dumps(cases),
                         capture_output=True, text=True, check=True, timeout=30)
    want = json.loads(out.stdout)
    got = [[names.resolve(a, c), names.canonicalize(a), names.is_legal_name(a)] for a, c in cases]
    assert got == want
