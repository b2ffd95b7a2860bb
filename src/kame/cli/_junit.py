"""JUnit XML results as rosunit writes and reads them, and the summaries rostest prints.

Rules (rosunit's core, junitxml, xmlrunner and baretest, Noetic):
- Results live under ROS_TEST_RESULTS_DIR, else ROS_HOME/test_results (~/.ros/test_results), in a
  folder per package: `rostest-<file name>.xml` for a whole rostest run, `rosunit-<test name>.xml`
  for one test node or unit test (` "'&$!`/\\` in the name become `_`).
- A test node is told where to write by the argument `--gtest_output=xml:<path>`.
- The XML: `<testsuite errors failures name tests time>` with one `<testcase classname name time>`
  per test, a `<failure type>` or `<error type>` child holding the message and traceback, then
  `<system-out>` and `<system-err>`. Their text is the captured output wrapped in the characters
  `<![CDATA[\\n...\\n]]>`, which rosunit hands to ElementTree as plain text, so the file holds them
  escaped (`&lt;![CDATA[`): kame writes the same bytes, since rosunit's readers strip them alike.
- Reading one file names each case `<results folder>.<file name without TEST- and .xml>/<name>`
  (`demo.rosunit-talker_test/test_hello`) and totals errors, failures and tests.
"""

from __future__ import annotations

import io
import os
import re
import sys
import time
import traceback
import unittest
import xml.etree.ElementTree as ET
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from types import TracebackType
from typing import TextIO

XML_OUTPUT_FLAG = "--gtest_output=xml:"
_UNSAFE_NAME_CHARS = " \"'&$!`/\\"
_NON_PRINTABLE = re.compile("[^\t\n\r\x20-\x7e\x85\xa0-\xff\u0100-\ud7ff\ue000-\ufdcf\ufde0-\ufffd]")
_ILLEGAL_XML = re.compile("[\x00-\x08\x0b\x0c\x0e-\x1f\ufffe\uffff]|[\ud800-\udfff]")
RED, GREEN, RESET = "\033[1;31m", "\033[32m", "\033[0m"

ExcInfo = tuple[type[BaseException], BaseException, TracebackType]


# ------------------------------------------------------------------ where results go


def test_results_dir(env: Mapping[str, str] | None = None) -> Path:
    """rospkg's get_test_results_dir: ROS_TEST_RESULTS_DIR, else ROS_HOME/test_results."""
    env = os.environ if env is None else env
    if env.get("ROS_TEST_RESULTS_DIR"):
        return Path(env["ROS_TEST_RESULTS_DIR"])
    home = Path(env["ROS_HOME"]) if env.get("ROS_HOME") else Path.home() / ".ros"
    return home / "test_results"


def xml_results_file(package: str, test_name: str, is_rostest: bool = False,
                     env: Mapping[str, str] | None = None, base_dir: str | None = None) -> Path:
    """The results file of `test_name` (its folder is created)."""
    folder = (Path(base_dir) if base_dir else test_results_dir(env)) / package
    try:
        folder.mkdir(parents=True, exist_ok=True)
    except OSError as exc:
        raise OSError(f"cannot create test results directory [{folder}]: {exc}") from exc
    for char in _UNSAFE_NAME_CHARS:
        test_name = test_name.replace(char, "_")
    return folder / (f"rostest-{test_name}.xml" if is_rostest else f"rosunit-{test_name}.xml")


def rostest_name_from_path(pkg_dir: str, test_file: str) -> str:
    """`<pkg>/test/talker.test` -> `test_talker`: the path inside the package, `/` as `_`, no suffix."""
    path = os.path.abspath(test_file)
    if path.startswith(pkg_dir):
        path = path[len(pkg_dir):].lstrip(os.sep)
    name = path.replace(os.sep, "_")
    return name[: name.rfind(".")] if "." in name else name


def result_file_from_args(args: list[str]) -> str | None:
    found = None
    for arg in args:
        if arg.startswith(XML_OUTPUT_FLAG):
            found = arg[len(XML_OUTPUT_FLAG):]
    return found


# ------------------------------------------------------------------ the result model


@dataclass
class Problem:
    """A <failure> or <error>: the exception's type name and its text."""

    type: str
    text: str


@dataclass
class CaseResult:
    name: str
    classname: str = ""
    time: float = 0.0
    failures: list[Problem] = field(default_factory=list)
    errors: list[Problem] = field(default_factory=list)

    @property
    def passed(self) -> bool:
        return not self.failures and not self.errors

    def _block(self, kind: str, problems: list[Problem]) -> str:
        head = f"[{self.name}][{kind}]"
        head += "-" * (80 - len(head))
        return "\n".join(f"{head}\n{p.text}\n" + "-" * 80 + "\n\n" for p in problems)

    @property
    def description(self) -> str:
        if self.passed:
            return f"[{self.name}][passed]\n"
        return self._block("FAILURE", self.failures) + self._block("ERROR", self.errors)


@dataclass
class Result:
    name: str
    num_errors: int = 0
    num_failures: int = 0
    num_tests: int = 0
    cases: list[CaseResult] = field(default_factory=list)
    system_out: str = ""
    system_err: str = ""
    time: float = 0.0

    def accumulate(self, other: Result) -> None:
        self.num_errors += other.num_errors
        self.num_failures += other.num_failures
        self.num_tests += other.num_tests
        self.time += other.time
        self.cases.extend(other.cases)
        if other.system_out:
            self.system_out += "\n" + other.system_out
        if other.system_err:
            self.system_err += "\n" + other.system_err


# ------------------------------------------------------------------ writing


def cdata(text: str) -> str:
    return f"<![CDATA[\n{text}\n]]>"


def filter_nonprintable_text(text: str) -> str:
    return _NON_PRINTABLE.sub(lambda m: f"&#x{ord(m.group(0)):04X};", text)


def suite_xml(name: str, cases: list[CaseResult], elapsed: float, out: str, err: str) -> str:
    """A whole results file, as rosunit's XML runner writes it."""
    suite = ET.Element("testsuite")
    suite.set("errors", str(sum(len(c.errors) for c in cases)))
    suite.set("failures", str(sum(len(c.failures) for c in cases)))
    suite.set("name", name)
    suite.set("tests", str(len(cases)))
    suite.set("time", f"{elapsed:.3f}")
    for case in cases:
        element = ET.SubElement(suite, "testcase")
        element.set("classname", case.classname)
        element.set("name", case.name)
        element.set("time", f"{case.time:.4f}")
        for tag, problems in (("failure", case.failures), ("error", case.errors)):
            for problem in problems:
                child = ET.SubElement(element, tag)
                child.set("type", problem.type)
                child.text = problem.text
    ET.SubElement(suite, "system-out").text = cdata(filter_nonprintable_text(out))
    ET.SubElement(suite, "system-err").text = cdata(filter_nonprintable_text(err))
    return '<?xml version="1.0" encoding="utf-8"?>\n' + ET.tostring(suite, encoding="unicode")


def failure_junit_xml(test_name: str, message: str, class_name: str = "Results",
                      testcase_name: str = "test_ran") -> str:
    """A one-case suite that failed (rostest's answer for a test file that does not exist)."""
    return (f'<?xml version="1.0" encoding="UTF-8"?>\n<testsuite tests="1" failures="1" time="1" errors="0" '
            f'name="{_attr(test_name)}">\n  <testcase name="{_attr(testcase_name)}" status="run" time="1" '
            f'classname="{_attr(class_name)}">\n    <failure message="{_attr(message)}" type=""/>\n'
            "  </testcase>\n</testsuite>")


def _attr(text: str) -> str:
    return text.replace("&", "&amp;").replace('"', "&quot;").replace("<", "&lt;").replace(">", "&gt;")


# ------------------------------------------------------------------ reading


def read(path: str | Path, test_name: str) -> Result:
    """The results in `path`, named as rosunit.junitxml.read names them; empty when unreadable."""
    path = Path(path)
    try:
        raw = path.read_bytes()
        try:
            text = raw.decode("utf-8")
        except UnicodeDecodeError:
            text = raw.decode("iso8859-1")
        text = _ILLEGAL_XML.sub("?", text)
        if not text.strip():
            print(f"WARN: test result file is empty [{path}]")
            return Result(test_name)
        root = ET.fromstring(text.encode("utf-8"))
    except (OSError, ET.ParseError) as exc:
        print(f"WARN: cannot read test result file [{path}]: {exc}")
        return Result(test_name)
    suites = [root] if root.tag == "testsuite" else root.findall("testsuite")
    if not suites:
        print(f"WARN: test result file [{path}] contains no results")
        return Result(test_name)
    fname = path.name
    fname = fname[5:] if fname.startswith("TEST-") else fname
    fname = fname[:-4] if fname.endswith(".xml") else fname
    prefix = f"{path.resolve().parent.name}.{fname}"
    total = Result(test_name)
    for suite in suites:
        result = Result(test_name, _int(suite.get("errors")), _int(suite.get("failures")), _int(suite.get("tests")))
        result.time = _float(suite.get("time"))
        _load_suite(prefix, suite, result)
        total.accumulate(result)
    return total


def _int(text: str | None) -> int:
    try:
        return int(text or 0)
    except ValueError:
        return 0


def _float(text: str | None) -> float:
    try:
        return float(text or 0.0)
    except ValueError:
        return 0.0


def _text(element: ET.Element) -> str:
    return (element.text or "").strip()


def _load_suite(prefix: str, suite: ET.Element, result: Result) -> None:
    for node in suite:
        if node.tag == "testsuite":
            _load_suite(prefix, node, result)
        elif node.tag in ("system-out", "system-err") and _text(node):
            kind = "stdout" if node.tag == "system-out" else "stderr"
            block = f"[{prefix}] {kind}" + "-" * (71 - len(prefix)) + "\n" + _text(node)
            if kind == "stdout":
                result.system_out += block
            else:
                result.system_err += block
        elif node.tag == "testcase":
            classname = node.get("classname") or "unknown"
            if "__main__." in classname:
                classname = classname[classname.find("__main__.") + 9:]
            if classname == "rostest.rostest.RosTest":
                classname = "rostest"
            elif not classname.startswith(result.name):
                classname = f"{result.name}.{classname}"
            case = CaseResult(f"{prefix}/{node.get('name') or 'unknown'}", classname, _float(node.get("time")))
            for child in node:
                if child.tag in ("failure", "error"):
                    problem = Problem(child.get("type") or "", _text(child) or child.get("message") or "")
                    (case.failures if child.tag == "failure" else case.errors).append(problem)
            result.cases.append(case)


# ------------------------------------------------------------------ running unittest suites


class _Outcome:
    def __init__(self, test: unittest.TestCase, elapsed: float, failure: ExcInfo | None, error: ExcInfo | None):
        self.classname, self.method = test.id().rsplit(".", 1)
        self.elapsed = elapsed
        self.failure = failure
        self.error = error

    def case(self) -> CaseResult:
        case = CaseResult(self.method, self.classname, self.elapsed)
        if self.failure is not None:
            case.failures.append(_problem(self.failure))
        if self.error is not None:
            case.errors.append(_problem(self.error))
        return case

    def text(self) -> str:
        out = f"[Testcase: {self.method}]"
        if self.failure is None and self.error is None:
            return out + " ... ok\n"
        for kind, info in (("failure", self.failure), ("error", self.error)):
            if info is not None:
                out += " ... FAILURE!\n" if kind == "failure" else " ... ERROR!\n"
                tb = "".join(traceback.format_tb(info[2]))
                out += f"{kind.upper()}: {_escape(str(info[1]))}\n{_escape(tb)}" + "-" * 80 + "\n"
        return out


def _escape(text: str) -> str:
    return text.replace("&", "&amp;").replace("<", "&lt;").replace(">", "&gt;")


def _problem(info: ExcInfo) -> Problem:
    return Problem(info[0].__name__, f"{info[1]}\n{''.join(traceback.format_tb(info[2]))}")


class XMLTestResult(unittest.TestResult):
    """Records each test's time and its failure or error, for the XML report."""

    def __init__(self) -> None:
        super().__init__()
        self.outcomes: list[_Outcome] = []
        self._started = 0.0
        self._failure: ExcInfo | None = None
        self._error: ExcInfo | None = None

    def startTest(self, test: unittest.TestCase) -> None:
        super().startTest(test)
        self._failure = self._error = None
        self._started = time.time()

    def stopTest(self, test: unittest.TestCase) -> None:
        super().stopTest(test)
        self.outcomes.append(_Outcome(test, time.time() - self._started, self._failure, self._error))

    def addError(self, test: unittest.TestCase, err: ExcInfo) -> None:  # type: ignore[override]
        super().addError(test, err)
        self._error = err

    def addFailure(self, test: unittest.TestCase, err: ExcInfo) -> None:  # type: ignore[override]
        super().addFailure(test, err)
        self._failure = err


class XMLTestRunner:
    """Runs a suite with stdout/stderr captured, writes the XML report, then prints one line per test."""

    def __init__(self, path: Path) -> None:
        self.path = path

    def run(self, test: unittest.TestSuite | unittest.TestCase) -> XMLTestResult:
        suite_name = f"{type(test).__module__}.{type(test).__name__}"
        result = XMLTestResult()
        started = time.time()
        stdout, stderr = sys.stdout, sys.stderr
        out, err = io.StringIO(), io.StringIO()
        sys.stdout, sys.stderr = out, err
        try:
            test(result)
        finally:
            sys.stdout, sys.stderr = stdout, stderr
        elapsed = time.time() - started
        text = suite_xml(suite_name, [o.case() for o in result.outcomes], elapsed, out.getvalue(), err.getvalue())
        self.path.write_text(text, encoding="utf-8")
        for outcome in result.outcomes:
            sys.stdout.write(outcome.text())
        sys.stdout.flush()
        return result


def create_xml_runner(package: str, test_name: str, results_file: str | None = None,
                      is_rostest: bool = False) -> XMLTestRunner:
    """rosunit's create_xml_runner: announces the file it will write."""
    path = Path(results_file) if results_file else xml_results_file(package, os.path.basename(test_name), is_rostest)
    folder = path.absolute().parent
    if folder.is_file():
        raise OSError(f"ERROR: cannot run test suite, file is preventing creation of test dir: {folder}")
    folder.mkdir(parents=True, exist_ok=True)
    print(f"[ROSUNIT] Outputting test results to {path}")
    return XMLTestRunner(path)


def load_suite(test: object) -> unittest.TestSuite:
    """A test given as a dotted name, a TestCase class, or a suite or case instance."""
    loader = unittest.TestLoader()
    if isinstance(test, str):
        return loader.loadTestsFromName(test)
    if isinstance(test, type) and issubclass(test, unittest.TestCase):
        return loader.loadTestsFromTestCase(test)
    if isinstance(test, unittest.TestSuite):
        return test
    if isinstance(test, unittest.TestCase):
        return unittest.TestSuite([test])
    raise TypeError(f"not a test case or suite: {test!r}")


# ------------------------------------------------------------------ summaries


def _names(problems: list[tuple[unittest.TestCase, str]]) -> str:
    return ", ".join(getattr(t, "_testMethodName", None) or str(t) for t, _ in problems)


def unittest_summary(result: unittest.TestResult) -> str:
    """rosunit's print_unittest_summary text (what a test node prints when its suite is done)."""
    lines = ["-------------------------------------------------------------", "SUMMARY:"]
    lines.append(f"{GREEN} * RESULT: SUCCESS{RESET}" if result.wasSuccessful() else " * RESULT: FAIL")
    lines.append(f" * TESTS: {result.testsRun}")
    lines.append(f" * ERRORS: {len(result.errors)} [{_names(result.errors)}]")
    lines.append(f" * FAILURES: {len(result.failures)} [{_names(result.failures)}]")
    return "\n".join(lines) + "\n"


def runner_summary(runner: unittest.TestResult, junit: Result, runner_name: str = "ROSTEST") -> str:
    """rosunit's print_runner_summary text: each case of the test nodes, then the totals."""
    out = f"[{runner_name}]" + "-" * 71 + "\n\n"
    out += "".join(case.description for case in junit.cases)
    failed_to_run = [getattr(t, "_testMethodName", str(t)) for t, _ in runner.failures]
    out += "".join(f"[{name}][failed]\n" for name in failed_to_run)
    out += "\nSUMMARY\n"
    ok = runner.wasSuccessful() and junit.num_errors + junit.num_failures == 0
    out += f"{GREEN} * RESULT: SUCCESS{RESET}\n" if ok else f"{RED} * RESULT: FAIL{RESET}\n"
    out += f" * TESTS: {junit.num_tests}\n"
    errors = junit.num_errors + len(runner.errors)
    out += f"{RED} * ERRORS: {errors}{RESET}\n" if errors else " * ERRORS: 0\n"
    failures = junit.num_failures + len(runner.failures)
    out += f"{RED} * FAILURES: {failures}{RESET}\n" if failures else " * FAILURES: 0\n"
    if failed_to_run:
        out += "\nERROR: The following tests failed to run:\n" + "".join(f" * {n}\n" for n in failed_to_run)
    return out


def print_text(text: str, stream: TextIO | None = None) -> None:
    print(text, file=stream or sys.stdout, flush=True)
