"""roswtf's checks over a snapshot of the environment and of the graph, and its report (pure).

- The CLI gathers facts (variables, what each named path is, what host names resolve to, what
  the master and each node answered); the rules here only read them, so every rule is a
  table test. Nothing here touches the network, the clock or the filesystem.
- A rule yields nothing (fine), a list (an item block: the title, then ` * item` lines and a
  blank line), or text appended to the title: roswtf's rule shapes, so the report reads as
  the real one does, its missing spaces included.
- Rules run in the real tool's order: environment warnings, then errors; network; packages;
  graph warnings, then errors. Items are sorted where the real tool's order is a hash's.
- kame adds two graph rules the real tool lacks (it only notices these as missing
  connections): a topic whose nodes disagree on the message type, and registrations at the
  master that the node itself does not report (a stale entry, or a second node started under
  the same name). And a third that ROS leaves to its documentation: machines whose clocks
  differ from this one's by more than a second (the Date of the master's and nodes' answers;
  whole seconds, so only a skew the answer's time bounds prove is reported).
"""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence
from dataclasses import dataclass, field
from enum import Enum
from urllib.parse import urlsplit

BOLD = "\x1b[1m"
RED = "\x1b[31m"
RESET = "\x1b[0m"
SEPARATOR = "=" * 80
WARNING_HINT = "Warnings are things that may be just fine, but are sometimes at fault"

Outcome = Sequence[str] | str | bool | None


@dataclass
class Report:
    warnings: list[str] = field(default_factory=list)
    errors: list[str] = field(default_factory=list)

    def warn(self, title: str, outcome: Outcome) -> None:
        _add(self.warnings, title, outcome)

    def error(self, title: str, outcome: Outcome) -> None:
        _add(self.errors, title, outcome)


def _add(into: list[str], title: str, outcome: Outcome) -> None:
    if not outcome:
        return
    if isinstance(outcome, str):
        into.append(title + outcome)
    elif isinstance(outcome, bool):
        into.append(title)
    else:
        into.append(title + "\n" + "\n".join(f" * {item}" for item in outcome) + "\n")


def format_report(report: Report) -> str:
    """The summary block: `No errors or warnings`, or the counted WARNING and ERROR lines."""
    if not report.warnings and not report.errors:
        return "No errors or warnings\n"
    out = []
    if report.warnings:
        out.append(f"Found {len(report.warnings)} warning(s).\n{WARNING_HINT}\n\n")
        out.extend(f"{BOLD}WARNING{RESET} {w}\n" for w in report.warnings)
        out.append("\n")
    if report.errors:
        out.append(f"Found {len(report.errors)} error(s).\n\n")
        out.extend(f"{RED}{BOLD}ERROR{RESET} {e}\n" for e in report.errors)
    return "".join(out)


# ------------------------------------------------------------------ environment


class PathKind(Enum):
    MISSING = "missing"
    FILE = "file"
    DIRECTORY = "directory"


@dataclass(frozen=True)
class PathFacts:
    kind: PathKind
    writable: bool = True


@dataclass(frozen=True)
class Environment:
    """What the environment checks read.

    `paths` says what each path named by `paths_to_inspect` is; `addresses` what each name of
    `hosts_to_resolve` resolves to (absent or None: it does not resolve).
    """

    variables: Mapping[str, str]
    master_uri: str
    paths: Mapping[str, PathFacts] = field(default_factory=dict)
    addresses: Mapping[str, Sequence[str] | None] = field(default_factory=dict)
    hostname: str = "localhost"
    local_addresses: Sequence[str] = ()

    def path(self, path: str) -> PathFacts:
        return self.paths.get(path, PathFacts(PathKind.MISSING, False))


WRITABLE_DIRS = ("ROS_HOME", "ROS_LOG_DIR", "ROS_TEST_RESULTS_DIR")


def split_paths(value: str | None) -> list[str]:
    return value.split(":") if value else []


def paths_to_inspect(variables: Mapping[str, str]) -> list[str]:
    found = [*split_paths(variables.get("ROS_PACKAGE_PATH")), *split_paths(variables.get("PYTHONPATH"))]
    found += [variables[name] for name in (*WRITABLE_DIRS, "ROSCONSOLE_CONFIG_FILE") if name in variables]
    return sorted({p for p in found if p})


def master_host(master_uri: str) -> str | None:
    """The host of a well-formed ROS_MASTER_URI's `host:port`, else None (another rule says why)."""
    netloc = urlsplit(master_uri).netloc if master_uri else ""
    parts = netloc.split(":")
    return parts[0] if len(parts) == 2 else None


def hosts_to_resolve(env_vars: Mapping[str, str], master_uri: str, hostname: str) -> list[str]:
    hosts = [master_host(master_uri), env_vars.get("ROS_HOSTNAME"), hostname]
    return sorted({h for h in hosts if h is not None})


def invalid_url(url: str) -> str | None:
    """Why `url` is not a usable master URI; an empty one is another rule's business."""
    if not url:
        return None
    parts = urlsplit(url)
    if parts.scheme != "http":
        return "protocol is not 'http'"
    if not parts.netloc:
        return "address is missing"
    if ":" not in parts.netloc:
        return "port number is missing"
    pieces = parts.netloc.split(":")
    if len(pieces) != 2:
        return f"invalid address string [{parts.netloc}]"
    if not pieces[1].isdigit():
        return f"port number [{pieces[1]}] is invalid"
    return None


def _writable_dir(env: Environment, name: str) -> str | None:
    path = env.variables.get(name)
    if path is None:
        return None
    facts = env.path(path)
    if facts.kind is PathKind.FILE:
        return f"{name} [{path}] must point to a directory, not a file"
    if not facts.writable:
        return f"{name} [{path}] is not writable"
    return None


def _master_host_unresolved(env: Environment) -> str | None:
    host = master_host(env.master_uri)
    if host is None or env.addresses.get(host):
        return None
    return f"Unknown host {host}"


def _ros_hostname(env: Environment) -> str | None:
    hostname = env.variables.get("ROS_HOSTNAME")
    if hostname is None:
        return None
    resolved = env.addresses.get(hostname)
    if not resolved:
        return f"ROS_HOSTNAME [{hostname}] cannot be resolved to an IP address"
    remote = sorted(set(resolved) - set(env.local_addresses))
    if remote:
        return (f"ROS_HOSTNAME [{hostname}] resolves to [{','.join(remote)}], which does not appear to be a "
                f"local IP address {list(env.local_addresses)}.")
    return None


def _ros_ip(env: Environment) -> str | None:
    ip = env.variables.get("ROS_IP")
    if ip is None:
        return None
    if " " in ip:
        return f"ROS_IP [{ip}] contains whitespace. This is not a valid IP."
    if ip not in env.local_addresses:
        return (f"ROS_IP [{ip}] does not appear to be an IP address of a local network interface "
                f"(one of {list(env.local_addresses)}).")
    return None


def _local_hostname(env: Environment) -> str | None:
    resolved = env.addresses.get(env.hostname) or ()
    remote = sorted({ip for ip in resolved if not ip.startswith("127.") and ip != "::1"} - set(env.local_addresses))
    if remote:
        return (f"Local hostname [{env.hostname}] resolves to [{','.join(remote)}], which does not appear to be "
                f"a local IP address {list(env.local_addresses)}.")
    return None


def check_environment(env: Environment, report: Report) -> None:
    v = env.variables
    package_path = v.get("ROS_PACKAGE_PATH")
    pythonpath = v.get("PYTHONPATH")
    uri = env.master_uri
    report.warn("ROS_PACKAGE_PATH is not set. This is not required, but is unusual", package_path is None)
    report.warn("ROS_PACKAGE_PATH is empty. This is not required, but is unusual",
                package_path is not None and not split_paths(package_path))
    report.warn("ROS_MASTER_URI is empty. This is not required, but is unusual", not uri)
    report.warn(f"Cannot resolve hostname in ROS_MASTER_URI [{uri}]", _master_host_unresolved(env))
    report.warn("ROS_CONSOLE_CONFIG_FILE does not point to an existing file",
                "ROSCONSOLE_CONFIG_FILE" in v and env.path(v["ROSCONSOLE_CONFIG_FILE"]).kind is not PathKind.FILE)

    entries = [p for p in split_paths(package_path) if p]
    report.error(f"Path(s) in ROS_PACKAGE_PATH [{package_path}] points to a file instead of a directory: ",
                 [p for p in entries if env.path(p).kind is PathKind.FILE])
    report.error(f"Not all paths in ROS_PACKAGE_PATH [{package_path}] point to an existing directory: ",
                 [p for p in entries if env.path(p).kind is not PathKind.DIRECTORY])
    report.error(f"Not all paths in PYTHONPATH [{pythonpath}] point to a directory: ",
                 [p for p in split_paths(pythonpath) if p and env.path(p).kind is not PathKind.DIRECTORY])
    for name in WRITABLE_DIRS:
        report.error(f"{name} is invalid: ", _writable_dir(env, name))
    bad_url = invalid_url(uri)
    report.error(f"ROS_MASTER_URI [{uri}] is not a valid URL: ", bad_url)


def is_loopback(address: str) -> bool:
    return address == "localhost" or address.startswith("127.") or address == "::1"


def master_is_remote(env: Environment) -> bool:
    """Whether ROS_MASTER_URI names another machine: its host resolves, and to none of ours."""
    host = master_host(env.master_uri)
    resolved = env.addresses.get(host) if host else None
    return bool(resolved) and not any(is_loopback(a) or a in env.local_addresses for a in resolved or ())


def _advertised_loopback(env: Environment) -> str | None:
    """kame's own addition: this machine's nodes advertise a name or address that means loopback
    (ROS_HOSTNAME=localhost, ROS_IP=127.0.0.1, a host name mapped to 127.0.1.1) while the master
    is on another machine, so that nodes there cannot reach the nodes here."""
    if not master_is_remote(env):
        return None
    v = env.variables
    advertised = v.get("ROS_HOSTNAME") or ("ROS_HOSTNAME" not in v and v.get("ROS_IP")) or None
    if advertised is None:
        if is_loopback(env.hostname):
            return None  # rosgraph then advertises an interface's address instead
        advertised = env.hostname
    resolved = list(env.addresses.get(advertised) or ([advertised] if is_loopback(advertised) else []))
    if not resolved or not all(is_loopback(a) for a in resolved):
        return None
    usable = [a for a in env.local_addresses if not is_loopback(a)]
    return (f"this machine's nodes advertise [{advertised}], which means [{','.join(resolved)}] (loopback), but "
            f"the master [{master_host(env.master_uri)}] is on another machine: nodes there cannot connect to "
            f"nodes here. Set ROS_IP to this machine's address (one of {usable}) or ROS_HOSTNAME to a name "
            f"that the other machines resolve to it.")


def check_network(env: Environment, report: Report) -> None:
    report.warn("ROS_HOSTNAME may be incorrect: ", _ros_hostname(env))
    report.warn("ROS_IP may be incorrect: ", _ros_ip(env))
    report.error("Local network configuration is invalid: ", _local_hostname(env))
    report.error("Nodes on other machines cannot reach this one: ", _advertised_loopback(env))


# ------------------------------------------------------------------ packages


@dataclass(frozen=True)
class PackageFacts:
    """A package as found on the search path, with what reading its files said."""

    name: str
    path: str
    manifest_problem: str | None = None
    # what went wrong with each msg/srv/action file that does not load, naming the file
    definition_problems: Sequence[str] = ()


def check_packages(packages: Iterable[PackageFacts], report: Report) -> None:
    packages = sorted(packages, key=lambda p: p.name)
    report.error("The following packages have an invalid package.xml:",
                 [f"{p.name} [{p.path}]: {p.manifest_problem}" for p in packages if p.manifest_problem])
    report.error("The following message and service definitions cannot be loaded:",
                 [problem for p in packages for problem in p.definition_problems])


# ------------------------------------------------------------------ the graph

Registrations = Mapping[str, Sequence[str]]  # topic or service -> node names


@dataclass(frozen=True)
class Link:
    """One connected entry of a node's getBusInfo: on `topic`, data flows from `source` to `sink`."""

    topic: str
    source: str
    sink: str


@dataclass(frozen=True)
class NodeFacts:
    """What the master and the node said. `uri` None: the master has no lookup information.

    `reachable` False: the node did not answer (ping). `bus` None: it would not give its bus
    info; `error`: its answer raised this. `publications`/`subscriptions` are (topic, type)
    pairs from the node's own API, None when it did not say.
    """

    uri: str | None
    reachable: bool = True
    bus: Sequence[Link] | None = ()
    error: str | None = None
    publications: Sequence[tuple[str, str]] | None = None
    subscriptions: Sequence[tuple[str, str]] | None = None
    # why its advertised address is unusable from here (it does not resolve, no route), when
    # that is why it did not answer
    unusable_address: str | None = None
    clock: ClockReading | None = None


@dataclass(frozen=True)
class ClockReading:
    """An answer's Date against our clock: the server's whole second `remote`, which it sent
    between our `sent` and `received` (seconds since the epoch)."""

    host: str
    who: str  # "the master", "node /talker"
    remote: float
    sent: float
    received: float

    @property
    def skew(self) -> float:
        """How far the server's clock is ahead (>0) or behind (<0) ours, at least; 0 when the
        answer cannot tell (its Date's second is compatible with our clock)."""
        ahead = self.remote - self.received  # it read at least `remote` when we read at most `received`
        behind = self.remote + 1.0 - self.sent  # it read less than `remote + 1` when we read `sent` or more
        return ahead if ahead > 0 else behind if behind < 0 else 0.0


CLOCK_SKEW_LIMIT = 1.0  # seconds: below, a Date (whole seconds) cannot tell


def clock_skews(readings: Iterable[ClockReading], limit: float = CLOCK_SKEW_LIMIT) -> list[str]:
    """One line per machine whose clock is off by more than `limit`, with its largest skew."""
    worst: dict[str, ClockReading] = {}
    for reading in readings:
        known = worst.get(reading.host)
        if known is None or abs(reading.skew) > abs(known.skew):
            worst[reading.host] = reading
    return [f"{host} ({r.who}): {abs(r.skew):.1f} s {'ahead of' if r.skew > 0 else 'behind'} this machine"
            for host, r in sorted(worst.items()) if abs(r.skew) > limit]


@dataclass(frozen=True)
class Graph:
    publishers: Registrations
    subscribers: Registrations
    services: Registrations
    nodes: Mapping[str, NodeFacts]
    use_sim_time: bool = False
    # service -> why probing it failed (services missing here answered)
    service_failures: Mapping[str, str] = field(default_factory=dict)
    master_clock: ClockReading | None = None

    @property
    def node_names(self) -> list[str]:
        found: set[str] = set()
        for part in (self.publishers, self.subscribers, self.services):
            for names in part.values():
                found.update(names)
        return sorted(found)


def bus_links(node: str, bus_info: Sequence[Sequence[object]], uri_nodes: Mapping[str, str]) -> list[Link]:
    """A node's getBusInfo rows as links; peers named by URI are named by node when known."""
    links = []
    for row in bus_info:
        if len(row) < 5:
            continue
        peer, direction, topic = str(row[1]), row[2], str(row[4])
        connected = bool(row[5]) if len(row) > 5 else True
        if not connected:
            continue
        if peer.startswith("http://"):
            peer = uri_nodes.get(peer, f"unknown ({peer})")
        if direction == "i":
            links.append(Link(topic, peer, node))
        elif direction == "o":
            links.append(Link(topic, node, peer))
    return links


def expected_links(graph: Graph) -> set[Link]:
    return {Link(topic, pub, sub)
            for topic, subs in graph.subscribers.items()
            for sub in subs
            for pub in graph.publishers.get(topic, ())}


def actual_links(graph: Graph) -> set[Link]:
    return {link for facts in graph.nodes.values() for link in (facts.bus or ())}


def unconnected_subscriptions(graph: Graph) -> str:
    ignored = {"/reset_time"} if graph.use_sim_time else {"/time", "/clock"}
    by_node: dict[str, list[str]] = {}
    for topic, subs in graph.subscribers.items():
        if topic in graph.publishers:
            continue
        for sub in subs:
            by_node.setdefault(sub, []).append(topic)
    out = ""
    for node in by_node:  # as roswtf: in the master's order (nodes as first met), not sorted
        topics = [t for t in by_node[node] if t not in ignored]
        if topics:
            out += f" * {node}:\n" + "".join(f"   * {t}\n" for t in topics)
    return out


def _link_text(links: Iterable[Link]) -> list[str]:
    return sorted(f"{link.source}->{link.sink} ({link.topic})" for link in links)


def unexpected_links(graph: Graph) -> list[str]:
    if not graph.node_names:
        return []
    return _link_text(actual_links(graph) - expected_links(graph))


def missing_links(graph: Graph) -> list[str]:
    if not graph.node_names:
        return []
    return _link_text(expected_links(graph) - actual_links(graph))


def unreachable_nodes(graph: Graph) -> list[str]:
    return [n for n in graph.node_names if n in graph.nodes and not graph.nodes[n].reachable]


def unusable_addresses(graph: Graph, master_remote: bool = False) -> list[str]:
    """Nodes whose URI this machine cannot use; with the master on another machine, a loopback
    URI too (it means the machine of whoever connects, not the node's)."""
    out = []
    for node, facts in sorted(graph.nodes.items()):
        if not facts.uri:
            continue
        reason = facts.unusable_address
        if reason is None and master_remote and is_loopback(urlsplit(facts.uri).hostname or ""):
            reason = "a loopback address, which only its own machine can use"
        if reason:
            out.append(f"{node} advertises [{urlsplit(facts.uri).netloc}]: {reason}")
    return out


def sim_time_without_clock(graph: Graph) -> bool:
    return graph.use_sim_time and not ({"/time", "/clock"} & set(graph.publishers))


def service_failures(graph: Graph) -> list[str]:
    return [f"service [{name}] {why}" for name, why in sorted(graph.service_failures.items())]


def type_mismatches(graph: Graph) -> list[str]:
    """Topics whose nodes disagree on the type, each node named with the type it uses."""
    uses: dict[str, dict[tuple[str, str], str]] = {}
    for node, facts in graph.nodes.items():
        for role, pairs in (("publishes", facts.publications), ("subscribes", facts.subscriptions)):
            for topic, type_name in pairs or ():
                if type_name and type_name != "*":
                    uses.setdefault(topic, {})[(node, role)] = type_name
    out = []
    for topic in sorted(uses):
        if len(set(uses[topic].values())) > 1:
            users = sorted(uses[topic].items(), key=lambda item: (item[0][1] != "publishes", item[0][0]))
            out.append(f"{topic}:\n" + "\n".join(f"   * {node} {role} [{t}]" for (node, role), t in users))
    return out


def stale_registrations(graph: Graph) -> list[str]:
    """What the master lists for a node that the node itself (answering at its URI) does not have."""
    out = []
    for node in graph.node_names:
        facts = graph.nodes.get(node)
        if facts is None or not facts.reachable:
            continue
        for role, registered, own in (("publisher", graph.publishers, facts.publications),
                                      ("subscriber", graph.subscribers, facts.subscriptions)):
            if own is None:
                continue
            mine = {topic for topic, _ in own}
            for topic in sorted(t for t, nodes in registered.items() if node in nodes and t not in mine):
                out.append(f"{node}: {role} of {topic}")
    return out


def check_graph(graph: Graph, report: Report, master_remote: bool = False) -> None:
    # what gathering each node found, in the order the real tool's threads report it
    for node in graph.node_names:
        facts = graph.nodes.get(node)
        if facts is None:
            continue
        if facts.uri is None:
            report.error(f"Master does not have lookup information for node [{node}]", True)
        elif facts.error is not None:
            report.error(f"Communication with [{node}] raised an error: {facts.error}", True)
        elif facts.reachable and facts.bus is None:
            report.warn(f"Node [{node}] would not return bus info", True)
        elif facts.reachable and not facts.bus and not any(node in p for p in graph.services.values()):
            report.warn(f"Node [{node}] is not connected to anything", True)
    report.warn("The following node subscriptions are unconnected:\n", unconnected_subscriptions(graph))
    report.warn("The following nodes are unexpectedly connected:", unexpected_links(graph))
    report.warn("The master lists registrations these nodes do not report "
                "(stale, or another node of the same name):", stale_registrations(graph))
    readings = [graph.master_clock, *(facts.clock for facts in graph.nodes.values())]
    report.warn("The clocks of these machines differ from this machine's (time stamps, tf and rosbag compare "
                "them; synchronise the machines' clocks, with chrony or ntpd):",
                clock_skews(r for r in readings if r is not None))
    report.error("/use_sim_time is set but no publisher of /clock is present", sim_time_without_clock(graph))
    report.error("Could not contact the following nodes:", unreachable_nodes(graph))
    report.error("The following nodes advertise an address this machine cannot use (start each with ROS_IP "
                 "set to its machine's IP address, or ROS_HOSTNAME set to a name that resolves to it here):",
                 unusable_addresses(graph, master_remote))
    report.error("The following nodes should be connected but aren't:", missing_links(graph))
    report.error("Errors connecting to the following services:", service_failures(graph))
    report.error("The following topics have nodes that disagree on the message type:", type_mismatches(graph))


def check_launches(listings: Sequence[tuple[Sequence[Sequence[object]], Sequence[Sequence[object]]]],
                   report: Report) -> None:
    """roswtf's roslaunch rules over each roslaunch server's `list_processes` answer (running,
    dead; each [process name, spawn count]); servers that did not answer are left out, as
    roswtf leaves them to a rule it has switched off."""
    respawned = [f"{name} ({count})" for running, _ in listings for name, count, *_ in running
                 if isinstance(count, int) and count > 1]
    died = [str(name) for _, dead in listings for name, *_ in dead]
    report.warn("These nodes have respawned at least once:", respawned)
    report.warn("These nodes have died:", died)


# ---------------------------------------------------------------- tf's roswtf plugin (tf.tfwtf)

@dataclass(frozen=True)
class TfTransform:
    parent: str
    child: str
    stamp: float  # seconds
    rotation_length: float  # of its quaternion


@dataclass(frozen=True)
class TfMessage:
    """One /tf message as tf's plugin keeps it: its transforms, when it came (ROS time) and from whom."""
    transforms: tuple[TfTransform, ...]
    received: float
    callerid: str


def _rostime_delta(messages: Sequence[TfMessage]) -> list[str]:
    deltas: dict[str, float] = {}
    for m in messages:
        for t in m.transforms:
            seconds = t.stamp - m.received
            if abs(seconds) > 1.0 and abs(seconds) > abs(deltas.get(m.callerid, 0.0)):
                deltas[m.callerid] = seconds
    return [f"receiving transform from [{k}] that differed from ROS time by {v}s" for k, v in deltas.items()]


def _not_normalized(messages: Sequence[TfMessage]) -> list[str]:
    return [f"rotation from [{t.parent}] to [{t.child}] is not unit length, {t.rotation_length}"
            for m in messages for t in m.transforms if abs(t.rotation_length - 1) > 1e-6]


def _reparenting(messages: Sequence[TfMessage]) -> list[str]:
    errors: list[str] = []
    parents: dict[str, str] = {}
    for m in messages:
        for t in m.transforms:
            if t.child in parents and parents[t.child] != t.parent:
                text = f"reparenting of [{t.child}] to [{t.parent}] by [{m.callerid}]"
                if text not in errors:
                    errors.append(text)
            parents[t.child] = t.parent
    return errors


def _cycles(messages: Sequence[TfMessage], max_depth: int = 100) -> list[str]:
    parents = {t.child: t.parent for m in messages for t in m.transforms}
    errors = []
    for frame in parents:
        chain, current = [], frame
        for _ in range(max_depth + 2):
            chain.append(current)
            if current not in parents:
                break
            current = parents[current]
            if current == frame:
                errors.append(f"Frame {frame} is in a loop. It's loop has elements:\n{' -> '.join(chain)}")
                break
    return errors


def _multiple_authority(messages: Sequence[TfMessage]) -> list[str]:
    errors: list[str] = []
    authority: dict[str, str] = {}
    for m in messages:
        for t in m.transforms:
            if t.child in authority and authority[t.child] != m.callerid:
                text = (f"node [{m.callerid}] publishing transform [{t.child}] with parent [{t.parent}] already "
                        f"published by node [{authority[t.child]}]")
                if text not in errors:
                    errors.append(text)
            authority[t.child] = m.callerid
    return errors


def check_tf(messages: Sequence[TfMessage], report: Report) -> None:
    """tf's roswtf plugin's rules over what /tf carried for a second, with its texts."""
    report.warn("No tf messages", not messages)
    report.warn("Received out-of-date/future transforms:", _rostime_delta(messages))
    report.warn("Received non-normalized rotation in transforms:", _not_normalized(messages))
    report.error("TF re-parenting contention:", _reparenting(messages))
    report.error("TF cycle detection::", _cycles(messages))
    report.error("TF multiple authority contention:", _multiple_authority(messages))
