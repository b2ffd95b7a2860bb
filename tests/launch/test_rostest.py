"""rostest end to end: rospy unittest nodes in a temporary package, run by `rostest` in a graph of
their own; exit statuses, the JUnit XML files, the printed summary, time limits, nothing left behind.
Compared with Debian's rostest where it is installed."""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import time
import xml.etree.ElementTree as ET
import xmlrpc.client
from pathlib import Path

import pytest

from tests.support import SYSTEM_PYTHON, Proc, free_port, kame_command, ros_env, running, wait_for_master

PACKAGE_XML = """<package format="2"><name>demo</name><version>0.0.1</version><description>d</description>
<maintainer email="a@b.c">a</maintainer><license>BSD</license></package>"""

PASS_TEST = """#!/usr/bin/env python3
import unittest
import rospy
import rostest
from std_msgs.msg import String

class ChatterCase(unittest.TestCase):
    def test_param(self):
        self.assertEqual(rospy.get_param("/answer"), 42)
        self.assertEqual(rospy.get_param("~mode"), "fast")

    def test_chatter(self):
        msg = rospy.wait_for_message("/chatter", String, timeout=10)
        self.assertTrue(msg.data.startswith("hello world"))
        self.assertTrue(rostest.is_publisher("/chatter", "/talker"))
        code, _, state = rostest.get_master().getSystemState("/pass_test")
        self.assertEqual(code, 1)
        self.assertIn(["/chatter", ["/talker"]], state[0])

if __name__ == "__main__":
    rospy.init_node("pass_test")
    rostest.rosrun("demo", "pass_test", ChatterCase)
"""

FAIL_TEST = """#!/usr/bin/env python3
import unittest
import rospy
import rostest

class BadCase(unittest.TestCase):
    def test_fails(self):
        self.assertEqual(1, 2, "one is not two")

    def test_ok(self):
        pass

    def test_error(self):
        raise ValueError("boom")

if __name__ == "__main__":
    rospy.init_node("fail_test")
    rostest.rosrun("demo", "fail_test", BadCase)
"""

SLOW_TEST = """#!/usr/bin/env python3
import os, sys, time
with open(os.environ["PID_FILE"], "w") as f:
    f.write(str(os.getpid()))
time.sleep(60)
"""

FLAKY_TEST = """#!/usr/bin/env python3
# Fails on its first run, passes on the second (counted in $FLAKY_FILE).
import os, unittest, rostest
path = os.environ["FLAKY_FILE"]
runs = int(open(path).read()) if os.path.exists(path) else 0
open(path, "w").write(str(runs + 1))

class FlakyCase(unittest.TestCase):
    def test_second_time(self):
        self.assertGreater(runs, 0)

if __name__ == "__main__":
    rostest.rosrun("demo", "flaky", FlakyCase)
"""

UNIT_TEST = """#!/usr/bin/env python3
import unittest, rostest

class Offline(unittest.TestCase):
    def test_math(self):
        self.assertEqual(2 + 2, 4)

if __name__ == "__main__":
    rostest.unitrun("demo", "offline", Offline)
"""

FILES = {
    "test/pass.test": """<launch>
  <arg name="mode" default="slow"/>
  <param name="answer" value="42"/>
  <node name="talker" pkg="rospy_tutorials" type="talker"/>
  <test test-name="pass_test" pkg="demo" type="pass_test.py" time-limit="20">
    <param name="mode" value="$(arg mode)"/>
  </test>
</launch>""",
    "test/fail.test": """<launch>
  <param name="answer" value="42"/>
  <test test-name="fail_test" pkg="demo" type="fail_test.py"/>
  <test test-name="missing" pkg="demo" type="nonexistent.py"/>
</launch>""",
    "test/slow.test": """<launch>
  <test test-name="slow_test" pkg="demo" type="slow_test.py" time-limit="1"/>
</launch>""",
    "launch/flaky.launch": """<launch>
  <test test-name="flaky" pkg="demo" type="flaky_test.py" retry="1"/>
</launch>""",
}
SCRIPTS = {"pass_test.py": PASS_TEST, "fail_test.py": FAIL_TEST, "slow_test.py": SLOW_TEST,
           "flaky_test.py": FLAKY_TEST, "unit_test.py": UNIT_TEST}


@pytest.fixture
def workspace(tmp_path: Path) -> Path:
    pkg = tmp_path / "ws" / "demo"
    for rel, text in FILES.items():
        (pkg / rel).parent.mkdir(parents=True, exist_ok=True)
        (pkg / rel).write_text(text)
    (pkg / "package.xml").write_text(PACKAGE_XML)
    (pkg / "scripts").mkdir()
    for name, text in SCRIPTS.items():
        script = pkg / "scripts" / name
        script.write_text(text)
        script.chmod(0o755)
    return tmp_path


def make_env(workspace: Path) -> dict[str, str]:
    env = ros_env(workspace / "home")
    env.update(ROS_PACKAGE_PATH=str(workspace / "ws"), PID_FILE=str(workspace / "slow.pid"),
               FLAKY_FILE=str(workspace / "flaky.count"))
    return env


def rostest(env: dict[str, str], *args: str, timeout: float = 60) -> subprocess.CompletedProcess[str]:
    return subprocess.run(kame_command("kame.cli.rostest", *args), env=env, capture_output=True, text=True,
                          timeout=timeout)


def results(workspace: Path, name: str) -> ET.Element:
    return ET.parse(workspace / "home" / "test_results" / "demo" / name).getroot()


def started_pids(root: ET.Element) -> list[int]:
    text = root.findtext("system-out") or ""
    return [int(p) for p in re.findall(r"started with pid \[(\d+)\]", text)]


def gone(pid: int) -> bool:
    try:
        with open(f"/proc/{pid}/stat") as f:
            return f.read().rsplit(")", 1)[1].split()[0] == "Z"
    except FileNotFoundError:
        return True


def test_passing_test_node_in_its_own_graph(workspace: Path) -> None:
    env = make_env(workspace)
    done = rostest(env, "demo", "pass.test", "mode:=fast")
    assert done.returncode == 0, done.stdout + done.stderr
    out = done.stdout
    results_dir = workspace / "home" / "test_results" / "demo"
    assert f"[ROSUNIT] Outputting test results to {results_dir / 'rostest-test_pass.xml'}\n" in out
    assert "[Testcase: testpass_test] ... ok\n" in out
    assert ("[ROSTEST]" + "-" * 71 + "\n\n[demo.rosunit-pass_test/test_chatter][passed]\n"
            "[demo.rosunit-pass_test/test_param][passed]\n\nSUMMARY\n\033[32m * RESULT: SUCCESS\033[0m\n"
            " * TESTS: 2\n * ERRORS: 0\n * FAILURES: 0\n") in out
    assert re.search(r"^\.\.\. logging to .*/home/log/rostest-.*\.log$", out, re.M)
    assert "rostest log file is in" in out
    run = results(workspace, "rostest-test_pass.xml")
    assert (run.get("name"), run.get("tests"), run.get("errors"), run.get("failures")) == (
        "unittest.suite.TestSuite", "1", "0", "0")
    case = run.find("testcase")
    assert case is not None and (case.get("classname"), case.get("name")) == ("rostest.runner.RosTest",
                                                                              "testpass_test")
    system_out = run.findtext("system-out") or ""
    assert system_out.startswith("<![CDATA[\n[ROSTEST]setup[")  # rosunit's CDATA, escaped as it writes it
    assert "process[talker-1]: started with pid" in system_out and "process[pass_test-2]" in system_out
    master = re.search(r"ROS_MASTER_URI=(http://[^/]+:(\d+)/)", system_out)
    assert master is not None and master.group(2) != "11311"  # a private master on a free port
    unit = results(workspace, "rosunit-pass_test.xml")
    assert [(c.get("classname"), c.get("name")) for c in unit.iter("testcase")] == [
        ("__main__.ChatterCase", "test_chatter"), ("__main__.ChatterCase", "test_param")]
    pids = started_pids(run)
    assert len(pids) == 2 and all(gone(p) for p in pids)


def test_failing_and_missing_tests(workspace: Path) -> None:
    env = make_env(workspace)
    done = rostest(env, str(workspace / "ws" / "demo" / "test" / "fail.test"))
    assert done.returncode == 1, done.stdout + done.stderr  # a test that could not run outranks failures
    out = done.stdout
    assert "[Testcase: testfail_test] ... ok\n" in out
    assert "[Testcase: testmissing] ... FAILURE!\nFAILURE: Test node [demo/nonexistent.py] does not exist" in out
    assert "[demo.rosunit-fail_test/test_error][ERROR]" + "-" * 38 + "\nboom\n" in out
    assert "[demo.rosunit-fail_test/test_fails][FAILURE]" + "-" * 36 + "\n1 != 2 : one is not two\n" in out
    assert "[demo.rosunit-fail_test/test_ok][passed]\n[testmissing][failed]\n" in out
    assert ("\033[1;31m * RESULT: FAIL\033[0m\n * TESTS: 3\n\033[1;31m * ERRORS: 1\033[0m\n"
            "\033[1;31m * FAILURES: 2\033[0m\n\nERROR: The following tests failed to run:\n * testmissing\n") in out
    unit = results(workspace, "rosunit-fail_test.xml")
    assert (unit.get("tests"), unit.get("errors"), unit.get("failures")) == ("3", "1", "1")
    failure = unit.find("testcase[@name='test_fails']/failure")
    assert failure is not None and failure.get("type") == "AssertionError"
    run = results(workspace, "rostest-test_fail.xml")
    assert (run.get("tests"), run.get("failures")) == ("2", "1")
    assert all(gone(p) for p in started_pids(run))


def test_failures_only_exit_2(workspace: Path) -> None:
    test_file = workspace / "ws" / "demo" / "test" / "fail.test"
    test_file.write_text(test_file.read_text().replace('<test test-name="missing" pkg="demo" '
                                                       'type="nonexistent.py"/>', ""))
    env = make_env(workspace)
    env["ROS_TEST_RESULTS_DIR"] = str(workspace / "elsewhere")
    done = rostest(env, "demo", "fail.test")
    assert done.returncode == 2, done.stdout + done.stderr
    assert (workspace / "elsewhere" / "demo" / "rostest-test_fail.xml").is_file()
    assert (workspace / "elsewhere" / "demo" / "rosunit-fail_test.xml").is_file()


def test_time_limit_overrun(workspace: Path) -> None:
    # 3 s, not 1 s: the test program must have started and written its PID before it is stopped
    test_file = workspace / "ws" / "demo" / "test" / "slow.test"
    test_file.write_text(test_file.read_text().replace('time-limit="1"', 'time-limit="3"'))
    env = make_env(workspace)
    started = time.monotonic()
    done = rostest(env, "demo", "slow.test")
    elapsed = time.monotonic() - started
    assert done.returncode == 1, done.stdout + done.stderr
    assert elapsed < 15
    assert "[Testcase: testslow_test] ... ERROR!\nERROR: max time [3.0s] allotted for test [slow_test] of type " \
           "[demo/slow_test.py]\n" in done.stdout
    assert " * TESTS: 0\n\033[1;31m * ERRORS: 1\033[0m\n * FAILURES: 0\n" in done.stdout
    run = results(workspace, "rostest-test_slow.xml")
    error = run.find("testcase/error")
    assert error is not None and error.get("type") == "RLTestTimeoutException"
    assert gone(int((workspace / "slow.pid").read_text()))


def test_retry_and_launch_file(workspace: Path) -> None:
    env = make_env(workspace)
    done = rostest(env, "demo", "flaky.launch")
    assert done.returncode == 0, done.stdout + done.stderr
    assert (workspace / "flaky.count").read_text() == "2"
    system_out = results(workspace, "rostest-launch_flaky.xml").findtext("system-out") or ""
    assert "[ROSTEST]test [flaky] failed, retrying. Retries left: 0" in system_out
    assert "[demo.rosunit-flaky/test_second_time][passed]" in done.stdout


def test_text_mode_shows_output_and_fails(workspace: Path) -> None:
    env = make_env(workspace)
    done = rostest(env, "--text", "demo", "fail.test")
    assert done.returncode == 1
    assert "FAIL: test_fails" in done.stderr and "one is not two" in done.stderr  # the node's unittest output
    assert "testfail_test (rostest.runner.RosTest" in done.stderr
    assert "test [fail_test] exited with status 1" in done.stderr  # kame's: the real rostest reports ok here
    assert "WARNING: overall test result is not accurate when --text is enabled" in done.stdout


def test_rostest_errors(workspace: Path) -> None:
    env = make_env(workspace)
    done = rostest(env, "demo", "nope.test")
    assert done.returncode == 1
    assert "[nope.test] is neither a launch file in package [demo] nor is [demo] a launch file name" in done.stderr
    done = rostest(env, "--clear", "demo", "pass.test")
    assert done.returncode == 1 and "The --clear option is only valid with --reuse-master" in done.stderr


def test_unitrun_without_rostest(workspace: Path) -> None:
    env = make_env(workspace)
    script = workspace / "ws" / "demo" / "scripts" / "unit_test.py"
    done = subprocess.run([sys.executable, str(script)], env=env, capture_output=True, text=True, timeout=30)
    assert done.returncode == 0, done.stdout + done.stderr
    path = workspace / "home" / "test_results" / "demo" / "rosunit-offline.xml"
    assert f"[ROSUNIT] Outputting test results to {path}" in done.stdout
    assert "[Testcase: test_math] ... ok" in done.stdout
    assert "SUMMARY:\n\033[32m * RESULT: SUCCESS\033[0m\n * TESTS: 1\n * ERRORS: 0 []\n * FAILURES: 0 []" in done.stdout
    assert ET.parse(path).getroot().get("tests") == "1"


def _summary(text: str) -> str:
    """From the [ROSTEST] line up to the log file line, without tracebacks."""
    block = text[text.index("[ROSTEST]---"): text.index("rostest log file")]
    return "\n".join(line for line in block.splitlines() if not line.startswith(" "))


@pytest.mark.skipif(not (os.path.exists("/usr/bin/rostest") and os.path.exists(SYSTEM_PYTHON)),
                    reason="Debian's rostest is not installed")
def test_same_summary_and_files_as_debian_rostest(workspace: Path) -> None:
    test_file = workspace / "ws" / "demo" / "test" / "fail.test"
    test_file.write_text(test_file.read_text().replace("nonexistent.py", "fail_test.py"))
    env = make_env(workspace)
    env["PATH"] = "/usr/bin:" + env.get("PATH", "")  # the scripts' `env python3` must find Debian's rospy there
    theirs = subprocess.run([SYSTEM_PYTHON, "/usr/bin/rostest", "demo", "fail.test"], env=env,
                            capture_output=True, text=True, timeout=60)
    their_files = sorted(p.name for p in (workspace / "home" / "test_results" / "demo").iterdir())
    shutil.rmtree(workspace / "home" / "test_results")
    ours = rostest(env, "demo", "fail.test")
    assert ours.returncode == theirs.returncode, theirs.stdout + theirs.stderr
    assert _summary(ours.stdout) == _summary(theirs.stdout)
    assert sorted(p.name for p in (workspace / "home" / "test_results" / "demo").iterdir()) == their_files


def test_reuse_master_with_clear(workspace: Path) -> None:
    port = free_port()
    env = make_env(workspace)
    env["ROS_MASTER_URI"] = f"http://127.0.0.1:{port}"
    with running(kame_command("kame.cli.roscore", "-p", str(port)), env) as core:
        wait_for_master(env["ROS_MASTER_URI"], proc=core)
        master = xmlrpc.client.ServerProxy(env["ROS_MASTER_URI"])
        master.setParam("/t", "/junk", 1)
        done = rostest(env, "--reuse-master", "--clear", "demo", "pass.test", "mode:=fast")
        assert done.returncode == 0, done.stdout + done.stderr
        names = master.getParamNames("/t")[2]
        assert "/junk" not in names and "/answer" in names  # cleared, then the launch's parameters set there
    system_out = results(workspace, "rostest-test_pass.xml").findtext("system-out") or ""
    assert f"ROS_MASTER_URI=http://127.0.0.1:{port}" in system_out


def test_ctrl_c_stops_every_process(workspace: Path) -> None:
    test_file = workspace / "ws" / "demo" / "test" / "slow.test"
    test_file.write_text(test_file.read_text().replace('time-limit="1"', 'time-limit="60"'))
    env = make_env(workspace)
    proc = Proc(kame_command("kame.cli.rostest", "demo", "slow.test"), env)
    try:
        pid_file = workspace / "slow.pid"
        deadline = time.monotonic() + 20
        while not (pid_file.exists() and pid_file.read_text()):
            assert time.monotonic() < deadline and proc.popen.poll() is None, proc.stop()
            time.sleep(0.05)
        pid = int(pid_file.read_text())
    finally:
        out, err = proc.stop(timeout=20)
    assert proc.popen.returncode == 1, out + err
    assert "rostest: interrupted, every process stopped" in err
    assert gone(pid)


def test_rosunit_unitrun_failure_and_output_flag(workspace: Path) -> None:
    script = workspace / "failing_unit.py"
    script.write_text("import unittest, rosunit\n"
                      "class Case(unittest.TestCase):\n"
                      "    def test_bad(self):\n"
                      "        self.assertTrue(False, 'nope')\n"
                      "rosunit.unitrun('demo', 'failing', Case)\n")
    out_file = workspace / "out" / "result.xml"
    done = subprocess.run([sys.executable, str(script), f"--gtest_output=xml:{out_file}"], env=make_env(workspace),
                          capture_output=True, text=True, timeout=30)
    assert done.returncode == 1, done.stdout + done.stderr
    assert "[Testcase: test_bad] ... FAILURE!\nFAILURE: False is not true : nope\n" in done.stdout
    assert " * RESULT: FAIL\n * TESTS: 1\n * ERRORS: 0 []\n * FAILURES: 1 [test_bad]" in done.stdout
    root = ET.parse(out_file).getroot()
    assert (root.get("tests"), root.get("failures")) == ("1", "1")
