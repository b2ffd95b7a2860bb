"""roswtf: checks of the environment, the packages and (when a master answers) the running graph.

This module gathers the facts: variables and the paths and host names they name, the packages
on ROS_PACKAGE_PATH (the current package's too, and kame's own with --all), and a snapshot of
the graph (the master's registrations, then every node asked in parallel for its pid, bus
info, publications and subscriptions, every service probed). The checks and the report
are kame.cli._wtf's. The exit status is 0 whatever was found, as with the real tool; the
online part is skipped, saying so, when no master answers.
"""

from __future__ import annotations

import errno
import os
import sys
import threading
import time
import xml.etree.ElementTree as ElementTree
from collections.abc import Callable, Mapping, Sequence
from concurrent.futures import ThreadPoolExecutor
from functools import partial
from pathlib import Path
from urllib.parse import urlsplit

from catkin_pkg.package import InvalidPackage, parse_package_string

from kame.cli import _wtf
from kame.cli._options import OptionParser
from kame.cli._tool import DEFAULT_MASTER_URI, run
from kame.msg.catalog import SHARE_DIR, MsgCatalog, Package, find_packages, package_path_roots
from kame.msg.errors import MessageError
from kame.net import interfaces
from kame.net.address import DOES_NOT_RESOLVE, NO_ROUTE, unreachable_reason
from kame.net.xmlrpc_client import XmlRpcProxy
from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.services import probe_service
from kame.protocol.http import parse_date
from kame.protocol.xmlrpc import XmlRpcError

ID = "/roswtf"
TIMEOUT = 3.0  # per call to a node, as the real tool's socket timeout
USAGE = "usage: roswtf [launch file]"
DESCRIPTION = ("roswtf is a tool for verifying a ROS installation and running system. Checks provided "
               "launchfile if provided, else current stack or package.")


class MasterLost(Exception):
    pass


# ------------------------------------------------------------------ the environment


def _path_facts(path: str) -> _wtf.PathFacts:
    if os.path.isdir(path):
        kind = _wtf.PathKind.DIRECTORY
    elif os.path.exists(path):
        kind = _wtf.PathKind.FILE
    else:
        kind = _wtf.PathKind.MISSING
    return _wtf.PathFacts(kind, os.access(path, os.W_OK))


def gather_environment(variables: Mapping[str, str]) -> _wtf.Environment:
    master_uri = variables.get("ROS_MASTER_URI", DEFAULT_MASTER_URI)
    ipv6 = variables.get("ROS_IPV6") == "on"
    hostname = interfaces.hostname()
    hosts = _wtf.hosts_to_resolve(variables, master_uri, hostname)
    return _wtf.Environment(
        variables=variables,
        master_uri=master_uri,
        paths={p: _path_facts(p) for p in _wtf.paths_to_inspect(variables)},
        addresses={h: interfaces.resolve(h, ipv6) for h in hosts},
        hostname=hostname,
        local_addresses=interfaces.local_addresses(ipv6),
    )


# ------------------------------------------------------------------ packages


def current_package(cwd: Path) -> str | None:
    """The folder holding the nearest package.xml at or above `cwd`, named as rospkg names it."""
    for folder in (cwd, *cwd.parents):
        if (folder / "package.xml").is_file() or (folder / "manifest.xml").is_file():
            return folder.name
    return None


def _manifest_problem(path: Path) -> str | None:
    try:
        text = path.read_text(encoding="utf-8")
        root = ElementTree.fromstring(text)
    except (OSError, UnicodeDecodeError) as exc:
        return f"cannot be read: {exc}"
    except ElementTree.ParseError as exc:
        return f"not well-formed XML: {exc}"
    if root.tag != "package":
        return f"the root element is <{root.tag}>, not <package>"
    try:
        parse_package_string(text, filename=str(path), warnings=[])
    except InvalidPackage as exc:
        lines = str(exc).splitlines()
        return "; ".join(lines[1:] or lines)
    return None


def _definition_problems(package: Package, catalog: MsgCatalog) -> list[str]:
    """What goes wrong loading each msg/srv/action file (and the types it uses), naming the file."""
    problems: list[str] = []

    def attempt(path: Path, load: Callable[[], None]) -> None:
        try:
            load()
        except MessageError as exc:
            text = str(exc)
            problems.append(text if text.startswith(str(path)) else f"{path}: {text}")

    def msg(name: str) -> None:
        catalog.check_dependencies(catalog.msg_spec(name))

    def srv(name: str) -> None:
        spec = catalog.srv_spec(name)
        catalog.check_dependencies(spec.request)
        catalog.check_dependencies(spec.response)

    def action(name: str) -> None:
        for suffix in ("Goal", "Result", "Feedback"):
            msg(name + suffix)

    loaders: list[tuple[str, Callable[[str], None]]] = [("msg", msg), ("srv", srv), ("action", action)]
    for kind, load in loaders:
        for path in package.interface_files(kind):
            attempt(path, partial(load, f"{package.name}/{path.stem}"))
    return problems


def gather_packages(variables: Mapping[str, str], cwd: Path, everything: bool) -> list[_wtf.PackageFacts]:
    roots = package_path_roots(variables.get("ROS_PACKAGE_PATH", ""))
    packages = find_packages(roots)
    catalog = MsgCatalog(packages)
    user_roots = [r.resolve() for r in roots if r != SHARE_DIR]
    here = cwd.resolve()

    def wanted(pkg: Package) -> bool:
        path = pkg.path.resolve()
        if everything or path == here or path in here.parents:
            return True
        return any(root == path or root in path.parents for root in user_roots)

    return [_wtf.PackageFacts(pkg.name, str(pkg.path), _manifest_problem(pkg.path / "package.xml"),
                              _definition_problems(pkg, catalog))
            for pkg in packages.values() if wanted(pkg)]


# ------------------------------------------------------------------ plugins

TF_LISTEN = 1.0  # seconds tf's plugin listens to /tf


def roswtf_plugins(variables: Mapping[str, str]) -> list[str]:
    """The plugins packages export to roswtf (`<export><roswtf plugin="tf.tfwtf"/>`) that kame
    runs: tf's, whose online rules look at a second of /tf."""
    found: list[str] = []
    for pkg in find_packages(package_path_roots(variables.get("ROS_PACKAGE_PATH", ""))).values():
        try:
            exports = ElementTree.parse(pkg.path / "package.xml").getroot().findall("export/roswtf")
        except (OSError, ElementTree.ParseError):
            continue
        found.extend(e.get("plugin", "") for e in exports if e.get("plugin") in ONLINE_PLUGINS)
    return sorted(found)


def listen_tf(uri: str, report: _wtf.Report) -> None:
    """tf's plugin: what /tf carries for TF_LISTEN seconds, then its rules."""
    from kame.node.config import node_config
    from kame.node.node import Node
    from tf2_msgs.msg import TFMessage

    print("running tf checks, this will take a second...", flush=True)
    special = {"name": f"roswtf_{os.getpid()}_{int(time.time() * 1000)}", "master": uri}
    node = Node(node_config("roswtf", special, os.environ))
    heard: list[_wtf.TfMessage] = []

    def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
        message = TFMessage._from_buffer(frames[-1])
        transforms = tuple(_wtf.TfTransform(t.header.frame_id, t.child_frame_id, t.header.stamp.to_sec(),
                                            sum(v * v for v in (t.transform.rotation.x, t.transform.rotation.y,
                                                                t.transform.rotation.z, t.transform.rotation.w))
                                            ** 0.5)
                           for t in message.transforms)
        heard.append(_wtf.TfMessage(transforms, time.time(), header.get("callerid", "")))

    try:
        node.subscribe("/tf", TFMessage._type, TFMessage._md5sum, TFMessage._full_text, deliver)
        threading.Event().wait(TF_LISTEN)  # the plugin's sample is a window of time, not an event
    finally:
        node.shutdown("roswtf done")
    print("... tf checks complete")
    _wtf.check_tf(list(heard), report)


ONLINE_PLUGINS: dict[str, Callable[[str, _wtf.Report], None]] = {"tf.tfwtf": listen_tf}


# ------------------------------------------------------------------ the graph


def _cause(exc: BaseException) -> BaseException:
    while exc.__cause__ is not None:
        exc = exc.__cause__
    return exc


def _ping_failure(node: str, uri: str, exc: BaseException) -> str:
    """What rosnode's ping says on stderr when a node does not answer."""
    cause = _cause(exc)
    if isinstance(cause, TimeoutError):
        return f"connection to [{node}] timed out"
    if isinstance(cause, interfaces.UnknownHostError):
        return f"ERROR: Unknown host [{urlsplit(uri).hostname}] for node [{node}]"
    if isinstance(cause, ConnectionRefusedError) or getattr(cause, "errno", None) == errno.ECONNREFUSED:
        return f"ERROR: connection refused to [{uri}]"
    return f"connection to [{node}] failed"


def _unusable(exc: BaseException) -> str | None:
    """Why a node's advertised address is no good from here, when that is why it did not answer
    (a refusal or a time-out is as likely a node that died or hangs: the ping error says those)."""
    reason = unreachable_reason(exc)
    return reason if reason in (DOES_NOT_RESOLVE, NO_ROUTE) else None


def _pairs(value: object) -> list[tuple[str, str]]:
    if not isinstance(value, list):
        return []
    return [(str(row[0]), str(row[1])) for row in value if isinstance(row, list) and len(row) >= 2]


def _timed_ping(proxy: MasterProxy, who: str) -> _wtf.ClockReading | None:
    """getPid, and what its answer's Date says of the server's clock (None: it sent no Date)."""
    sent = time.time()
    proxy.call_raw("getPid")
    received = time.time()
    remote = parse_date(proxy.last_date or "")
    if remote is None:
        return None
    return _wtf.ClockReading(urlsplit(proxy.uri).hostname or proxy.uri, who, remote, sent, received)


def _ask_node(node: str, uri: str | None, uri_nodes: Mapping[str, str]) -> tuple[_wtf.NodeFacts, str | None]:
    """The node's facts and, when it did not answer, rosnode ping's complaint."""
    if uri is None:
        return _wtf.NodeFacts(None, reachable=False), f"cannot ping [{node}]: unknown node"
    proxy = MasterProxy(uri, ID, timeout=TIMEOUT)
    try:
        try:
            clock = _timed_ping(proxy, f"node {node}")
        except (OSError, XmlRpcError) as exc:
            return _wtf.NodeFacts(uri, reachable=False, unusable_address=_unusable(exc)), _ping_failure(node, uri, exc)
        try:
            result = proxy.call_raw("getBusInfo")
            bus: list[_wtf.Link] | None = None
            if isinstance(result, list) and len(result) == 3 and result[0] == 1:
                bus = _wtf.bus_links(node, result[2], uri_nodes)
            pubs = subs = None
            try:
                pubs = _pairs(proxy.call("getPublications"))
                subs = _pairs(proxy.call("getSubscriptions"))
            except MasterError:
                pass
            return _wtf.NodeFacts(uri, bus=bus, publications=pubs, subscriptions=subs, clock=clock), None
        except (OSError, XmlRpcError) as exc:
            return _wtf.NodeFacts(uri, error=str(_cause(exc)), clock=clock), None
    finally:
        proxy.close()


def _probe(master_uri: str, service: str) -> str | None:
    """Why the service does not answer a probe, in the real tool's words; None when it does."""
    master = MasterProxy(master_uri, ID, timeout=TIMEOUT)
    try:
        try:
            address = str(master.call("lookupService", service))
        except MasterError:
            return None  # gone since the snapshot: nothing to probe
        try:
            header = probe_service(master, ID, service, TIMEOUT)
        except MasterError:
            return None
        except OSError:
            return (f"appears to be malfunctioning: Unable to communicate with service [{service}], "
                    f"address [{address}]")
        except Exception:  # a handshake the service botched
            return "appears to be malfunctioning"
        return None if header else "did not return service headers"
    finally:
        master.close()


def _registrations(part: object) -> dict[str, list[str]]:
    if not isinstance(part, list):
        return {}
    return {str(row[0]): [str(n) for n in row[1]] for row in part}


def gather_graph(master_uri: str) -> tuple[_wtf.Graph, list[str]]:
    """The graph's snapshot and rosnode ping's complaints about the nodes that did not answer."""
    master = MasterProxy(master_uri, ID, timeout=TIMEOUT)
    try:
        master_clock = _timed_ping(master, "the master")
        try:
            use_sim_time = bool(master.call("getParam", "/use_sim_time"))
        except MasterError:
            use_sim_time = False
        state = master.call("getSystemState")
        pubs, subs, srvs = (_registrations(part) for part in state)
        names = _wtf.Graph(pubs, subs, srvs, {}).node_names
        uris: dict[str, str | None] = {}
        for node in names:
            try:
                uris[node] = str(master.call("lookupNode", node))
            except MasterError:
                uris[node] = None
    except (OSError, XmlRpcError) as exc:
        raise MasterLost from exc
    finally:
        master.close()
    uri_nodes = {uri: node for node, uri in uris.items() if uri}
    with ThreadPoolExecutor(max_workers=16) as pool:
        asked = {n: pool.submit(_ask_node, n, uris[n], uri_nodes) for n in names}
        probed = {s: pool.submit(_probe, master_uri, s) for s in sorted(srvs)}
        nodes = {n: f.result()[0] for n, f in asked.items()}
        complaints = [c for f in asked.values() if (c := f.result()[1])]
        failures = {s: why for s, f in probed.items() if (why := f.result())}
    return _wtf.Graph(pubs, subs, srvs, nodes, use_sim_time, failures, master_clock), complaints


def gather_launches(master_uri: str) -> list[tuple[Sequence[Sequence[object]], Sequence[Sequence[object]]]]:
    """Each roslaunch server's process lists, from the URIs under /roslaunch/uris."""
    master = MasterProxy(master_uri, ID, timeout=TIMEOUT)
    try:
        uris = master.call("getParam", "/roslaunch/uris")
    except (OSError, XmlRpcError, MasterError):
        return []
    finally:
        master.close()
    listings: list[tuple[Sequence[Sequence[object]], Sequence[Sequence[object]]]] = []
    for uri in (uris.values() if isinstance(uris, dict) else []):
        try:
            proxy = XmlRpcProxy(str(uri), timeout=TIMEOUT)
        except ValueError:
            continue
        try:
            answer = proxy.call("list_processes")
        except (OSError, XmlRpcError):
            continue  # an unreachable server: roswtf's rule for it is switched off
        finally:
            proxy.close()
        if not (isinstance(answer, list) and len(answer) == 3 and answer[0] == 1):
            continue
        value = answer[2]
        if isinstance(value, list) and len(value) == 2:
            running, dead = value
            if isinstance(running, list) and isinstance(dead, list):
                listings.append(([p for p in running if isinstance(p, list) and len(p) >= 2],
                                 [p for p in dead if isinstance(p, list) and len(p) >= 2]))
    return listings


def _master_offline(uri: str) -> BaseException | None:
    """None when the master answers, else what calling it raised."""
    try:
        proxy = MasterProxy(uri, ID, timeout=TIMEOUT)
    except ValueError as exc:
        return exc
    try:
        proxy.call("getPid")
        return None
    except (OSError, XmlRpcError, MasterError) as exc:
        return exc
    finally:
        proxy.close()


# ------------------------------------------------------------------ the command


def _load_launch_files(files: Sequence[str]) -> str | None:
    for name in files:
        try:
            ElementTree.parse(name)
        except OSError as exc:
            return f"Unable to load roslaunch file [{name}]: Invalid roslaunch XML syntax: {exc}"
        except ElementTree.ParseError as exc:
            return f"Unable to load roslaunch file [{name}]: Invalid roslaunch XML syntax: {exc}"
    return None


def _main(argv: list[str]) -> int:
    parser = OptionParser(usage=USAGE, description=DESCRIPTION, prog="roswtf")
    parser.add_argument("--all", dest="all_packages", default=False, action="store_true",
                      help="run roswtf against all packages")
    parser.add_argument("--no-plugins", dest="disable_plugins", default=False, action="store_true",
                      help="disable roswtf plugins")
    parser.add_argument("--offline", dest="offline", default=False, action="store_true",
                      help="only run offline tests")
    options = parser.parse_args(argv)
    args = options.args
    out = sys.stdout
    plugins = [] if options.disable_plugins else roswtf_plugins(os.environ)
    for plugin in plugins:
        print("Loaded plugin", plugin)
    if args:
        problem = _load_launch_files(args)
        if problem:
            print(problem, file=sys.stderr)
            return 0
    else:
        package = current_package(Path.cwd())
        print(f"Package: {package}" if package else "No package or stack in the current directory")
        if options.all_packages:
            print("roswtf will run against all packages")
    out.flush()

    variables = dict(os.environ)
    env = gather_environment(variables)
    report = _wtf.Report()
    _wtf.check_environment(env, report)
    _wtf.check_network(env, report)
    _wtf.check_packages(gather_packages(variables, Path.cwd(), options.all_packages), report)
    out.write(f"{_wtf.SEPARATOR}\nStatic checks summary:\n\n{_wtf.format_report(report)}{_wtf.SEPARATOR}\n")
    out.flush()

    uri = env.master_uri
    offline = None if options.offline or not uri or _wtf.invalid_url(uri) else _master_offline(uri)
    if options.offline or not uri or _wtf.invalid_url(uri) or offline is not None:
        print(f"\nROS Master does not appear to be running.\nOnline graph checks will not be run.\n"
              f"ROS_MASTER_URI is [{uri}]")
        reason = unreachable_reason(offline) if offline is not None else None
        if reason and (_wtf.master_is_remote(env) or reason == DOES_NOT_RESOLVE):
            # kame's addition: with the master on another machine, "not running" may be the network
            print(f"The master's machine cannot be reached from here: {reason}.")
        return 0
    print("Beginning tests of your ROS graph. These may take a while...")
    print("analyzing graph...", flush=True)
    online = _wtf.Report()
    try:
        graph, complaints = gather_graph(uri)
    except MasterLost:
        online.error(f"cannot contact ROS Master at {uri}", True)
        print(f"roswtf lost connection to the ROS Master at {uri}", file=sys.stderr)
        out.write(f"\nAborting checks, partial results summary:\n\n{_wtf.format_report(online)}")
        return 0
    print("... done analyzing graph")
    print("running graph rules...", flush=True)
    for complaint in complaints:
        print(complaint, file=sys.stderr)
    sys.stderr.flush()
    _wtf.check_graph(graph, online, _wtf.master_is_remote(env))
    print("... done running graph rules")
    _wtf.check_launches(gather_launches(uri), online)
    for plugin in plugins:
        ONLINE_PLUGINS[plugin](uri, online)
    out.write(f"\nOnline checks summary:\n\n{_wtf.format_report(online)}")
    return 0


def main(argv: Sequence[str] | None = None) -> int:
    return run(_main, argv)


if __name__ == "__main__":
    sys.exit(main())
