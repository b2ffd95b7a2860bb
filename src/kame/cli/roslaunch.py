"""roslaunch: run launch files, or print what they declare (--nodes, --args, --dump-params, ...).

    roslaunch [options] [package] <file.launch> [arg:=value ...]
    roslaunch [options] <file.launch> [<file.launch> ...] [arg:=value ...]

Options, output and exit statuses are the real roslaunch's (ros1-user-behaviour §12). The launch
is read into a model first (kame.launch.loader); any error is reported with its file and line
before anything starts. Then kame.launch.runner starts the master (and rosout) if none answers,
sets the parameters and starts the nodes under kame.launch.supervisor.
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import os
import random
import signal
import subprocess
import sys
import uuid
from collections.abc import Mapping, Sequence
from pathlib import Path

from kame import environ, names
from kame.catkin import executables
from kame.cli._options import OptionParser
from kame.cli.roscore import _disk_usage_check, _link_latest, _title
from kame.cli.rosmaster import setup_file_logging
from kame.launch import plan
from kame.launch.errors import LaunchError, PackageNotFound
from kame.launch.loader import ArgDecl, LaunchLoader, LoaderHost
from kame.launch.model import LaunchConfig, Node
from kame.launch.remote import CHILD_READY
from kame.launch.runner import LaunchRun, RunOptions, core_params, master_answers, ros_home_of, run_dir_of
from kame.launch.server import LaunchServer
from kame.launch.supervisor import say, say_bold, say_error
from kame.net import interfaces
from kame.net.address import host_addresses
from kame.node.master_proxy import MasterError, MasterProxy
from kame.node.remote_poll import poll_remote

LOGGER = "kame.launch"
log = logging.getLogger(LOGGER)


# ------------------------------------------------------------------ the loader's outside world


def anonymous_name(name: str) -> str:
    """rosgraph's anonymous_name: name_<host>_<pid>_<random>, made a legal ROS name."""
    text = f"{name}_{interfaces.hostname()}_{os.getpid()}_{random.randint(0, sys.maxsize)}"
    return text.replace(".", "_").replace("-", "_").replace(":", "_")


def run_command(argv: list[str]) -> tuple[int, str]:
    """A `<param command>`: a Python program named by its path (`$(find xacro)/xacro`) runs
    under this interpreter, as rosrun runs it, not whichever python3 its #! line finds."""
    if argv and os.sep in argv[0]:
        argv = [*executables.command_for(Path(argv[0])), *argv[1:]]
    done = subprocess.run(argv, stdout=subprocess.PIPE, check=False)
    return done.returncode, done.stdout.decode("utf-8", "replace")


def loader_host(env: Mapping[str, str]) -> LoaderHost:
    found = executables.packages(env)

    def find_package(name: str) -> str:
        package = found.get(name)
        if package is None:
            raise PackageNotFound("\n".join([name, *(f"ROS path [{i}]={p}"
                                                     for i, p in enumerate(executables.ros_paths(env)))]))
        return str(package.path)

    return LoaderHost(env, find_package, run_command, anonymous_name)


def load_config(files: Sequence[str], argv: Sequence[str], env: Mapping[str, str], *, strings: Sequence[str] = (),
                core: bool = True, verbose: bool = False, resolve_anon: bool = True,
                args_only: bool = False) -> tuple[LaunchConfig, LaunchLoader]:
    """roslaunch's load_config_default: the core (params; rosout) first, then each file."""
    config = LaunchConfig()
    loader = LaunchLoader(config, loader_host(env), verbose=verbose, resolve_anon=resolve_anon, args_only=args_only)
    if core:
        for param in core_params():
            config.add_param(param, verbose=verbose)
        config.add_node(Node("rosout", "rosout", "rosout", respawn=True), core=True, verbose=verbose)
    for f in files:
        loader.load(f, argv)
    for text in strings:
        loader.load_string(text, argv)
    return config, loader


# ------------------------------------------------------------------ command line


def _parser() -> argparse.ArgumentParser:
    p = OptionParser(
        prog="roslaunch", usage="roslaunch [options] [package] <filename> [arg_name:=value...]\n"
        "       roslaunch [options] <filename> [<filename>...] [arg_name:=value...]\n\n"
        "If <filename> is a single dash ('-'), launch XML is read from standard input.")
    add = p.add_argument
    add("--files", dest="file_list", action="store_true",
        help="Print list files loaded by launch file, including launch file itself")
    add("--args", dest="node_args", metavar="NODE_NAME", help="Print command-line arguments for node")
    add("--nodes", dest="node_list", action="store_true", help="Print list of node names in launch file")
    add("--find-node", dest="find_node", metavar="NODE_NAME", help="Find launch file that node is defined in")
    add("-c", "--child", dest="child_name", metavar="NAME", help="Run as child service 'NAME'. Required with -u")
    add("--local", dest="local_only", action="store_true", help="Do not launch remote nodes")
    add("--screen", dest="force_screen", action="store_true", help="Force output of all local nodes to screen")
    add("--required", dest="force_required", action="store_true", help="Force all nodes to be required")
    add("--log", dest="force_log", action="store_true", help="Force output of all local nodes to log")
    add("-u", "--server_uri", dest="server_uri", metavar="URI", help="URI of server. Required with -c")
    add("--run_id", dest="run_id", metavar="RUN_ID", help="run_id of session. Required with -c")
    add("--wait", dest="wait_for_master", action="store_true", help="wait for master to start before launching")
    add("-p", "--port", dest="port", type=int, metavar="PORT", help="master port. Only valid if master is launched")
    add("--core", action="store_true", help="Launch core services only")
    add("--pid", dest="pid_fn", default="", help="write the roslaunch pid to filename")
    add("-v", dest="verbose", action="store_true", help="verbose printing")
    add("--no-summary", dest="no_summary", action="store_true", help="hide summary printing")
    add("--dump-params", dest="dump_params", action="store_true",
        help="Dump parameters of all roslaunch files to stdout")
    add("--skip-log-check", dest="skip_log_check", action="store_true", help="skip check size of log folder")
    add("--ros-args", dest="ros_args", action="store_true",
        help="Display command-line arguments for this launch file")
    add("--disable-title", dest="disable_title", action="store_true", help="Disable setting of terminal title")
    add("-w", "--numworkers", dest="num_workers", type=int, default=3, metavar="NUM_WORKERS",
        help="override number of worker threads. Only valid for core services.")
    add("-t", "--timeout", dest="timeout", type=float, metavar="TIMEOUT",
        help="override the socket connection timeout (in seconds). Only valid for core services.")
    add("--master-logger-level", dest="master_logger_level",
        help="set rosmaster.master logger level ('debug', 'info', 'warn', 'error', 'fatal')")
    add("--sigint-timeout", dest="sigint_timeout", type=float, default=15.0, metavar="SIGINT_TIMEOUT",
        help="the SIGINT timeout used when killing nodes (in seconds).")
    add("--sigterm-timeout", dest="sigterm_timeout", type=float, default=2.0, metavar="SIGTERM_TIMEOUT",
        help="the SIGTERM timeout used when killing nodes if SIGINT does not stop the node (in seconds).")
    return p


def find_resource(package: str, filename: str, env: Mapping[str, str]) -> list[str]:
    """Files named `filename` anywhere below the package (roslib's find_resource)."""
    pkg = executables.packages(env).get(package)
    if pkg is None:
        return []
    hits = []
    for folder, dirnames, filenames in os.walk(pkg.path, followlinks=True):
        dirnames[:] = sorted(d for d in dirnames if not d.startswith("."))
        if filename in filenames:
            hits.append(os.path.join(folder, filename))
    return hits


def resolve_launch_arguments(args: Sequence[str], env: Mapping[str, str] | None = None) -> list[str]:
    """`pkg file.launch` or files, the `name:=value` arguments left out (roslaunch.rlutil's)."""
    env = os.environ if env is None else env
    plain = [a for a in args if ":=" not in a]
    if not plain:
        return plain
    if len(plain) >= 2:
        found = find_resource(plain[0], plain[1], env)
        if len(found) > 1:
            listed = "".join(f"\n- {r}" for r in found)
            raise LaunchError(f"multiple files named [{plain[1]}] in package [{plain[0]}]:{listed}\n"
                              "Please specify full path instead")
        if len(found) == 1:
            return [found[0], *plain[2:]]
    if plain[0] == "-" or os.path.isfile(plain[0]):
        return plain
    if len(plain) >= 2:
        raise LaunchError(f"[{plain[1]}] is neither a launch file in package [{plain[0]}] "
                          f"nor is [{plain[0]}] a launch file name")
    raise LaunchError(f"[{plain[0]}] is not a launch file name")


def get_or_generate_uuid(run_id: str | None, wait_for_master: bool, env: Mapping[str, str] | None = None) -> str:
    """The run_id: given, else the running master's /run_id, else a new uuid1."""
    if run_id:
        return run_id
    env = os.environ if env is None else env
    uri = environ.master_uri(env, default=environ.SETUP_MASTER_URI)

    def master_run_id() -> str | None:
        proxy = MasterProxy(uri, "/roslaunch", timeout=2.0)
        try:
            return str(proxy.call("getParam", "/run_id"))
        except (OSError, MasterError, ValueError):
            return None
        finally:
            proxy.close()

    if not wait_for_master:
        return master_run_id() or str(uuid.uuid1())
    found = poll_remote(master_run_id)  # Ctrl-C ends it
    assert found is not None  # poll_remote gives up only when stopped, and nothing stops this wait
    return found


def _arg_lines(decls: Sequence[ArgDecl]) -> list[str]:
    if not decls:
        return ["No arguments."]
    required = sorted((d.name, d.doc or "undocumented") for d in decls if not d.default)
    optional = sorted((d.name, d.default or "", d.doc or "undocumented") for d in decls if d.default)
    lines = []
    if required:
        lines += ["Required Arguments:", *(f"  {n}: {doc}" for n, doc in required)]
    if optional:
        lines += ["Optional Arguments:", *(f'  {n} (default "{dflt}"): {doc}' for n, dflt, doc in optional)]
    return lines


def _print_info(options: argparse.Namespace, files: list[str], argv: list[str]) -> int:
    env = os.environ
    try:
        if options.dump_params:
            try:
                config, _ = load_config(files, argv, env, core=False)
            except LaunchError as exc:
                sys.stderr.write(f"Unable to load file {files[-1] if files else ''}: {exc.describe()}")
                return 1
            sys.stdout.write(plan.dump_params(config))
            return 0
        if options.ros_args:
            _, loader = load_config(files, argv, env, resolve_anon=False, args_only=True)
            print("\n".join(_arg_lines(loader.arg_decls)))
            return 0
        if options.file_list:
            config, _ = load_config(files, argv, env)
            print("\n".join(os.path.abspath(f) for f in dict.fromkeys(config.files)))
            return 0
        config, _ = load_config(files, argv, env, resolve_anon=options.node_args is not None)
        if options.node_list:
            print("\n".join(plan.node_list(config)))
            return 0
        wanted = names.canonicalize(names.ns_join(names.make_global_ns(env.get("ROS_NAMESPACE", "/") or "/"),
                                                  options.find_node or options.node_args))
        nodes = [n for n in (*config.nodes, *config.tests) if n.resolved_name == wanted]
        if len(nodes) > 1:
            raise LaunchError(f"ERROR: multiple nodes named [{wanted}] in [{', '.join(files)}].\n"
                              "Please fix the launch files as duplicate names are not allowed.")
        if options.find_node:
            if not nodes:
                print(f"ERROR: cannot find node named [{wanted}]. Run \n\troslaunch --nodes <files>\n"
                      "to see list of node names.", file=sys.stderr)
                return 0
            print(nodes[0].filename)
            return 0
        if not nodes:
            listed = "\n".join(f" * {n}" for n in plan.node_list(config))
            raise LaunchError(f"ERROR: Cannot find node named [{wanted}] in [{', '.join(files)}].\n"
                              f"Node names are:\n{listed}")
        run = LaunchRun(config, _run_options(options, "", env))
        print(plan.args_line(nodes[0], run.program(nodes[0]), env, run.options.master_uri))
        return 0
    except LaunchError as exc:
        print(exc.describe(), file=sys.stderr)
        return 1


def _run_options(options: argparse.Namespace, run_id: str, env: Mapping[str, str], title: str | None = None
                 ) -> RunOptions:
    uri = environ.master_uri(env, default=environ.SETUP_MASTER_URI)
    if options.port:
        uri = f"http://localhost:{options.port}/"
    elif options.core:
        uri = "http://localhost:11311/"
    return RunOptions(run_id=run_id, master_uri=uri, run_dir=run_dir_of(env, run_id), ros_home=ros_home_of(env),
                      env=dict(env), port=options.port, force_screen=options.force_screen,
                      force_log=options.force_log, force_required=options.force_required,
                      local_only=options.local_only, sigint_timeout=options.sigint_timeout,
                      sigterm_timeout=options.sigterm_timeout, num_workers=options.num_workers,
                      master_timeout=options.timeout, master_logger_level=options.master_logger_level or None,
                      is_core=options.core, title=title)


def _fail(text: str) -> int:
    say_error(f"RLException: {text}")
    say_error("The traceback for the exception was written to the log file")
    if log.hasHandlers():  # before the log file is set up, logging's last resort would print it again
        log.error("%s", text)
    return 1


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = _parser()
    options, rest = parser.parse_known_args(argv)
    unknown = [a for a in rest if a.startswith("-") and a != "-"]
    if unknown:
        parser.error(f"no such option: {unknown[0]}")
    positional = [*options.args, *rest]
    if options.sigint_timeout <= 0:
        return _fail(f"sigint_timeout must be a positive number, received {options.sigint_timeout:f}")
    if options.sigterm_timeout <= 0:
        return _fail(f"sigterm_timeout must be a positive number, received {options.sigterm_timeout:f}")
    if options.child_name:
        if not options.run_id:
            parser.error("--child option requires --run_id to be set as well")
        return _child(options)
    try:
        files = resolve_launch_arguments(positional)
    except LaunchError as exc:
        return _fail(str(exc))
    if options.core:
        if files:
            parser.error("Input files are not allowed when launching core")
    elif not files:
        parser.error("you must specify at least one input file")
    missing = [f for f in files if not (f == "-" or os.path.exists(f))]
    if missing:
        parser.error(f"The following input files do not exist: {', '.join(missing)}")
    if files.count("-") > 1:
        parser.error("Only a single instance of the dash ('-') may be specified.")
    if sum(bool(x) for x in (options.node_list, options.find_node, options.node_args, options.ros_args)) > 1:
        parser.error("only one of [--nodes, --find-node, --args --ros-args] may be specified")
    if any((options.node_args, options.node_list, options.find_node, options.dump_params, options.file_list,
            options.ros_args)):
        return _print_info(options, files, argv)
    return _launch(options, files, argv)


def _launch(options: argparse.Namespace, files: list[str], argv: list[str]) -> int:
    env = os.environ
    if options.wait_for_master:
        if options.core:
            print("usage: roslaunch [options]\nroslaunch: error: --wait cannot be used with roscore", file=sys.stderr)
            return 2
        uri = environ.master_uri(env, default=environ.SETUP_MASTER_URI)
        if not master_answers(uri):
            say("roscore/master is not yet running, will wait for it to start")
            poll_remote(lambda: master_answers(uri) or None)  # Ctrl-C ends it
        say("master has started, initiating launch")
    if options.pid_fn:
        Path(options.pid_fn).write_text(f"{os.getpid()}")
    run_id = get_or_generate_uuid(options.run_id, options.wait_for_master)
    run_dir = run_dir_of(env, run_id)
    own_log = run_dir / f"roslaunch-{interfaces.hostname()}-{os.getpid()}.log"
    handler = setup_file_logging(own_log, LOGGER)
    try:
        say(f"... logging to {own_log}")
        if not options.skip_log_check:
            _disk_usage_check(run_dir.parent)
        title = "roscore" if options.core else " ".join(files)
        if not options.disable_title:
            print(_title(title), flush=True)
        strings = []
        if "-" in files:
            say("Passed '-' as file argument, attempting to read roslaunch XML from stdin.")
            strings.append(sys.stdin.read())
            say(f"... {len(strings[-1])} bytes read successfully.\n")
            files = [f for f in files if f != "-"]
        try:
            config, _ = load_config(files, argv, env, strings=strings, verbose=options.verbose)
            run = LaunchRun(config, _run_options(options, run_id, env, None if options.disable_title else title),
                            run_command=lambda args: subprocess.run(
                                [sys.executable, "-m", "kame.cli.rosparam", *args[1:]], check=False).returncode)
            run.check()
        except LaunchError as exc:
            return _fail(exc.describe())
        host = host_addresses(env)
        run.server = server = LaunchServer(host.bind, host.advertised, run.process_states)
        server.start()
        say_bold(f"started roslaunch server {server.uri}")
        for line in config.messages:
            say(line)
        if options.core:
            say(f"ros_comm version {config.params['/rosversion'].value.strip()}")
        if not options.no_summary:
            say(plan.summary(config, local=not run.remote_nodes(), is_local=run.is_local))
        for err in config.errors:
            say_error(f"WARNING: {err}")
        _link_latest(run_dir.parent, run_dir)
        try:
            status = asyncio.run(_run(run))
        finally:
            run.withdraw_server()
            server.close()
        if status == 0:
            say_bold("done")
        return status
    finally:
        handler.close()
        if options.pid_fn:
            Path(options.pid_fn).unlink(missing_ok=True)


def _read_line(fd: int) -> bytes:
    """One line from `fd`, read unbuffered: what follows it (its end) is watched on the fd itself."""
    data = b""
    while not data.endswith(b"\n"):
        chunk = os.read(fd, 1 if data else 65536)
        if not chunk:
            break
        data += chunk
    return data


def _child(options: argparse.Namespace) -> int:
    """`roslaunch -c NAME --run_id ID`: a remote machine's share of a launch (kame.launch.remote).

    The nodes come as one line of JSON on stdin; `ready` goes back on stdout; the end of stdin
    (the parent stopping, or its connection lost) stops them. Python nodes' output is unbuffered:
    their stdout is the SSH channel, read by a person at the parent's terminal."""
    env = dict(os.environ)
    env.setdefault("PYTHONUNBUFFERED", "1")
    try:
        nodes = plan.nodes_from_json(_read_line(sys.stdin.fileno()).decode("utf-8", "replace"))
    except LaunchError as exc:
        return _fail(str(exc))
    run_dir = run_dir_of(env, options.run_id)
    handler = setup_file_logging(run_dir / f"roslaunch-{interfaces.hostname()}-{os.getpid()}.log", LOGGER)
    try:
        run = LaunchRun(LaunchConfig(nodes=nodes), _run_options(options, options.run_id, env))
        return asyncio.run(_run_child(run))
    finally:
        handler.close()


async def _run_child(run: LaunchRun) -> int:
    loop = asyncio.get_running_loop()
    stdin = sys.stdin.fileno()

    def readable() -> None:
        if not os.read(stdin, 4096):  # the parent is done with us
            loop.remove_reader(stdin)
            run.monitor.done.set()

    loop.add_reader(stdin, readable)
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, run.monitor.done.set)
    try:
        say(CHILD_READY)
        await run.launch_nodes()
        await run.spin()
        return 0
    except BaseException:
        await run.monitor.shutdown()  # whatever went wrong, no node is left behind
        raise
    finally:
        loop.remove_reader(stdin)
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.remove_signal_handler(sig)


async def _run(run: LaunchRun) -> int:
    loop = asyncio.get_running_loop()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, run.monitor.done.set)
    try:
        try:
            await run.setup()
            if not run.options.is_core:
                await run.launch_nodes()
        except LaunchError as exc:
            await run.monitor.shutdown()
            return _fail(exc.describe())
        await run.spin()
        return 0
    except BaseException:
        await run.monitor.shutdown()  # whatever went wrong, no child is left behind
        raise
    finally:
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.remove_signal_handler(sig)


if __name__ == "__main__":
    sys.exit(main())
