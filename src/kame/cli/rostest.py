"""rostest: run the <test> nodes of a launch file, each inside its own freshly launched graph.

    rostest [options] [package] <file.test> [arg:=value ...]

Rules (ros_comm's rostest, Noetic; ros1-user-behaviour §12):
- The file is loaded as roslaunch loads it (`.test` or `.launch`); its <test> tags are the tests,
  run in the order of their method names `test<test-name>` (unittest sorts them), one at a time.
- For each test: a private master on a free port (in this process; `--reuse-master` uses the one
  at ROS_MASTER_URI instead, `--clear` then deletes its parameters first), the launch's parameters
  and nodes, then the test node with `--gtest_output=xml:<results>/<pkg>/rosunit-<test-name>.xml`
  added to its args. It gets `time-limit` seconds (60) to exit; then everything is stopped
  (SIGINT, SIGTERM, SIGKILL to each process group, as roslaunch does). `retry="N"` runs a test
  that failed or timed out again, up to N more times, in a new graph.
- The run's own record, one case per test (`classname="rostest.runner.RosTest"`), is written to
  `<results>/<pkg>/rostest-<path of the file in its package, / as _, no suffix>.xml`; the launch
  output goes into its system-out, the console only gets `[Testcase: testNAME] ... ok`, then the
  summary of every case the test nodes reported.
- Exit status: 1 when a test could not run (timed out, failed to launch, wrote no results),
  2 when the tests reported errors or failures, else 0.
- `--text`: test nodes print to the console (`--text` is added to their args; rostest.rosrun then
  uses a plain unittest runner) and no results are read. Unlike the real rostest, which then
  cannot tell a failing test from a passing one, a test node exiting non-zero fails its case.
"""

from __future__ import annotations

import argparse
import asyncio
import contextlib
import dataclasses
import logging
import os
import signal
import subprocess
import sys
import threading
import unittest
import uuid
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path

from kame import environ
from kame.catkin import executables
from kame.cli import _junit
from kame.cli.rosmaster import log_dir, setup_file_logging
from kame.launch import plan
from kame.launch.errors import LaunchError
from kame.launch.model import LaunchConfig, Node
from kame.launch.runner import CALLER, LaunchRun, RunOptions, ros_home_of, run_dir_of
from kame.launch.supervisor import say
from kame.master.server import MasterServer
from kame.net import interfaces
from kame.net.address import host_addresses
from kame.node.master_proxy import MasterError, MasterProxy

log = logging.getLogger("kame.rostest")
KEPT_PARAMS = ("/run_id", "/rosversion", "/rosdistro")


class RLException(Exception):
    """roslaunch's exception name, kept: it is the `type` of an <error> in the results."""


class RLTestTimeoutException(RLException):
    pass


def printlog(text: str) -> None:
    log.info("%s", text)
    print("[ROSTEST]" + text, flush=True)


def printlogerr(text: str) -> None:
    log.error("%s", text)
    print("[ROSTEST]" + text, file=sys.stderr, flush=True)


class PrivateMaster:
    """A master serving on a free port from a thread of this process, as rostest's own is."""

    def __init__(self, env: Mapping[str, str]) -> None:
        self.env = env
        self.loop = asyncio.new_event_loop()
        self.thread = threading.Thread(target=self.loop.run_forever, name="rostest-master", daemon=True)
        self.server: MasterServer | None = None

    def start(self) -> str:
        self.thread.start()

        async def start() -> str:
            host = host_addresses(self.env)
            self.server = MasterServer(host.bind, 0, host.advertised)
            return await self.server.start()

        return asyncio.run_coroutine_threadsafe(start(), self.loop).result(10)

    def stop(self) -> None:
        async def stop() -> None:
            if self.server is not None:
                await self.server.close()
            others = [t for t in asyncio.all_tasks() if t is not asyncio.current_task()]
            for task in others:
                task.cancel()
            await asyncio.gather(*others, return_exceptions=True)

        with contextlib.suppress(Exception):
            asyncio.run_coroutine_threadsafe(stop(), self.loop).result(10)
        self.loop.call_soon_threadsafe(self.loop.stop)
        self.thread.join(5)
        if not self.thread.is_alive():
            self.loop.close()


@dataclasses.dataclass
class Settings:
    test_file: str
    package: str
    config: LaunchConfig
    env: dict[str, str]
    reuse_master: bool = False
    clear: bool = False
    text_mode: bool = False
    results_base_dir: str | None = None


class Harness:
    """Runs one <test> at a time in a graph of its own, on an event loop kept across tests."""

    def __init__(self, settings: Settings) -> None:
        self.settings = settings
        self.loop = asyncio.new_event_loop()
        self.counter = 0  # process numbers go on across tests, as in one roslaunch
        self.results = _junit.Result("rostest")
        self.interrupted = False

    # ------------------------------------------------------------------ called by the test methods

    def run_test(self, case: unittest.TestCase, test: Node) -> None:
        task = self.loop.create_task(self._run_test(case, test))

        def interrupt() -> None:
            if not self.interrupted:  # once: a second Ctrl-C must not cut the teardown short
                self.interrupted = True
                task.cancel()

        for sig in (signal.SIGINT, signal.SIGTERM):
            self.loop.add_signal_handler(sig, interrupt)
        try:
            self.loop.run_until_complete(task)
        except asyncio.CancelledError:
            if self.interrupted:
                raise KeyboardInterrupt from None
            raise
        finally:
            for sig in (signal.SIGINT, signal.SIGTERM):
                self.loop.remove_signal_handler(sig)

    def close(self) -> None:
        self.loop.close()

    # ------------------------------------------------------------------ one test

    async def _run_test(self, case: unittest.TestCase, test: Node) -> None:
        name = test.test_name or test.name
        retry = test.retry
        settings = self.settings
        while True:
            run, master = await self._set_up()
            try:
                printlog(f"Running test [{name}]")
                await run.setup()
                await run.launch_nodes()
                case.assertTrue(not run.failed, f"Test Fixture Nodes {run.failed} failed to launch")
                path = _junit.xml_results_file(settings.package, name, False, settings.env,
                                               settings.results_base_dir)
                if path.exists():
                    printlog(f"removing previous test results file [{path}]")
                    path.unlink()
                args = f"{test.args} {_junit.XML_OUTPUT_FLAG}{path}"
                output = test.output
                if settings.text_mode:
                    output, args = "screen", args + " --text"
                node = dataclasses.replace(test, args=args, output=output)
                printlog(f"running test {name}")
                timed_out = False
                try:
                    code = await self._run_node(run, node)
                except RLTestTimeoutException:
                    if not retry:
                        raise
                    timed_out = True
                    code = None
                if timed_out:
                    printlogerr(f"test [{name}] timed out")
                else:
                    printlog(f"test [{name}] finished")
                if settings.text_mode and not timed_out:
                    if retry:
                        printlogerr("retry is disabled in --text mode")
                    case.assertTrue(code == 0, f"test [{name}] exited with status {code}")
                else:
                    results = _junit.Result(name)
                    if not timed_out:
                        case.assertTrue(path.is_file(), f"test [{name}] did not generate test results")
                        printlog(f"test [{name}] results are in [{path}]")
                        results = _junit.read(path, name)
                    if retry > 0 and (timed_out or results.num_errors or results.num_failures):
                        retry -= 1
                        printlog(f"test [{name}] failed, retrying. Retries left: {retry}")
                        continue  # torn down below; set up anew
                    self.results.accumulate(results)
                    printlog(f"test [{name}] results summary: {results.num_errors} errors, "
                             f"{results.num_failures} failures, {results.num_tests} tests")
                printlog(f"[ROSTEST] test [{name}] done")
                return
            except LaunchError as exc:
                raise RLException(exc.describe()) from None
            finally:
                await self._tear_down(run, master)

    async def _run_node(self, run: LaunchRun, node: Node) -> int | None:
        """Start the test node and wait for it within its time limit; its exit status."""
        child = await run.launch_node(node)
        if child is None or child.proc is None:
            raise RLException(f"test [{node.test_name}] failed to launch")
        exited = asyncio.ensure_future(child.proc.wait())
        graph_down = asyncio.ensure_future(run.monitor.done.wait())  # a required node died
        try:
            done, _ = await asyncio.wait([exited, graph_down], timeout=node.time_limit,
                                         return_when=asyncio.FIRST_COMPLETED)
        finally:
            for future in (exited, graph_down):
                future.cancel()
        if not done:
            raise RLTestTimeoutException(f"max time [{node.time_limit}s] allotted for test [{node.test_name}] "
                                         f"of type [{node.package}/{node.type}]")
        return child.proc.returncode

    async def _set_up(self) -> tuple[LaunchRun, PrivateMaster | None]:
        settings = self.settings
        env = settings.env
        master: PrivateMaster | None = None
        if settings.reuse_master:
            uri = environ.master_uri(env, default=environ.SETUP_MASTER_URI)
            run_id = self._existing_run_id(uri)
        else:
            run_id = str(uuid.uuid1())
        printlog(f"setup[{settings.test_file}] run_id[{run_id}] starting")
        if not settings.reuse_master:
            master = PrivateMaster(env)
            uri = master.start()
        options = RunOptions(run_id=run_id, master_uri=uri, run_dir=run_dir_of(env, run_id),
                             ros_home=ros_home_of(env), env=env)
        run = LaunchRun(settings.config, options, run_command=_rosparam)
        run.monitor.keep_alive = True  # the graph stays up when its nodes are done: the test decides
        run.counter = self.counter
        say(plan.summary(settings.config))
        printlog(f"setup[{settings.test_file}] run_id[{run_id}] done")
        return run, master

    def _existing_run_id(self, uri: str) -> str:
        proxy = MasterProxy(uri, CALLER, timeout=5.0)
        try:
            run_id = str(proxy.call("getParam", "/run_id"))
            if self.settings.clear:
                for param in proxy.call("getParamNames"):
                    if param not in KEPT_PARAMS and not param.startswith("/roslaunch/"):
                        proxy.call("deleteParam", param)
            return run_id
        except (OSError, MasterError, ValueError) as exc:
            raise RLException(f"Could not connect to existing ROS master. Original exception was: {exc}") from None
        finally:
            proxy.close()

    async def _tear_down(self, run: LaunchRun, master: PrivateMaster | None) -> None:
        printlog(f"tearDown[{self.settings.test_file}]")
        try:
            await run.stop()
        finally:
            self.counter = run.counter
            if master is not None:
                master.stop()
        printlog(f"rostest teardown {self.settings.test_file} complete")


def _rosparam(args: list[str]) -> int:
    return subprocess.run([sys.executable, "-m", "kame.cli.rosparam", *args[1:]], check=False).returncode


# ------------------------------------------------------------------ the test case class


def _program_problem(test: Node, env: Mapping[str, str]) -> str | None:
    package = executables.packages(env).get(test.package)
    if package is None:
        return f"Package [{test.package}] for test node [{test.package}/{test.type}] does not exist"
    if not executables.find_node(package, test.type, env):
        return f"Test node [{test.package}/{test.type}] does not exist or is not executable"
    return None


def _failing(message: str, printed: str | None = None) -> Callable[[unittest.TestCase], None]:
    def method(self: unittest.TestCase) -> None:
        if printed is None:
            print(message, file=sys.stderr)
        else:
            print(printed)
        self.fail(message)

    return method


def _running(harness: Harness, test: Node) -> Callable[[unittest.TestCase], None]:
    def method(self: unittest.TestCase) -> None:
        harness.run_test(self, test)

    return method


def test_case_class(harness: Harness) -> type[unittest.TestCase]:
    """rostest's RosTest: one method per <test>, so unittest runs and reports them."""
    methods: dict[str, object] = {}
    running: list[str] = []
    for test in harness.settings.config.tests:
        test_name = test.test_name or test.name
        method_name = f"test{test_name}"
        problem = _program_problem(test, harness.settings.env)
        if problem:
            methods[method_name] = _failing(problem)
        elif method_name in running:
            message = f"Duplicate tests named [{test_name}] in rostest suite"
            methods[method_name] = _failing(message, message)
        else:
            methods[method_name] = _running(harness, test)
            running.append(method_name)
    methods["__module__"] = "rostest.runner"
    return type("RosTest", (unittest.TestCase,), methods)


# ------------------------------------------------------------------ command line


def _parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(prog="rostest", usage="rostest [options] [package] <filename>")
    add = p.add_argument
    add("-t", "--text", dest="text_mode", action="store_true", help="Run with stdout output instead of XML output")
    add("--pkgdir", dest="pkg_dir", metavar="PKG_DIR", help="package dir")
    add("--package", dest="package", metavar="PACKAGE", help="package")
    add("--results-filename", dest="results_filename", metavar="RESULTS_FILENAME", help="results_filename")
    add("--results-base-dir", dest="results_base_dir", metavar="RESULTS_BASE_DIR",
        help="The base directory of the test results. The test result file is created in a subfolder name PKG_DIR.")
    add("-r", "--reuse-master", dest="reuse_master", action="store_true",
        help="Connect to an existing ROS master instead of spawning a new ROS master on a custom port")
    add("-c", "--clear", dest="clear", action="store_true",
        help="Clear all parameters when connecting to an existing ROS master (only works with --reuse-master)")
    add("args", nargs="*", help=argparse.SUPPRESS)
    return p


def package_of(path: str, env: Mapping[str, str]) -> tuple[str, str] | None:
    """(name, folder) of the package holding `path`: the nearest folder above it with a package.xml."""
    known = {str(p.path.resolve()): p.name for p in executables.packages(env).values()}
    folder = Path(path).resolve().parent
    for candidate in (folder, *folder.parents):
        if (candidate / "package.xml").is_file() or (candidate / "manifest.xml").is_file():
            name = known.get(str(candidate)) or _manifest_name(candidate) or candidate.name
            return name, str(candidate)
    return None


def _manifest_name(folder: Path) -> str | None:
    import xml.etree.ElementTree as ET

    try:
        root = ET.parse(folder / "package.xml").getroot()
    except (OSError, ET.ParseError):
        return None
    name = root.findtext("name")
    return name.strip() if name else None


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv[1:] if argv is None else argv)
    parser = _parser()
    options, rest = parser.parse_known_args(argv)
    unknown = [a for a in rest if a.startswith("-")]
    if unknown:
        parser.error(f"no such option: {unknown[0]}")
    positional = [*options.args, *rest]
    if options.clear and not options.reuse_master:
        print("The --clear option is only valid with --reuse-master", file=sys.stderr)
        return 1
    from kame.cli.roslaunch import load_config, resolve_launch_arguments

    env = dict(os.environ)
    try:
        files = resolve_launch_arguments(positional, env)
    except LaunchError as exc:
        print(str(exc), file=sys.stderr)
        return 1
    logfile = log_dir(env) / f"rostest-{interfaces.hostname()}-{os.getpid()}.log"
    handler = setup_file_logging(logfile, "kame")
    try:
        print(f"... logging to {logfile}", flush=True)
        log.info("rostest starting with options %s, args %s", options, files)
        if not files:
            parser.error("You must supply a test file argument to rostest.")
        if len(files) != 1:
            parser.error("rostest only accepts a single test file")
        test_file = files[0]
        if options.pkg_dir and options.package:
            pkg, pkg_dir = options.package, options.pkg_dir
        else:
            found = package_of(test_file, env)
            if found is None:
                print(f"rostest: [{test_file}] is not inside a ROS package (no package.xml above it)",
                      file=sys.stderr)
                return 1
            pkg, pkg_dir = found
        if options.results_filename:
            outname = options.results_filename
            outname = outname[: outname.rfind(".")] if "." in outname else outname
        else:
            outname = _junit.rostest_name_from_path(pkg_dir, test_file)
        base_dir = options.results_base_dir
        if not os.path.isfile(test_file):
            results_file = _junit.xml_results_file(pkg, outname, True, env, base_dir)
            results_file.write_text(_junit.failure_junit_xml(outname, f"rostest file [{test_file}] does not exist"))
            parser.error(f"test file is invalid. Generated failure case result file in {results_file}")
        try:
            config, _ = load_config([test_file], [a for a in positional if ":=" in a], env)
            LaunchRun(config, RunOptions("", "", Path(), Path(), env)).check()
        except LaunchError as exc:
            print(f"RLException: {exc.describe()}", file=sys.stderr)
            return 1
        return _run(Settings(test_file, pkg, config, env, options.reuse_master, options.clear, options.text_mode,
                             base_dir), outname, logfile)
    finally:
        handler.close()


def _run(settings: Settings, outname: str, logfile: Path) -> int:
    harness = Harness(settings)
    suite = unittest.TestLoader().loadTestsFromTestCase(test_case_class(harness))
    try:
        if settings.text_mode:
            result: unittest.TestResult = unittest.TextTestRunner(verbosity=2).run(suite)
        else:
            path = _junit.xml_results_file(settings.package, outname, True, settings.env, settings.results_base_dir)
            result = _junit.create_xml_runner(settings.package, outname, str(path), is_rostest=True).run(suite)
    except KeyboardInterrupt:
        print("rostest: interrupted, every process stopped", file=sys.stderr)
        return 1
    finally:
        harness.close()
    if settings.config.errors:
        print("\n[ROSTEST WARNINGS]" + "-" * 62 + "\n", file=sys.stderr)
        for err in settings.config.errors:
            print(f" * {err}", file=sys.stderr)
    print("")
    if settings.text_mode:
        print("WARNING: overall test result is not accurate when --text is enabled")
    else:
        print(_junit.runner_summary(result, harness.results), flush=True)
    print(f"rostest log file is in {logfile}")
    if not result.wasSuccessful():
        return 1
    if harness.results.num_errors or harness.results.num_failures:
        return 2
    return 0


if __name__ == "__main__":
    sys.exit(main())
