"""roswtf's pure checks (kame.cli._wtf): tables of environments and graph snapshots, and the
report text they give."""

from __future__ import annotations

import pytest

from kame.cli import _wtf
from kame.cli._wtf import Environment, Graph, Link, NodeFacts, PackageFacts, PathFacts, PathKind, Report

DIR = PathFacts(PathKind.DIRECTORY)
FILE = PathFacts(PathKind.FILE)
RO_DIR = PathFacts(PathKind.DIRECTORY, writable=False)
LOCAL = ("127.0.0.1", "10.0.0.5")
URI = "http://localhost:11311/"


def env_report(variables: dict[str, str], master_uri: str = URI, **facts: object) -> Report:
    facts.setdefault("addresses", {"localhost": ["127.0.0.1"], "box": ["10.0.0.5"]})
    facts.setdefault("paths", {"/ws": DIR})
    env = Environment(variables, master_uri, hostname="box", local_addresses=LOCAL, **facts)  # type: ignore[arg-type]
    report = Report()
    _wtf.check_environment(env, report)
    _wtf.check_network(env, report)
    return report


@pytest.mark.parametrize(("variables", "master_uri", "facts", "warnings", "errors"), [
    ({"ROS_PACKAGE_PATH": "/ws"}, URI, {}, [], []),
    ({}, URI, {}, ["ROS_PACKAGE_PATH is not set. This is not required, but is unusual"], []),
    ({"ROS_PACKAGE_PATH": ""}, URI, {}, ["ROS_PACKAGE_PATH is empty. This is not required, but is unusual"], []),
    ({"ROS_PACKAGE_PATH": "/ws:/gone:/f"}, URI, {"paths": {"/ws": DIR, "/f": FILE}}, [], [
        "Path(s) in ROS_PACKAGE_PATH [/ws:/gone:/f] points to a file instead of a directory: \n * /f\n",
        "Not all paths in ROS_PACKAGE_PATH [/ws:/gone:/f] point to an existing directory: \n * /gone\n * /f\n"]),
    ({"ROS_PACKAGE_PATH": "/ws", "PYTHONPATH": "/ws:/nope"}, URI, {}, [],
     ["Not all paths in PYTHONPATH [/ws:/nope] point to a directory: \n * /nope\n"]),
    ({"ROS_PACKAGE_PATH": "/ws"}, "", {}, ["ROS_MASTER_URI is empty. This is not required, but is unusual"], []),
    ({"ROS_PACKAGE_PATH": "/ws"}, "foo://x", {}, [],
     ["ROS_MASTER_URI [foo://x] is not a valid URL: protocol is not 'http'"]),
    ({"ROS_PACKAGE_PATH": "/ws"}, "http://localhost", {}, [],
     ["ROS_MASTER_URI [http://localhost] is not a valid URL: port number is missing"]),
    ({"ROS_PACKAGE_PATH": "/ws"}, "http://localhost:x/", {}, [],
     ["ROS_MASTER_URI [http://localhost:x/] is not a valid URL: port number [x] is invalid"]),
    ({"ROS_PACKAGE_PATH": "/ws"}, "http://nowhere:11311", {}, [
        "Cannot resolve hostname in ROS_MASTER_URI [http://nowhere:11311]Unknown host nowhere"], []),
    ({"ROS_PACKAGE_PATH": "/ws", "ROS_HOSTNAME": "nowhere"}, URI, {}, [
        "ROS_HOSTNAME may be incorrect: ROS_HOSTNAME [nowhere] cannot be resolved to an IP address"], []),
    ({"ROS_PACKAGE_PATH": "/ws", "ROS_HOSTNAME": "far"}, URI,
     {"addresses": {"localhost": ["127.0.0.1"], "far": ["8.8.8.8"]}}, [
         "ROS_HOSTNAME may be incorrect: ROS_HOSTNAME [far] resolves to [8.8.8.8], which does not appear to be a "
         "local IP address ['127.0.0.1', '10.0.0.5']."], []),
    ({"ROS_PACKAGE_PATH": "/ws", "ROS_HOSTNAME": "localhost", "ROS_IP": "10.0.0.5"}, URI, {}, [], []),
    ({"ROS_PACKAGE_PATH": "/ws", "ROS_IP": "10.9.9.9"}, URI, {}, [
        "ROS_IP may be incorrect: ROS_IP [10.9.9.9] does not appear to be an IP address of a local network "
        "interface (one of ['127.0.0.1', '10.0.0.5'])."], []),
    ({"ROS_PACKAGE_PATH": "/ws", "ROS_IP": "10.0.0.5 "}, URI, {}, [
        "ROS_IP may be incorrect: ROS_IP [10.0.0.5 ] contains whitespace. This is not a valid IP."], []),
    ({"ROS_PACKAGE_PATH": "/ws"}, URI, {"addresses": {"localhost": ["127.0.0.1"], "box": ["10.7.7.7"]}}, [], [
        "Local network configuration is invalid: Local hostname [box] resolves to [10.7.7.7], which does not "
        "appear to be a local IP address ['127.0.0.1', '10.0.0.5']."]),
    ({"ROS_PACKAGE_PATH": "/ws", "ROS_HOME": "/f", "ROS_LOG_DIR": "/ro"}, URI,
     {"paths": {"/ws": DIR, "/f": FILE, "/ro": RO_DIR}}, [],
     ["ROS_HOME is invalid: ROS_HOME [/f] must point to a directory, not a file",
      "ROS_LOG_DIR is invalid: ROS_LOG_DIR [/ro] is not writable"]),
    ({"ROS_PACKAGE_PATH": "/ws", "ROSCONSOLE_CONFIG_FILE": "/none"}, URI, {},
     ["ROS_CONSOLE_CONFIG_FILE does not point to an existing file"], []),
])
def test_environment_rules(variables: dict[str, str], master_uri: str, facts: dict[str, object],
                           warnings: list[str], errors: list[str]) -> None:
    report = env_report(variables, master_uri, **facts)
    assert (report.warnings, report.errors) == (warnings, errors)


def test_what_the_cli_must_look_up() -> None:
    variables = {"ROS_PACKAGE_PATH": "/b:/a:", "PYTHONPATH": "/p", "ROS_HOME": "/h", "ROS_HOSTNAME": "me"}
    assert _wtf.paths_to_inspect(variables) == ["/a", "/b", "/h", "/p"]
    assert _wtf.hosts_to_resolve(variables, "http://master:11311/", "box") == ["box", "master", "me"]
    assert _wtf.hosts_to_resolve({}, "http://a:b:c/", "box") == ["box"]


def test_package_rules() -> None:
    report = Report()
    _wtf.check_packages([PackageFacts("ok", "/ws/ok"),
                         PackageFacts("z", "/ws/z", "not well-formed XML: x", ["/ws/z/msg/A.msg:2: bad"]),
                         PackageFacts("a", "/ws/a", None, ["/ws/a/srv/S.srv:1: worse"])], report)
    assert report.errors == [
        "The following packages have an invalid package.xml:\n * z [/ws/z]: not well-formed XML: x\n",
        "The following message and service definitions cannot be loaded:\n"
        " * /ws/a/srv/S.srv:1: worse\n * /ws/z/msg/A.msg:2: bad\n"]


# ------------------------------------------------------------------ the graph

UP = NodeFacts("http://h:1/")


def node(*links: Link, pubs: list[tuple[str, str]] | None = None, subs: list[tuple[str, str]] | None = None,
         **kw: object) -> NodeFacts:
    return NodeFacts("http://h:1/", bus=list(links), publications=pubs, subscriptions=subs, **kw)  # type: ignore[arg-type]


def graph_report(graph: Graph) -> Report:
    report = Report()
    _wtf.check_graph(graph, report)
    return report


CONNECTED = Graph({"/chatter": ["/talker"]}, {"/chatter": ["/listener"]}, {},
                  {"/talker": node(Link("/chatter", "/talker", "/listener")),
                   "/listener": node(Link("/chatter", "/talker", "/listener"))})


@pytest.mark.parametrize(("graph", "warnings", "errors"), [
    (CONNECTED, [], []),
    (Graph({}, {"/b": ["/n"], "/a": ["/n"], "/clock": ["/n"]}, {"/n/s": ["/n"]}, {"/n": node()}),
     ["The following node subscriptions are unconnected:\n * /n:\n   * /b\n   * /a\n"], []),  # master order
    (Graph({}, {"/clock": ["/n"], "/reset_time": ["/n"]}, {"/s": ["/n"]}, {"/n": node()}, use_sim_time=True),
     ["The following node subscriptions are unconnected:\n * /n:\n   * /clock\n"],
     ["/use_sim_time is set but no publisher of /clock is present"]),
    (Graph({"/t": ["/p"]}, {"/t": ["/s"]}, {}, {"/p": node(Link("/t", "/p", "/other")), "/s": node(),
                                                 "/other": node(Link("/t", "/p", "/other"))}),
     ["Node [/s] is not connected to anything",
      "The following nodes are unexpectedly connected:\n * /p->/other (/t)\n"],
     ["The following nodes should be connected but aren't:\n * /p->/s (/t)\n"]),
    (Graph({"/t": ["/p", "/dead"]}, {}, {"/dead/srv": ["/dead"]},
           {"/p": node(), "/dead": NodeFacts("http://h:2/", reachable=False)},
           service_failures={"/dead/srv": "appears to be malfunctioning: Unable to communicate"}),
     ["Node [/p] is not connected to anything"],
     ["Could not contact the following nodes:\n * /dead\n",
      "Errors connecting to the following services:\n"
      " * service [/dead/srv] appears to be malfunctioning: Unable to communicate\n"]),
    (Graph({"/t": ["/ghost"]}, {}, {}, {"/ghost": NodeFacts(None, reachable=False)}), [],
     ["Master does not have lookup information for node [/ghost]",
      "Could not contact the following nodes:\n * /ghost\n"]),
    (Graph({"/t": ["/n"]}, {}, {"/s": ["/n"]}, {"/n": NodeFacts("http://h:1/", bus=None)}),
     ["Node [/n] would not return bus info"], []),
    (Graph({"/t": ["/n"]}, {}, {"/s": ["/n"]}, {"/n": NodeFacts("http://h:1/", error="boom")}), [],
     ["Communication with [/n] raised an error: boom"]),
])
def test_graph_rules(graph: Graph, warnings: list[str], errors: list[str]) -> None:
    report = graph_report(graph)
    assert (report.warnings, report.errors) == (warnings, errors)


def test_type_mismatch_names_every_node_with_its_type() -> None:
    link = Link("/chatter", "/talker", "/ok")
    graph = Graph({"/chatter": ["/talker"]}, {"/chatter": ["/wrong", "/ok"]}, {"/x": ["/wrong"]},
                  {"/talker": node(link, pubs=[("/chatter", "std_msgs/String")]),
                   "/ok": node(link, subs=[("/chatter", "std_msgs/String")]),
                   "/wrong": node(subs=[("/chatter", "std_msgs/Int32")])})
    assert graph_report(graph).errors == [
        "The following nodes should be connected but aren't:\n * /talker->/wrong (/chatter)\n",
        "The following topics have nodes that disagree on the message type:\n * /chatter:\n"
        "   * /talker publishes [std_msgs/String]\n   * /ok subscribes [std_msgs/String]\n"
        "   * /wrong subscribes [std_msgs/Int32]\n"]


def test_registrations_the_node_does_not_report_are_stale() -> None:
    graph = Graph({"/old": ["/n"], "/t": ["/n"]}, {"/gone": ["/n"]}, {"/s": ["/n"]},
                  {"/n": node(pubs=[("/t", "std_msgs/String")], subs=[])})
    assert graph_report(graph).warnings == [
        "The following node subscriptions are unconnected:\n * /n:\n   * /gone\n",
        "The master lists registrations these nodes do not report (stale, or another node of the same name):\n"
        " * /n: publisher of /old\n * /n: subscriber of /gone\n"]


def test_bus_links() -> None:
    rows = [[1, "http://h:1/", "i", "TCPROS", "/a", True], [2, "/sub", "o", "TCPROS", "/b", 1, "info"],
            [3, "http://x:9/", "i", "TCPROS", "/c"], [4, "/gone", "o", "TCPROS", "/d", False],
            [5, "/x", "b", "T", "/e"]]
    assert _wtf.bus_links("/me", rows, {"http://h:1/": "/pub"}) == [
        Link("/a", "/pub", "/me"), Link("/b", "/me", "/sub"), Link("/c", "unknown (http://x:9/)", "/me")]


@pytest.mark.parametrize(("report", "text"), [
    (Report(), "No errors or warnings\n"),
    (Report(["w1", "w2\n * x\n"], []),
     "Found 2 warning(s).\nWarnings are things that may be just fine, but are sometimes at fault\n\n"
     "\x1b[1mWARNING\x1b[0m w1\n\x1b[1mWARNING\x1b[0m w2\n * x\n\n\n"),
    (Report([], ["e"]), "Found 1 error(s).\n\n\x1b[31m\x1b[1mERROR\x1b[0m e\n"),
])
def test_format_report(report: Report, text: str) -> None:
    assert _wtf.format_report(report) == text


def test_roslaunch_rules_over_list_processes_answers() -> None:
    report = Report()
    _wtf.check_launches([([["master", 1], ["resp-2", 3]], [["brief-5", 1]]),
                         ([["talker-1", 2]], [])], report)
    assert report.warnings == ["These nodes have respawned at least once:\n * resp-2 (3)\n * talker-1 (2)\n",
                               "These nodes have died:\n * brief-5\n"]
    quiet = Report()
    _wtf.check_launches([([["master", 1]], [])], quiet)
    assert quiet.warnings == [] and quiet.errors == []


REMOTE = "http://robot:11311/"
ROBOT = {"robot": ["10.0.0.9"], "box": ["10.0.0.5"], "localhost": ["127.0.0.1"]}


@pytest.mark.parametrize(("variables", "addresses", "advertised"), [
    ({"ROS_HOSTNAME": "localhost"}, ROBOT, "[localhost], which means [127.0.0.1]"),
    ({"ROS_IP": "127.0.0.1"}, ROBOT, "[127.0.0.1], which means [127.0.0.1]"),
    ({}, {**ROBOT, "box": ["127.0.1.1"]}, "[box], which means [127.0.1.1]"),  # Debian's hosts file
])
def test_advertising_loopback_with_the_master_on_another_machine_is_an_error(
        variables: dict[str, str], addresses: dict[str, list[str]], advertised: str) -> None:
    report = env_report({"ROS_PACKAGE_PATH": "/ws", **variables}, REMOTE, addresses=addresses)
    found = [e for e in report.errors if e.startswith("Nodes on other machines cannot reach this one: ")]
    assert len(found) == 1 and advertised in found[0] and "Set ROS_IP" in found[0], report.errors


@pytest.mark.parametrize(("variables", "master_uri", "addresses"), [
    ({"ROS_HOSTNAME": "localhost"}, URI, ROBOT),  # everything on this machine: loopback is right
    ({"ROS_HOSTNAME": "box"}, REMOTE, ROBOT),
    ({"ROS_IP": "10.0.0.5"}, REMOTE, ROBOT),
    ({"ROS_HOSTNAME": "localhost"}, REMOTE, {"box": ["10.0.0.5"]}),  # the master's host is unknown: another rule
])
def test_no_loopback_error_when_it_is_right_or_not_the_problem(
        variables: dict[str, str], master_uri: str, addresses: dict[str, list[str]]) -> None:
    report = env_report({"ROS_PACKAGE_PATH": "/ws", **variables}, master_uri, addresses=addresses)
    assert not [e for e in report.errors if e.startswith("Nodes on other machines")], report.errors


def test_nodes_advertising_an_unusable_address_are_an_error_naming_the_fix() -> None:
    graph = Graph({"/chatter": ["/talker", "/local", "/fine"]}, {}, {}, {
        "/talker": NodeFacts("http://laptop.wrong:4100/", reachable=False,
                             unusable_address="its name does not resolve on this machine"),
        "/local": NodeFacts("http://127.0.0.1:4200/", reachable=False),
        "/fine": NodeFacts("http://laptop:4300/"),
    })
    title = "The following nodes advertise an address this machine cannot use"
    report = Report()
    _wtf.check_graph(graph, report, master_remote=True)
    [error] = [e for e in report.errors if e.startswith(title)]
    assert "ROS_IP" in error and "ROS_HOSTNAME" in error
    assert error.splitlines()[1:] == [
        " * /local advertises [127.0.0.1:4200]: a loopback address, which only its own machine can use",
        " * /talker advertises [laptop.wrong:4100]: its name does not resolve on this machine"]
    report = Report()
    _wtf.check_graph(graph, report)  # the master on this machine: loopback URIs are fine
    [error] = [e for e in report.errors if e.startswith(title)]
    assert "/local" not in error


@pytest.mark.parametrize(("remote", "sent", "received", "skew"), [
    (1000.0, 1000.2, 1000.3, 0.0),  # the same second: fine
    (1000.0, 1000.9, 1001.0, 0.0),  # its second ended as ours began: cannot tell
    (1030.0, 1000.2, 1000.3, 29.7),  # at least 29.7 s ahead
    (970.0, 1000.2, 1000.3, -29.2),  # at least 29.2 s behind (its second ends at 971)
])
def test_a_clock_reading_claims_only_the_skew_its_whole_second_proves(remote: float, sent: float, received: float,
                                                                       skew: float) -> None:
    reading = _wtf.ClockReading("laptop", "the master", remote, sent, received)
    assert reading.skew == pytest.approx(skew)


def test_machines_whose_clocks_are_off_are_a_warning_one_line_each() -> None:
    def at(host: str, who: str, offset: float) -> _wtf.ClockReading:
        return _wtf.ClockReading(host, who, 1000.0 + offset, 1000.2, 1000.3)

    graph = Graph({"/a": ["/talker", "/listener", "/local"]}, {}, {}, {
        "/talker": NodeFacts("http://laptop:1/", clock=at("laptop", "node /talker", 5.0)),
        "/listener": NodeFacts("http://laptop:2/", clock=at("laptop", "node /listener", 12.0)),
        "/local": NodeFacts("http://robot:3/", clock=at("robot", "node /local", 0.0)),
    }, master_clock=at("tablet", "the master", -60.0))
    report = Report()
    _wtf.check_graph(graph, report)
    [warning] = [w for w in report.warnings if w.startswith("The clocks of these machines differ")]
    assert "chrony" in warning
    assert warning.splitlines()[1:] == [" * laptop (node /listener): 11.7 s ahead of this machine",
                                        " * tablet (the master): 59.2 s behind this machine"]
    report = Report()
    _wtf.check_graph(Graph({}, {}, {}, {}, master_clock=at("robot", "the master", 0.0)), report)
    assert report.warnings == []
