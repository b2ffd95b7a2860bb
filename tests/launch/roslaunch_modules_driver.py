"""Runs roslaunch's modules on fixed inputs and prints what they answer as JSON, under Debian's
interpreter (real roslaunch) or kame's: tests/launch/test_roslaunch_modules.py compares the two.

`python roslaunch_modules_driver.py SECTION LAUNCH_FILE` prints one JSON object for SECTION.
"""

from __future__ import annotations

import io
import json
import os
import re
import sys
import threading
import time
import traceback
from collections.abc import Callable
from contextlib import redirect_stderr, redirect_stdout
from typing import Any
from xml.dom.minidom import parseString

import roslaunch
import roslaunch.arg_dump
import roslaunch.config
import roslaunch.core
import roslaunch.depends
import roslaunch.loader
import roslaunch.node_args
import roslaunch.nodeprocess
import roslaunch.param_dump
import roslaunch.pmon
import roslaunch.rlutil
import roslaunch.substitution_args
import roslaunch.xmlloader
from roslaunch.core import Machine, Node, Test


def outcome(fn: Callable[[], Any]) -> Any:
    """What fn() returns, or [exception type name, message]."""
    try:
        return fn()
    except Exception as exc:  # kame's RLException is its launch error class under another name
        return ["RLException" if type(exc) is roslaunch.core.RLException else type(exc).__name__, str(exc)]


def without_ros_paths(text: str | None) -> list[str]:
    """The lines of `text` but the ROS paths a not-found package lists (each installation's own)."""
    return [line for line in (text or "").splitlines() if not line.startswith("ROS path [")]


def core_section(_: str) -> dict[str, Any]:
    bad_nodes = {
        "empty package": lambda: Node("", "t"),
        "blank type": lambda: Node("p", "  "),
        "namespaced name": lambda: Node("p", "t", name="a/b"),
        "respawn and required": lambda: Node("p", "t", respawn=True, required=True),
        "bad output": lambda: Node("p", "t", output="file"),
        "bad cwd": lambda: Node("p", "t", cwd="here"),
        "zero time limit": lambda: Test("tn", "p", "t", time_limit=-1),
        "text time limit": lambda: Test("tn", "p", "t", time_limit="5"),
    }
    remaps = [["a", "b"], ["c", "d"]]
    node = Node("pkg", "type", name="n", namespace="ns//sub", machine_name="m", args='x "y"', respawn=True,
                respawn_delay=2.5, remap_args=remaps, env_args=[("E", "v&<>")], output="screen", cwd="ros_home",
                launch_prefix="nice")
    test = Test("tname", "pkg", "type", name="tn", time_limit=30, retry=2, cwd="node")
    m1 = Machine("a", "host1", env_loader="/e.sh", user="u", timeout=3)
    m2 = Machine("b", "host1", env_loader="/e.sh", user="u", timeout=3)
    master = roslaunch.core.Master(uri="http://example.invalid:1234/")
    handled: list[Any] = []
    roslaunch.core.add_printlog_handler(lambda m: handled.append(["log", m]))
    roslaunch.core.add_printerrlog_handler(lambda m: handled.append(["err", m]))
    roslaunch.core.add_printlog_handler(lambda m: 1 / 0)
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        roslaunch.core.printlog("plain")
        roslaunch.core.printlog_bold("bold")
        roslaunch.core.printerrlog("error")
    roslaunch.core.clear_printlog_handlers()
    roslaunch.core.clear_printerrlog_handlers()
    with redirect_stdout(io.StringIO()):
        roslaunch.core.printlog("after clearing")
    was_child = roslaunch.core.is_child_mode()
    roslaunch.core.set_child_mode(True)
    run_id = roslaunch.core.generate_run_id()
    env = roslaunch.core.setup_env(node, m1, "http://m:1/", env={"ROS_NAMESPACE": "/old", "KEEP": "k"})
    return {
        "bad nodes": {k: outcome(v) for k, v in bad_nodes.items()},
        "node": [node.cwd, node.namespace, node.remap_args is remaps, node.xmltype(), node.xmlattrs(), node.to_xml(),
                 node.to_remote_xml(), node.process_name, node.machine],
        "test": [test.xmltype(), test.xmlattrs(), test.to_xml(), test.time_limit, test.output],
        "bare node": [Node("p", "t").to_xml(), Node("p", "t", name="").name, Node("p", "t", namespace="").namespace],
        "machines": [str(m1), m1.config_key(), m1.config_equals(m2), m1 == m2, Machine("x", "h").timeout,
                     Machine("x", "h", user="").user],
        "local machine": [str(roslaunch.core.local_machine()),
                          roslaunch.core.local_machine() is roslaunch.core.local_machine()],
        "master": [type(master.get()).__name__, type(master.get_multi()).__name__, master.get_host(),
                   master.get_port(), master.type, master.auto],
        "executables": [str(roslaunch.core.Executable("cmd", ("a", "b"))),
                        repr(roslaunch.core.RosbinExecutable("rosparam", ("dump", "f"), roslaunch.core.PHASE_SETUP)),
                        roslaunch.core.Executable("c", ()).phase, roslaunch.core.PHASE_SETUP,
                        roslaunch.core.PHASE_TEARDOWN, roslaunch.core.TEST_TIME_LIMIT_DEFAULT],
        "printlog": [handled, out.getvalue(), err.getvalue()],
        "child mode": [was_child, roslaunch.core.is_child_mode()],
        "run id": [len(run_id), run_id.count("-")],
        "env": env,
        "rle_wrapper": outcome(lambda: roslaunch.core.rle_wrapper(lambda: int("x"))()),
        "param": [str(roslaunch.core.Param("a//b", 1)), roslaunch.core.Param("x", 1) == roslaunch.core.Param("/x", 1)],
    }


def base64_value(value: Any) -> bytes:
    """A binfile's value: ROS's loader gives an xmlrpc.client.Binary, kame's the bytes it sends as base64."""
    return value if isinstance(value, bytes) else value.data


class Config:
    """A stand-in ROSLaunchConfig recording what a Loader adds."""

    def __init__(self) -> None:
        self.added: list[Any] = []

    def add_param(self, p: Any, filename: Any = None, verbose: bool = True) -> None:
        self.added.append(["param", p.key, p.value])

    def add_executable(self, e: Any) -> None:
        self.added.append(["exe", str(e), e.phase, type(e).__name__])


def loader_section(launch: str) -> dict[str, Any]:
    L = roslaunch.loader
    values = {text: {t: outcome(lambda text=text, t=t: L.convert_value(text, t))
                     for t in ("auto", "int", "double", "bool", "str", "yaml", "nope")}
              for text in ("1", "1.5", "010", "true", " 0 ", "1_0", "[1, 2]", "x")}
    ctx = L.LoaderContext("ns", "f.launch")
    ctx.add_remap(("a", "b"))
    ctx.add_remap(("a", "c"))
    child = ctx.child("sub")
    child.add_remap(("d", "/e"))
    bad_remaps = [outcome(lambda r=r: ctx.add_remap(r)) for r in (("", "x"), ("1a", "x"), ("x", "a b"))]
    ctx.add_arg("one", default="d1")
    ctx.add_arg("two", value="v2")
    arg_errors = [outcome(lambda: ctx.add_arg("one")), outcome(lambda: ctx.add_arg("three", value="x") or
                                                               ctx.add_arg("three2", value="y"))]
    ctx.resolve_dict["arg"]["four"] = "x"
    override = outcome(lambda: L.LoaderContext("/", "f").add_arg("a", value="1") or None)
    inc = ctx.include_child("inc", "inner.launch")
    inc.add_arg("passed", value="p")
    inc_declared = inc.arg_names[:]
    L.process_include_args(inc)
    post = outcome(lambda: L.post_process_include_args(inc))
    inc2 = ctx.include_child(None, "x.launch")
    inc2.arg_names = ["needed"]
    missing = outcome(lambda: L.process_include_args(inc2))
    L.load_sysargs_into_context(ctx, ["prog", "a:=1", "_p:=2", "__ns:=x", "b:=c"])
    config = Config()
    loader = L.Loader()
    loader.add_param(config, "/top", {"a": 1, "b": {"c": "x"}})
    loader.add_param(config, "/leaf", [1, 2])
    add_errors = [outcome(lambda: loader.add_param(config, "", 1)), outcome(lambda: loader.add_param(config, "/", 1))]
    rosparam_ctx = L.LoaderContext("/r", launch)
    loader.load_rosparam(rosparam_ctx, config, "load", "p", None, "{x: 1, y: [1, 2]}")
    loader.load_rosparam(rosparam_ctx, config, "load", None, None, "z: 2")
    loader.load_rosparam(rosparam_ctx, config, "dump", "q", "out.yaml", "")
    loader.load_rosparam(rosparam_ctx, config, "delete", "q", None, "")
    loader.load_rosparam(rosparam_ctx, config, "load", "s", None, "$(arg x)", subst_function=lambda t: t.upper())
    rosparam_errors = [outcome(lambda c=c: loader.load_rosparam(rosparam_ctx, config, *c)) for c in
                       (("bad", None, None, ""), ("delete", "q", "f.yaml", ""), ("load", "p", "/no/such.yaml", ""),
                        ("load", None, None, "[1, 2]"), ("load", "p", None, "{a: [1"))]
    loader.load_env(rosparam_ctx, config, "N", "v")
    env_error = outcome(lambda: loader.load_env(rosparam_ctx, config, "", "v"))
    pvalues = [outcome(lambda: loader.param_value(False, "n", "auto", " 5 ", None, None, None)),
               outcome(lambda: loader.param_value(False, "n", "str", None, launch, None, None)[:8]),
               outcome(lambda: base64_value(loader.param_value(False, "n", "auto", None, None, launch, None))),
               outcome(lambda: loader.param_value(False, "n", "int", None, None, None, "echo 42")),
               outcome(lambda: loader.param_value(False, "n", "auto", None, None, None, "false")),
               outcome(lambda: loader.param_value(False, "n", "auto", None, None, None, None))]
    return {"values": values, "remaps": [ctx.remap_args(), child.remap_args(), child.ns, ctx.child("/abs").ns,
                                         outcome(lambda: ctx.child("~").ns), ctx.child(None).ns, bad_remaps],
            "args": [ctx.arg_names, ctx.resolve_dict, arg_errors, override, inc_declared, inc.args_passed, post,
                     missing, inc.resolve_dict],
            "added": config.added, "add errors": add_errors, "rosparam errors": rosparam_errors,
            "env": [rosparam_ctx.env_args, env_error], "param values": pvalues, "rosparam": L.rosparam is None}


def substitution_section(launch: str) -> dict[str, Any]:
    resolve = roslaunch.substitution_args.resolve_args
    context: dict[str, Any] = {"arg": {"a": "1", "b": "x"}, "filename": launch}
    anon1 = resolve("$(anon foo)", context=context)
    anon2 = resolve("$(anon foo)", context=context)
    cases = ["$(env HOME)", "$(optenv NO_SUCH_VAR dflt val)", "$(optenv NO_SUCH_VAR)", "$(arg a)-$(arg b)",
             "$(find rl_pkg)/launch", "$(dirname)", "$(eval arg('a') + 1)", "$(eval b + 'y')",
             "$(eval 2 * pi > 6)", "plain", "", None, "$(arg missing)", "$(env NO_SUCH_VAR)", "$(find no_such_pkg)",
             "$(bogus x)", "$(env)", "$(anon)", "$(arg a b)", "$(eval __import__('os'))", "$($(arg a))"]
    results = [outcome(lambda c=c: resolve(c, context={"arg": {"a": "1", "b": "x"}, "filename": launch}))
               for c in cases]
    # the ROS paths a not-found package lists after its name are each installation's own
    results = [[r[0], without_ros_paths(r[1])] if isinstance(r, list) and r[0] == "ResourceNotFound" else r
               for r in results]
    return {"cases": results,
            "anon": [anon1 == anon2, anon1.startswith("foo_"), sorted(context["anon"])],
            "unresolved anon": resolve("$(anon foo) $(arg a)", context={"arg": {"a": "1"}},
                                       resolve_anon=False).startswith("foo_"),
            "types": [issubclass(roslaunch.substitution_args.ArgException,
                                 roslaunch.substitution_args.SubstitutionException)]}


def files_section(launch: str) -> dict[str, Any]:
    out = io.StringIO()
    with redirect_stdout(out):
        dumped = roslaunch.param_dump.dump_params([launch])
    loader = roslaunch.xmlloader.XmlLoader(resolve_anon=False)
    config = roslaunch.config.load_config_default([launch], None, loader=loader, verbose=False,
                                                  assign_machines=False)
    node = next(n for n in config.nodes if n.name == "first")
    node.machine = roslaunch.core.local_machine()
    base, file_deps, missing = roslaunch.depends.roslaunch_deps([launch])
    xml = roslaunch.xmlloader.XmlLoader()
    xml_config = roslaunch.config.ROSLaunchConfig()
    xml.load(launch, xml_config, argv=["who:=me", "__ns:=/space"])
    return {
        "dump_params": [dumped, out.getvalue()],
        "args": {k: list(v) for k, v in roslaunch.arg_dump.get_args([launch]).items()},
        "node list": roslaunch.node_args.get_node_list(config),
        "process args": outcome(lambda: roslaunch.node_args.create_local_process_args(node, node.machine)),
        "node args": outcome(lambda: roslaunch.node_args.get_node_args("/g/second", [launch])),
        "node args missing": outcome(lambda: roslaunch.node_args.get_node_args("/nope", [launch])),
        "missing program": outcome(lambda: roslaunch.node_args.create_local_process_args(
            next(n for n in config.nodes if n.name == "ghost"), node.machine)),
        "depends": [base, {os.path.basename(k): [sorted(v.nodes), sorted(v.includes), sorted(v.pkgs)]
                           for k, v in file_deps.items()}, {k: sorted(v) for k, v in missing.items()}],
        "check": without_ros_paths(roslaunch.rlutil.check_roslaunch(launch)),
        "check bad": roslaunch.rlutil.check_roslaunch(launch + ".missing"),
        "namespaces_of": [roslaunch.config.namespaces_of(n) for n in ("", "/a/b/c", "a/b")] +
                         [outcome(lambda: roslaunch.config.namespaces_of(None)),
                          outcome(lambda: roslaunch.config.namespaces_of(1))],
        "root context": [xml.root_context.ns, xml.root_context.resolve_dict.get("arg"),
                         sorted(xml.root_context.resolve_dict.get("arg_doc", {}).items())],
        "ifunless": [outcome(lambda tag=tag: roslaunch.xmlloader.ifunless_test(xml, tag, xml.root_context))
                     for tag in parseString('<l><a if="true"/><a unless="1"/><a if="$(arg who)"/><a/>'
                                            '<a if="1" unless="0"/></l>').documentElement.getElementsByTagName("a")],
        "xml loader": [isinstance(xml, roslaunch.loader.Loader)],
        "remap args": [[type(n.remap_args).__name__, [type(r).__name__ for r in n.remap_args], n.remap_args]
                       for n in xml_config.nodes],
        "xml nodes": [outcome(lambda n=n: load_node_xml(n)) for n in (
            'pkg="p" type="t" name="n" respawn="true" required="true"', 'pkg="p" type="" name="n"',
            'pkg="" type="t" name="n"', 'pkg="p" type="t" name="a/b"', 'pkg="p" type="t" name="n" cwd="x"',
            'pkg="p" type="t" name="n" output="file"', 'pkg="p" type="t" name="n" cwd="ros_home"')],
    }


def load_node_xml(attrs: str) -> list[Any]:
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load_string(f"<launch><node {attrs}/></launch>", config, verbose=False)
    return [[n.name, n.cwd, n.output] for n in config.nodes]


def process_section(launch: str) -> dict[str, Any]:
    """Real processes under a ProcessMonitor: one that exits 3, one respawning, one killed."""
    machine = roslaunch.core.local_machine()
    exits = Node("rl_pkg", "exiter", name="exits", args="3", namespace="/g")
    exits.machine = machine
    process = roslaunch.nodeprocess.create_node_process("rid", exits, "http://127.0.0.1:1/")
    info = [process.name.rsplit("-", 1)[0], process.package, process.log_output, process.respawn, process.required,
            process.cwd, process.env.get("ROS_NAMESPACE"), process.env["ROS_MASTER_URI"], process.args[-3:],
            process.is_alive(), process.pid, process.spawn_count, process.get_exit_description()]
    master = roslaunch.nodeprocess.create_master_process("rid", "rosmaster", None, 11999, 4, 2.5, "debug")
    # the program differs (ROS's rosmaster, kame's python -m kame.cli.rosmaster), not its arguments
    master_info = [master.name, master.package, master.required, master.args[master.args.index("--core"):],
                   master.log_output, master.is_node]
    errors = [outcome(lambda: roslaunch.nodeprocess.create_master_process("r", "rosmaster", None, 0)),
              outcome(lambda: roslaunch.nodeprocess.create_master_process("r", "zen", None, 1)),
              outcome(lambda: roslaunch.nodeprocess.LocalProcess("r", "p", "n", [], {}, False, sigint_timeout=0)),
              outcome(lambda: roslaunch.nodeprocess.create_node_process("r", Node("p", "t", name="x"), "u"))]
    died: list[Any] = []
    all_died = threading.Event()

    class Listener(roslaunch.pmon.ProcessListener):
        def process_died(self, name: str, code: int) -> None:
            died.append([name, code])
            if {"dead", "again"} <= {n for n, _ in died}:
                all_died.set()

    pm = roslaunch.pmon.ProcessMonitor()
    pm.add_process_listener(Listener())
    pm.start()
    env = dict(os.environ)
    dead = roslaunch.nodeprocess.LocalProcess("rid", "rl_pkg", "dead", ["/bin/sh", "-c", "sleep 0.5; exit 3"], env,
                                              False, is_node=False)
    again = roslaunch.nodeprocess.LocalProcess("rid", "rl_pkg", "again", ["/bin/sh", "-c", "exit 0"], env, False,
                                               respawn=True, respawn_delay=0.0, is_node=False)
    sleeper = roslaunch.nodeprocess.LocalProcess("rid", "rl_pkg", "sleeper", ["/bin/sleep", "30"], env, False,
                                                 is_node=False)
    out = io.StringIO()
    with redirect_stdout(out), redirect_stderr(io.StringIO()):
        for p in (dead, again, sleeper):
            pm.register(p)
            p.start()
        duplicate = outcome(lambda: pm.register(sleeper))
        all_died.wait(20)
        killed = pm.kill_process("sleeper")
        unknown = pm.kill_process("nobody")
        bad_kill = outcome(lambda: pm.kill_process(3))
        deadline = time.time() + 20
        while pm.has_process("sleeper") and time.time() < deadline:
            time.sleep(0.05)
        names = pm.get_process_names_with_spawn_count()
        active = pm.get_active_names()
        dead_info = [(d.name, d.exit_code, d.is_alive(), d.get_info()["name"], outcome(d.start)) for d in pm.dead_list]
        pm.shutdown()
        pm.join(30)
    died_sorted = sorted(map(tuple, died))
    return {"node process": info, "master process": master_info, "errors": errors,
            "died": [list(d) for d in sorted(set(died_sorted))], "respawned": again.spawn_count > 1,
            "duplicate": duplicate, "killed": [killed, unknown, bad_kill, sleeper.exit_code],
            "names": [sorted(n for n, _ in names[0]), sorted(n for n, _ in names[1])], "active": sorted(active),
            "dead": sorted(dead_info), "done": [pm.done, pm.is_shutdown, pm.is_alive()],
            "printed": sorted(re.sub(r"pid \[?\d+", "pid N", line) for line in out.getvalue().splitlines()
                              if "sleeper" in line or "dead" in line)}


SECTIONS = {"core": core_section, "loader": loader_section, "substitution": substitution_section,
            "files": files_section, "process": process_section}

if __name__ == "__main__":
    section, launch_file = sys.argv[1:3]
    sys.argv[1:] = ["who:=me"]  # the launch file's required arg, as roslaunch's command line gives it
    try:
        result = SECTIONS[section](launch_file)
    except Exception:
        traceback.print_exc()
        sys.exit(2)
    print(json.dumps(result, default=repr))
