"""Launching from a Python program, as roslaunch's script API does (the roslaunch package
re-exports these): Node (a node to launch), ROSLaunch (scriptapi: start, launch a node, stop)
and ROSLaunchParent (parent: a whole launch run from a program).

The launch runs on an asyncio loop in a thread the ROSLaunchParent owns; `shutdown()` stops
every process it started and ends the thread. Signal handling stays the program's own.
"""

from __future__ import annotations

import asyncio
import os
import sys
import threading
from collections.abc import Coroutine, Sequence
from typing import Any, TypeVar

from kame import environ, names
from kame.cli.roslaunch import anonymous_name, get_or_generate_uuid, load_config
from kame.launch import plan
from kame.launch.errors import LaunchError
from kame.launch.model import Node as ModelNode
from kame.launch.runner import LaunchRun, RunOptions, ros_home_of, run_dir_of
from kame.launch.supervisor import Child, say, say_error

RLException = LaunchError


class Node:
    """A node to launch, as roslaunch.core.Node takes it."""

    def __init__(self, package: str, node_type: str, name: str | None = None, namespace: str = "/",
                 machine_name: str | None = None, args: str = "", respawn: bool = False, respawn_delay: float = 0.0,
                 remap_args: list[tuple[str, str]] | None = None, env_args: list[tuple[str, str]] | None = None,
                 output: str | None = None, cwd: str | None = None, launch_prefix: str | None = None,
                 required: bool = False, filename: str = "<unknown>") -> None:
        self.package = package
        self.type = node_type
        self.name = name
        self.namespace = names.make_global_ns(namespace or "/")
        self.machine_name = machine_name
        self.machine: Any = None  # the roslaunch.core.Machine ROSLaunchConfig.assign_machines picks
        self.args = args
        self.respawn = respawn
        self.respawn_delay = respawn_delay
        self.remap_args = list(remap_args or [])
        self.env_args = list(env_args or [])
        self.output = output
        self.cwd = cwd
        self.launch_prefix = launch_prefix
        self.required = required
        self.filename = filename

    def to_model(self, default_name: str) -> ModelNode:
        return ModelNode(self.package, self.type, self.name or default_name, namespace=self.namespace,
                         machine_name=self.machine_name, args=self.args, respawn=self.respawn,
                         respawn_delay=self.respawn_delay, remap_args=list(self.remap_args),
                         env_args=list(self.env_args), output=self.output, cwd=self.cwd,
                         launch_prefix=self.launch_prefix, required=self.required, filename=self.filename)


T = TypeVar("T")


class Process:
    """A launched process as roslaunch's API hands it back."""

    def __init__(self, child: Child, loop: asyncio.AbstractEventLoop, run: LaunchRun) -> None:
        self._child = child
        self._loop = loop
        self._run = run

    @property
    def name(self) -> str:
        return self._child.name

    @property
    def pid(self) -> int:
        return self._child.pid

    @property
    def exit_code(self) -> int | None:
        proc = self._child.proc
        return None if proc is None else proc.returncode

    def is_alive(self) -> bool:
        proc = self._child.proc
        return proc is not None and proc.returncode is None

    def stop(self) -> None:
        opts = self._run.options
        asyncio.run_coroutine_threadsafe(self._child.stop(opts.sigint_timeout, opts.sigterm_timeout),
                                         self._loop).result()


class _Runner:
    """`parent.runner`: launch_node(node) -> (process, success)."""

    def __init__(self, parent: ROSLaunchParent) -> None:
        self._parent = parent

    def launch_node(self, node: Node) -> tuple[Process | None, bool]:
        run = self._parent._require_run()
        model = node.to_model(anonymous_name(node.type))
        child = self._parent._call(run.launch_node(model))
        if child is None:
            return None, False
        return Process(child, self._parent._loop, run), True


class ROSLaunchParent:
    def __init__(self, run_id: str, roslaunch_files: Sequence[Any], is_core: bool = False, port: int | None = None,
                 local_only: bool = False, process_listeners: Sequence[object] | None = None,
                 verbose: bool = False, force_screen: bool = False, force_log: bool = False,
                 is_rostest: bool = False, roslaunch_strs: Sequence[str] | None = None, num_workers: int = 3,
                 timeout: float | None = None, master_logger_level: str | bool = False, show_summary: bool = True,
                 force_required: bool = False, sigint_timeout: float = 15.0, sigterm_timeout: float = 2.0) -> None:
        self.run_id = run_id
        self.roslaunch_files = list(roslaunch_files)
        self.roslaunch_strs = list(roslaunch_strs or [])
        self.is_core = is_core
        self.show_summary = show_summary
        env = dict(os.environ)
        level = master_logger_level if isinstance(master_logger_level, str) else None
        uri = f"http://localhost:{port}/" if port else environ.master_uri(env, default=environ.SETUP_MASTER_URI)
        self.options = RunOptions(run_id=run_id, master_uri=uri, run_dir=run_dir_of(env, run_id),
                                  ros_home=ros_home_of(env), env=env, port=port, force_screen=force_screen,
                                  force_log=force_log, force_required=force_required, local_only=local_only,
                                  sigint_timeout=sigint_timeout, sigterm_timeout=sigterm_timeout,
                                  num_workers=num_workers, master_timeout=timeout,
                                  master_logger_level=level, is_core=is_core)
        self.verbose = verbose
        self.process_listeners = list(process_listeners or [])
        self.runner = _Runner(self)
        self._run: LaunchRun | None = None
        self._loop = asyncio.new_event_loop()
        self._thread: threading.Thread | None = None

    def _require_run(self) -> LaunchRun:
        if self._run is None:
            raise LaunchError("please start ROSLaunch first")
        return self._run

    def _call(self, coro: Coroutine[Any, Any, T]) -> T:
        return asyncio.run_coroutine_threadsafe(coro, self._loop).result()

    def _load(self) -> LaunchRun:
        files: list[str] = []
        argv: list[str] = list(sys.argv)
        for entry in self.roslaunch_files:
            if isinstance(entry, tuple):  # (file, [args]) as roslaunch accepts it
                files.append(entry[0])
                argv = [*argv, *entry[1]]
            else:
                files.append(entry)
        config, _ = load_config(files, argv, self.options.env, strings=self.roslaunch_strs, verbose=self.verbose)
        run = LaunchRun(config, self.options)
        run.check()
        run.monitor.on_death = self._tell_listeners
        return run

    def _tell_listeners(self, child: Child) -> None:
        """process_died(name, exit code) on each listener (roslaunch.pmon.ProcessListener), on the launch's
        thread; a listener that raises is reported, and the others are still told."""
        for listener in self.process_listeners:
            try:
                listener.process_died(child.name, child.exit_code)  # type: ignore[attr-defined]
            except Exception as exc:  # a user's callback: reported, never the end of the launch
                say_error(f"process listener {listener!r} failed on [{child.name}]: {exc!r}")

    def start(self, auto_terminate: bool = True) -> None:
        """Load, start the master if needed, set parameters and start the nodes."""
        run = self._load()
        if not auto_terminate:
            run.monitor.keep_alive = True
        if self.show_summary:
            say(plan.summary(run.config))
        for err in run.config.errors:
            say_error(f"WARNING: {err}")
        self._thread = threading.Thread(target=self._loop.run_forever, name="roslaunch", daemon=True)
        self._thread.start()
        self._run = run
        self._call(self._start(run))

    async def _start(self, run: LaunchRun) -> None:
        try:
            await run.setup()
            await run.launch_nodes()
        except BaseException:
            await run.monitor.shutdown()
            raise

    def spin_once(self) -> bool:
        return self._run is not None and not self._run.monitor.done.is_set()

    def spin(self) -> None:
        """Until the launch ends (every node gone, a required node died, or shutdown())."""
        run = self._require_run()
        self._call(run.monitor.done.wait())
        self.shutdown()

    def shutdown(self) -> None:
        run, self._run = self._run, None
        if run is not None:
            self._call(run.stop())
        if self._thread is not None:
            self._loop.call_soon_threadsafe(self._loop.stop)
            self._thread.join(5)
            self._thread = None
            self._loop.close()


class ROSLaunch:
    def __init__(self) -> None:
        self.parent = ROSLaunchParent(get_or_generate_uuid(None, False), [], is_core=False, show_summary=False)
        self.started = False

    def start(self) -> None:
        self.parent.start(auto_terminate=False)
        self.started = True

    def launch(self, node: Node) -> Process:
        if not self.started:
            raise LaunchError("please start ROSLaunch first")
        if not isinstance(node, Node):
            raise ValueError("arg must be of type Node")
        process, success = self.parent.runner.launch_node(node)
        if not success or process is None:
            raise LaunchError(f"failed to launch {node.package}/{node.type}")
        return process

    def spin(self) -> None:
        self.parent.spin()

    def spin_once(self) -> None:
        self.parent.spin_once()

    def stop(self) -> None:
        self.parent.shutdown()
