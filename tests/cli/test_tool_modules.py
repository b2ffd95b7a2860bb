"""rostopic's and rosmsg's library functions, and the `rosgraph` command, as ROS 1's: the same
calls through Debian's real modules (tests/cli/tool_modules_driver.py under both interpreters,
on a workspace of two test packages), and kame's `rosgraph` beside Debian's /usr/bin/rosgraph
on one live kame graph."""

from __future__ import annotations

import json
import subprocess
import sys
from collections.abc import Iterator
from pathlib import Path
from typing import Any

import pytest

from tests.cli.live_graph import BIN, LiveGraph, live_graph
from tests.libs import debian
from tests.support import SYSTEM_PYTHON, Proc, wait_until

DRIVER = Path(__file__).with_name("tool_modules_driver.py")
DEBIAN_PACKAGES = [Path("/usr/share") / p for p in ("std_msgs", "geometry_msgs", "std_srvs", "sensor_msgs")]
PACKAGE_XML = ('<package format="2"><name>{}</name><version>0.0.1</version><description>probe</description>'
               '<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>\n')
needs_debian = pytest.mark.skipif(
    not (debian.has("rosmsg", "rostopic", "sensor_msgs.msg") and all(p.is_dir() for p in DEBIAN_PACKAGES)),
    reason="Debian's rosmsg, rostopic and message packages are not installed")


def workspace(root: Path) -> Path:
    """Two packages with a `Probe` message each (an ambiguous short name) and a service in one."""
    for name in ("kame_probe_a", "kame_probe_b"):
        (root / name / "msg").mkdir(parents=True)
        (root / name / "package.xml").write_text(PACKAGE_XML.format(name))
        (root / name / "msg" / "Probe.msg").write_text("int32 a\nstring bar\n")
    (root / "kame_probe_a" / "srv").mkdir()
    (root / "kame_probe_a" / "srv" / "Do.srv").write_text("int32 x\n---\nbool ok\n")
    (root / "kame_probe_b" / "msg" / "Other.msg").write_text("int8 b\n")
    return root


def answers(python: str | Path, ws: Path) -> Any:
    env = {**debian.debian_env(), "ROS_ROOT": "/usr/share/ros",
           "ROS_PACKAGE_PATH": ":".join(str(p) for p in [ws, *DEBIAN_PACKAGES])}
    done = subprocess.run([str(python), str(DRIVER)], capture_output=True, text=True, env=env, timeout=120)
    assert done.returncode == 0, done.stderr
    return json.loads(done.stdout)


@pytest.fixture(scope="module")
def ws(tmp_path_factory: pytest.TempPathFactory) -> Path:
    return workspace(tmp_path_factory.mktemp("ws"))


@pytest.fixture(scope="module")
def kame(ws: Path) -> Any:
    return answers(sys.executable, ws)


@pytest.fixture(scope="module")
def ros(ws: Path) -> Any:
    return answers(SYSTEM_PYTHON, ws)


@needs_debian
def test_rostopic_plot_helpers(kame: Any, ros: Any) -> None:
    fields = kame["rostopic"]["fields"]
    assert fields[0] == [["header", "pose"], "time,field.header.seq,field.header.stamp,field.header.frame_id,"
                         "field.pose.position.x,field.pose.position.y,field.pose.position.z,"
                         "field.pose.orientation.x,field.pose.orientation.y,field.pose.orientation.z,"
                         "field.pose.orientation.w"]
    assert kame["rostopic"]["plot"][0][0].startswith("5000000006,0,3000000004,map,1.5,")
    for key in ("fields", "plot", "header_stamp", "no_header_no_time"):
        assert kame["rostopic"][key] == ros["rostopic"][key], key


@needs_debian
def test_rostopic_msgevalgen(kame: Any, ros: Any) -> None:
    assert kame["rostopic"]["evalgen"]["/pose["] == [None, "", "missing closing ']' in slice spec 'pose['\n"]
    assert kame["rostopic"]["evalgen"] == ros["rostopic"]["evalgen"]


@needs_debian
def test_rostopic_callback_echo(kame: Any, ros: Any) -> None:
    assert kame["echo"]["count"][1:] == [1, True]
    assert kame["echo"]["plot"][0].startswith("%time,field.header.seq,")
    assert kame["echo"] == ros["echo"]


@needs_debian
def test_rosmsg_prototype(kame: Any, ros: Any) -> None:
    assert kame["rosmsg"]["prototype"]["msg Probe"] == [["exit", 1], "", "Ambiguous message name Probe"]
    assert kame["rosmsg"]["prototype"] == ros["rosmsg"]["prototype"]


@needs_debian
def test_rosmsg_command_parts(kame: Any, ros: Any) -> None:
    assert kame["rosmsg"]["list"] == ["kame_probe_a/Probe", "kame_probe_b/Other", "kame_probe_b/Probe"]
    assert kame["rosmsg"]["names_filter"][1] == ["header", "name", "position", "velocity", "effort"]
    for key in ("iterate", "iterate_bad_mode", "search", "list", "list_srv", "packages", "packages_one_line", "md5",
                "debug", "fullusage", "names_filter", "exceptions"):
        assert kame["rosmsg"][key] == ros["rosmsg"][key], key


def star_names(python: str | Path) -> set[str]:
    code = "ns = {}\nexec('from rosmsg import *', ns)\nprint(' '.join(sorted(ns)))"
    done = subprocess.run([str(python), "-c", code], capture_output=True, text=True, env=debian.debian_env(),
                          timeout=60)
    assert done.returncode == 0, done.stderr
    return set(done.stdout.split()) - {"__builtins__"}


@pytest.mark.skipif(not debian.has("rosmsg"), reason="Debian's rosmsg is not installed")
def test_from_rosmsg_import_star() -> None:
    """The same names as ROS's, but for those README's "ROS Python modules: names not provided"
    gives reasons for (the genmsg module) and a __future__ feature."""
    left_out = {"genmsg", "print_function"}
    assert star_names(sys.executable) == star_names(SYSTEM_PYTHON) - left_out


# ------------------------------------------------------------------------------- rosgraph


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[LiveGraph]:
    with live_graph(tmp_path_factory.mktemp("rosgraph")) as g:
        listener = Proc([str(BIN / "rostopic"), "echo", "/chatter"], g.env)  # a node-to-node connection
        g.procs.append(listener)
        listener.wait_line("data:")
        yield g


def pictures(proc: Proc, count: int) -> list[dict[str, Any]]:
    """The first `count` pictures rosgraph printed, as {node: (inbound, outbound)} and services,
    each list sorted (rosgraph prints sets, in an order that varies between runs)."""
    assert wait_until(lambda: "".join(proc.out).count("Services:") > count, timeout=30), "".join(proc.err)
    found: list[dict[str, Any]] = []
    for text in "".join(proc.out).split("Nodes:")[1:count + 1]:
        nodes: dict[str, list[list[str]]] = {}
        services: list[str] = []
        node = part = ""
        for line in text.splitlines():
            if line.startswith("  ") and line.endswith(" :"):
                node = line.strip()[:-2]
                nodes[node] = [[], []]
            elif line.strip() in ("Inbound:", "Outbound:", "Services:"):
                part = line.strip()
            elif line.strip():
                if part == "Services:":
                    services.append(line.strip())
                else:
                    nodes[node][part == "Outbound:"].append(line.strip())
        found.append({"nodes": {n: [sorted(i), sorted(o)] for n, (i, o) in nodes.items()},
                      "services": sorted(services)})
    return found


def rosgraph_run(graph: LiveGraph, command: list[str]) -> list[dict[str, Any]]:
    proc = Proc(command, graph.env, cwd=graph.home)
    try:
        return pictures(proc, 2)
    finally:
        proc.stop()


def test_rosgraph_command(graph: LiveGraph) -> None:
    second = rosgraph_run(graph, [str(BIN / "rosgraph")])[1]
    listener = next(n for n in second["nodes"] if n.startswith("/rostopic_"))
    assert second["nodes"]["/graph_node"][1] == ["/rosout", listener]
    assert second["nodes"][listener][0] == ["/graph_node"]
    assert "/add_two_ints" in second["services"]
    if debian.has("rosgraph.rosgraph_main"):
        assert rosgraph_run(graph, [str(SYSTEM_PYTHON), "/usr/bin/rosgraph"])[1] == second


def test_rosgraph_usage(graph: LiveGraph) -> None:
    ours = graph.kame("rosgraph", "-h")
    assert ours.returncode == 0 and ours.stdout.startswith("rosgraph is a command-line tool")
    extra = graph.kame("rosgraph", "x")
    assert extra.returncode == 255 and extra.stdout == ours.stdout
    if debian.has("rosgraph.rosgraph_main"):
        for args in (["-h"], ["x"]):
            real = graph.real("rosgraph", *args)
            mine = graph.kame("rosgraph", *args)
            assert (mine.returncode, mine.stdout, mine.stderr) == (real.returncode, real.stdout, real.stderr)
