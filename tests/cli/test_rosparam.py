"""rosparam end to end: kame's installed command against a live kame roscore, as a user types it,
then side by side with Debian's real rosparam on the same parameter server."""

from __future__ import annotations

import xmlrpc.client
from collections.abc import Iterator
from pathlib import Path

import pytest

from tests.cli.live_graph import LiveGraph, live_graph, no_master_env
from tests.support import have_debian_ros


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveGraph]:
    with live_graph(tmp_path_factory.mktemp("rosparam")) as g:
        yield g


def stored(graph: LiveGraph, name: str) -> object:
    code, msg, value = xmlrpc.client.ServerProxy(graph.uri).getParam("/test", name)
    assert code == 1, msg
    return value


def ok(graph: LiveGraph, *args: str, input: str | None = None) -> str:
    result = graph.kame("rosparam", *args, input=input)
    assert result.returncode == 0, result.stderr
    assert result.stderr == ""
    return result.stdout


# (typed on the command line, stored value) from spec §7
TYPING = [
    ("1", 1), ("-3", -3), ("0x10", 16), ("010", 8), ("1:30", 90),
    ("1.0", 1.0), ("1.5e-3", 1.5e-3), ("1e3", "1e3"), ("nan", "nan"),
    ("true", True), ("True", True), ("yes", True), ("on", True), ("false", False), ("no", False), ("off", False),
    ('"1"', "1"), ("'2'", "2"), ("!!str 1", "1"), ("hello", "hello"), ("", ""),
    ("[1, 2, three]", [1, 2, "three"]),
]


@pytest.mark.parametrize(("typed", "value"), TYPING, ids=[t or "empty" for t, _ in TYPING])
def test_yaml_typing(graph: LiveGraph, typed: str, value: object) -> None:
    ok(graph, "set", "/typing", typed)
    got = stored(graph, "/typing")
    assert got == value and type(got) is type(value)


def test_infinity_is_a_double(graph: LiveGraph) -> None:
    ok(graph, "set", "/inf", ".inf")
    assert stored(graph, "/inf") == float("inf")
    assert ok(graph, "get", "/inf") == ".inf\n"


@pytest.mark.parametrize(("typed", "problem"), [
    ("~", "null"), ("null", "null"), ("2020-01-01", "date"), ("3000000000", "32-bit"), ("[1, ~]", "null"),
])
def test_values_the_server_cannot_hold_are_one_error_line(graph: LiveGraph, typed: str, problem: str) -> None:
    result = graph.kame("rosparam", "set", "/bad", typed)
    assert result.returncode == 1
    assert result.stderr.startswith("ERROR: cannot set parameter [/bad]: ")
    assert problem in result.stderr and result.stderr.count("\n") == 1
    assert "Traceback" not in result.stderr


def test_set_verbose_and_dict_merges_leaf_by_leaf(graph: LiveGraph) -> None:
    assert ok(graph, "set", "-v", "/vv", "3") == "set parameter [/vv] to [3]\n"
    ok(graph, "set", "/s", "{a: 1, b: {c: x}}")
    assert ok(graph, "set", "-v", "/s", "{a: 2, e: [1, 2]}") == (
        "set parameter [/s/a] to [2]\nset parameter [/s/e] to [[1, 2]]\n")
    assert stored(graph, "/s") == {"a": 2, "b": {"c": "x"}, "e": [1, 2]}
    assert ok(graph, "get", "/s") == "a: 2\nb:\n  c: x\ne:\n- 1\n- 2\n\n"
    assert ok(graph, "get", "-p", "/s") == "a: 2\nb:\n  c: x\ne: - 1\n- 2\n"
    assert ok(graph, "get", "/s/a") == "2\n"


def test_get_formats(graph: LiveGraph) -> None:
    assert ok(graph, "get", "/rosdistro") == "'noetic\n\n  '\n\n"
    assert ok(graph, "get", "-p", "/rosdistro") == "noetic\n\n"
    ok(graph, "set", "/quoted", "'1'")
    assert ok(graph, "get", "/quoted") == "'1'\n\n"  # strings have no `...` to strip
    ok(graph, "set", "/flag", "yes")
    assert ok(graph, "get", "/flag") == "true\n"
    assert ok(graph, "get", "-v", "/flag") == "getting parameter [/flag]\ntrue\n"


def test_negative_numbers_and_text_files(graph: LiveGraph) -> None:
    ok(graph, "set", "/neg", "-3.5")
    assert stored(graph, "/neg") == -3.5
    (graph.home / "t.txt").write_text("multi\nline\n")
    ok(graph, "set", "-t", "t.txt", "/txt")
    assert stored(graph, "/txt") == "multi\nline\n"
    assert ok(graph, "get", "-p", "/txt") == "multi\nline\n\n"


def test_load_dump_list_delete(graph: LiveGraph) -> None:
    (graph.home / "p.yaml").write_text(
        "a: 1\nb:\n  c: x\n  d: [1, 2.5, '3']\n/abs_key: on\nang: !degrees 180\nr: rad(pi/2)\n---\nsecond: 2\n")
    out = ok(graph, "load", "-v", "p.yaml", "/cp")
    assert out == ("reading parameters from [p.yaml]\n/cp/a=1\n/cp/b/c=x\n/cp/b/d=[1, 2.5, '3']\n/abs_key=True\n"
                   "/cp/ang=3.141592653589793\n/cp/r=1.5707963267948966\n/cp/second=2\n")
    assert stored(graph, "/abs_key") is True
    assert ok(graph, "list", "/cp") == "/cp/a\n/cp/ang\n/cp/b/c\n/cp/b/d\n/cp/r\n/cp/second\n"
    dumped = ("a: 1\nang: 3.141592653589793\nb:\n  c: x\n  d:\n  - 1\n  - 2.5\n  - '3'\n"
              "r: 1.5707963267948966\nsecond: 2\n")
    assert ok(graph, "dump", "out.yaml", "/cp") == ""
    assert (graph.home / "out.yaml").read_text() == dumped
    assert ok(graph, "dump", "-", "/cp") == dumped
    # the tutorial's round trip: dump, load into another namespace
    ok(graph, "load", "out.yaml", "/copy")
    assert stored(graph, "/copy") == stored(graph, "/cp")
    assert ok(graph, "load", "-", "/stdin", input="k: v\n") == ""
    assert stored(graph, "/stdin/k") == "v"
    assert ok(graph, "delete", "-v", "/copy") == "deleted parameter [/copy]\n"
    assert "/copy/a" not in ok(graph, "list").split()
    listing = ok(graph, "list").splitlines()
    assert listing == sorted(listing) and "/cp/b/c" in listing and "/rosdistro" in listing


@pytest.mark.parametrize(("args", "stderr"), [
    (("get", "/nosuch"), "ERROR: Parameter [/nosuch] is not set\n"),
    (("delete", "/nosuch"), "ERROR: parameter [/nosuch] is not set\n"),
    (("load", "nofile.yaml"), "ERROR: file [nofile.yaml] does not exist\n"),
])
def test_errors(graph: LiveGraph, args: tuple[str, ...], stderr: str) -> None:
    result = graph.kame("rosparam", *args)
    assert (result.returncode, result.stdout, result.stderr) == (1, "", stderr)


def test_load_of_a_file_that_is_not_text_is_one_line(graph: LiveGraph) -> None:
    (graph.home / "binary.yaml").write_bytes(b"a: 1\nb: \xff\xfe\x00\n")
    result = graph.kame("rosparam", "load", "binary.yaml")
    assert (result.returncode, result.stdout) == (1, "")
    assert result.stderr == "ERROR: file [binary.yaml] is not UTF-8 text (byte 8): not a YAML file?\n"


def test_usage_errors(graph: LiveGraph) -> None:
    result = graph.kame("rosparam", "set", "/x")
    assert result.returncode == 2
    assert result.stderr.endswith("rosparam: error: invalid arguments. Please specify a parameter value\n")
    result = graph.kame("rosparam")
    assert result.returncode == 0 and result.stdout.startswith("rosparam is a command-line tool")


@pytest.mark.parametrize("args", [("get", "/x"), ("set", "/x", "1"), ("list",), ("delete", "/x"), ("dump",)])
def test_no_master(graph: LiveGraph, tmp_path: Path, args: tuple[str, ...]) -> None:
    result = graph.kame("rosparam", *args, env=no_master_env(tmp_path))
    assert (result.returncode, result.stderr) == (1, "ERROR: Unable to communicate with master!\n")


# ------------------------------------------------------------------ beside Debian's rosparam

debian = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 is not installed")


@debian
def test_same_typing_as_real_rosparam(graph: LiveGraph) -> None:
    values = [t for t, _ in TYPING] + [".inf", "{a: 1, b: {c: [x, 2]}}", "'multi\n\nline'", "deg(90)", "-0.5"]
    for i, typed in enumerate(values):
        ok(graph, "set", f"/cmp/kame/v{i}", typed)
        assert graph.real("rosparam", "set", f"/cmp/real/v{i}", typed).returncode == 0
    assert stored(graph, "/cmp/kame") == stored(graph, "/cmp/real")
    for sub in ("", "/v1", "/v18"):
        assert ok(graph, "get", f"/cmp/kame{sub}") == graph.real("rosparam", "get", f"/cmp/real{sub}").stdout


@debian
@pytest.mark.parametrize("args", [
    ("get", "/"), ("get", "-p", "/"), ("get", "/rosdistro"), ("get", "-p", "/rosdistro"), ("list",),
    ("dump",), ("get", "/nosuch"), ("delete", "/nosuch"), ("get",), ("set",), ("list", "a", "b"), ("bogus",),
    ("set", "-v", "/same", "{x: 1, y: [1, 2]}"),
])
def test_same_output_as_real_rosparam(graph: LiveGraph, args: tuple[str, ...]) -> None:
    ok(graph, "set", "/shown", "{a: 1, b: {c: 'two'}, t: 'x\n\ny', l: [1, 2]}")
    mine = graph.kame("rosparam", *args)
    real = graph.real("rosparam", *args)
    assert (mine.returncode, mine.stdout, mine.stderr) == (real.returncode, real.stdout, real.stderr)
