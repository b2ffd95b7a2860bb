"""roscore: the master, the parameter server and the core parameters, with roscore's output.

What the user sees follows ros1-user-behaviour §1: the banner (SUMMARY / PARAMETERS / NODES),
ROS_MASTER_URI, `setting /run_id to ...`, the refusal when a master already answers on the port,
and the Ctrl-C lines. Logs go to <log dir>/<run_id>/ (master.log, roslaunch-<host>-<pid>.log)
with <log dir>/latest pointing there; ROS_HOME/roscore-<port>.pid holds our PID while we run.

The master runs in this process, so `process[master]` reports our own PID. The rosout node runs
as a child process (`python -m kame.cli.rosout`), respawned when it dies, its stdout in
<run dir>/rosout-1-stdout.log, and stopped before the master on Ctrl-C (see `start_core_nodes`).
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import os
import sys
import uuid
from collections.abc import Sequence
from pathlib import Path
from urllib.parse import urlsplit

from kame.cli.rosmaster import DEFAULT_PORT, flush_periodically, log_dir, ros_home, serve, setup_file_logging
from kame.launch.server import LaunchServer, ProcessState
from kame.master.server import NOTIFY_TIMEOUT, MasterServer
from kame.net import interfaces, peers
from kame.net.address import host_addresses, uri_host
from kame.net.process import SupervisedProcess
from kame.net.xmlrpc_client import XmlRpcProxy
from kame.protocol.xmlrpc import XmlRpcError

ROS_VERSION = "1.15.15"
ROS_DISTRO = "noetic"
BOLD, RED, RESET = "\033[1m", "\033[31m", "\033[0m"
LOGGER = "kame.cli.roscore"  # not __name__, which is __main__ under python -m
log = logging.getLogger(LOGGER)


def _title(text: str) -> str:
    """The terminal-title escape; roslaunch print()s it, so a newline follows it on the output."""
    return f"\033]2;{text}\007"


def _bold(text: str) -> None:
    print(f"{BOLD}{text}{RESET}", flush=True)


def _running_master(uri: str) -> XmlRpcProxy | None:
    """A proxy to the master answering at `uri` (each call bounded by 2 s), or None if nothing
    answers."""
    proxy = XmlRpcProxy(uri, timeout=2.0)
    try:
        proxy.call("getPid", "/roscore")
    except (OSError, XmlRpcError):
        proxy.close()
        return None
    return proxy


def _disk_usage_check(directory: Path) -> None:
    print("Checking log directory for disk usage. This may take a while.\nPress Ctrl-C to interrupt", flush=True)
    total = 0
    for root, _dirs, files in os.walk(directory):
        for f in files:
            try:
                total += os.lstat(os.path.join(root, f)).st_size
            except OSError:
                continue
    if total > 1024**3:
        print(f"WARNING: disk usage in log directory [{directory}] is over 1GB.\n"
              "It's recommended that you use the 'rosclean' command.", file=sys.stderr, flush=True)
    else:
        print("Done checking log file disk usage. Usage is <1GB.", flush=True)


def _summary(server_uri: str) -> None:
    print(_title("roscore"), flush=True)
    _bold(f"started roslaunch server {server_uri}")
    print(f"ros_comm version {ROS_VERSION}\n\n")
    print("SUMMARY\n========\n")
    print(f"PARAMETERS\n * /rosdistro: {ROS_DISTRO}\n * /rosversion: {ROS_VERSION}\n")
    print("NODES\n", flush=True)


def _link_latest(logs: Path, run_dir: Path) -> None:
    latest = logs / "latest"
    try:
        if latest.is_symlink() or latest.exists():
            latest.unlink()
        latest.symlink_to(run_dir, target_is_directory=True)
    except OSError:
        pass  # a read-only or odd log dir must not stop the core; ROS ignores this too


ROSOUT = "rosout-1"  # roslaunch's process name: the node's name and its launch counter


async def start_core_nodes(server: MasterServer, uri: str, run_dir: Path) -> list[SupervisedProcess]:
    """The single place where roscore's core nodes start; returns them for `stop_core_nodes`.

    roscore's only core node is rosout (`rosout __name:=rosout __log:=<run_dir>/rosout-1.log`,
    respawned when it dies), as roscore.xml declares it.
    """

    def started(pid: int, restarted: bool) -> None:
        if restarted:
            print(f"[{ROSOUT}] restarting process", flush=True)
        _bold(f"process[{ROSOUT}]: started with pid [{pid}]")

    def died(pid: int, code: int) -> None:
        log.warning("%s (pid %d) died with exit code %d; respawning", ROSOUT, pid, code)

    env = {**os.environ, "ROS_MASTER_URI": uri}
    rosout = SupervisedProcess(
        ROSOUT, [sys.executable, "-m", "kame.cli.rosout", "__name:=rosout", f"__log:={run_dir / (ROSOUT + '.log')}"],
        env=env, stdout=run_dir / f"{ROSOUT}-stdout.log", respawn=True, on_start=started, on_exit=died)
    try:
        await rosout.start()
    except OSError as exc:
        print(f"{RED}ERROR: cannot launch node of type [rosout/rosout]: {exc}{RESET}", file=sys.stderr, flush=True)
        log.error("cannot start rosout: %s", exc)
        return []
    print("started core service [/rosout]", flush=True)
    return [rosout]


async def stop_core_nodes(nodes: list[SupervisedProcess]) -> None:
    """SIGINT to each, SIGKILL to any still there after 1 s: all within roscore's 2 s budget."""
    for node in nodes:
        print(f"[{node.name}] killing on exit", flush=True)
    await asyncio.gather(*(node.stop(timeout=1.0) for node in nodes))


def main(argv: Sequence[str] | None = None) -> int:
    parser = argparse.ArgumentParser(prog="roscore", usage="roscore [options]")
    parser.add_argument("-p", "--port", type=int, default=DEFAULT_PORT, help="master port")
    parser.add_argument("-v", action="store_true", dest="verbose", help="verbose printing")
    parser.add_argument("-w", "--numworkers", type=int, default=3, metavar="NUM_WORKERS",
                        help="accepted for compatibility (notifications are concurrent per node)")
    parser.add_argument("-t", "--timeout", type=float, default=NOTIFY_TIMEOUT, metavar="TIMEOUT",
                        help="timeout of each notification to a node, in seconds")
    parser.add_argument("--allowed-peers", metavar="PEERS", default=None,
                        help="only these addresses, networks (10.0.0.0/24) and host names, and this machine, may "
                             "connect to the master and to the nodes started here (sets KAME_ALLOWED_PEERS)")
    options = parser.parse_args(sys.argv[1:] if argv is None else argv)
    try:
        peers.setup(options.allowed_peers)
    except ValueError as exc:
        parser.error(str(exc))
    env = os.environ
    port = options.port
    local_uri = f"http://localhost:{port}/"
    # what roslaunch calls the master in its refusal: the advertised host (ROS_HOSTNAME, ROS_IP or hostname)
    host = host_addresses(env)
    named_uri = f"http://{uri_host(host.advertised)}:{port}/"

    existing = _running_master(local_uri)
    run_id = str(uuid.uuid1())
    if existing is not None:
        try:
            answer = existing.call("getParam", "/roscore", "/run_id")
        except (OSError, XmlRpcError):
            answer = None
        finally:
            existing.close()
        if isinstance(answer, list) and len(answer) == 3 and answer[0] == 1 and isinstance(answer[2], str):
            run_id = answer[2]  # a second roscore logs under the running master's run_id
    logs = log_dir(env)
    run_dir = logs / run_id
    own_log = run_dir / f"roslaunch-{interfaces.hostname()}-{os.getpid()}.log"
    handler = setup_file_logging(own_log, LOGGER)
    print(f"... logging to {own_log}", flush=True)
    _disk_usage_check(logs)
    core_nodes: list[SupervisedProcess] = []

    def processes() -> list[ProcessState]:  # the master runs in this process: it is the first
        return [ProcessState("master", 1, True),
                *(ProcessState(p.name, p.starts, p.running, args=p.args, respawn=p.respawn) for p in core_nodes)]

    launch_server = LaunchServer(host.bind, host.advertised, processes)
    launch_server.start()
    _summary(launch_server.uri)

    if existing is not None:
        print(f"{RED}RLException: roscore cannot run as another roscore/master is already running. \n"
              f"Please kill other roscore/master processes before relaunching.\n"
              f"The ROS_MASTER_URI is {named_uri}{RESET}\n"
              f"{RED}The traceback for the exception was written to the log file{RESET}",
              file=sys.stderr, flush=True)
        log.error("another master is running at %s", local_uri)
        launch_server.close()
        handler.close()
        return 1

    master_port = urlsplit(env.get("ROS_MASTER_URI", "")).port
    if master_port is not None and master_port != port:
        print(f"WARNING: ROS_MASTER_URI port [{master_port}] does not match this roscore [{port}]",
              file=sys.stderr, flush=True)
    if options.verbose:
        console = logging.StreamHandler(sys.stdout)
        console.setFormatter(logging.Formatter("%(message)s"))
        logging.getLogger("kame").addHandler(console)

    master_log = setup_file_logging(run_dir / "master.log")
    pid_file = ros_home(env) / f"roscore-{port}.pid"

    async def on_started(server: MasterServer, uri: str) -> None:
        print("auto-starting new master", flush=True)
        _bold(f"process[master]: started with pid [{os.getpid()}]")
        _bold(f"ROS_MASTER_URI={uri}")
        print(_title(f"roscore {uri}"), flush=True)
        assert server.api is not None
        api = server.api
        if not api.params.has("/run_id"):
            _bold(f"setting /run_id to {run_id}")
            api.call("setParam", ["/roslaunch", "/run_id", run_id])
        # as the output of `rosversion -d` / `rosversion roslaunch`, with their newline
        api.call("setParam", ["/roslaunch", "/rosversion", ROS_VERSION + "\n"])
        api.call("setParam", ["/roslaunch", "/rosdistro", ROS_DISTRO + "\n"])
        api.call("setParam", ["/roslaunch", launch_server.param, launch_server.uri])
        _link_latest(logs, run_dir)
        pid_file.parent.mkdir(parents=True, exist_ok=True)
        pid_file.write_text(f"{os.getpid()}\n")
        log.info("master at %s, run_id %s, pid file %s", uri, run_id, pid_file)
        core_nodes.extend(await start_core_nodes(server, uri, run_dir))

    async def on_stopping() -> None:
        await stop_core_nodes(core_nodes)

    async def run() -> int:
        flushers = [asyncio.ensure_future(flush_periodically(h)) for h in (handler, master_log)]
        try:
            return await serve(port, options.timeout, on_started, on_stopping)
        finally:
            for f in flushers:
                f.cancel()

    try:
        status = asyncio.run(run())
    finally:
        launch_server.close()
        pid_file.unlink(missing_ok=True)
        handler.close()
        master_log.close()
    if status == 0:
        print("[master] killing on exit\nshutting down processing monitor...\n"
              "... shutting down processing monitor complete", flush=True)
        _bold("done")
    return status


if __name__ == "__main__":
    sys.exit(main())
