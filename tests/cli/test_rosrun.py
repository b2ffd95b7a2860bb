"""rosrun end to end: the installed console script on a temporary workspace, as a user types it;
the messages and statuses side by side with Debian's real rosrun (a bash script) where both
see the same package; and the rospy tutorial talker run from kame's own rospy_tutorials.
"""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

from tests.support import Proc, free_port, ros_env, wait_for_master

BIN = Path(sys.executable).parent
# The interpreter rosrun itself runs on (its script's shebang): python and python3 in a venv
# are the same interpreter under two names, and pytest may have been started by either.
KAME_PY = (BIN / "rosrun").read_text().splitlines()[0].removeprefix("#!").strip()
REAL_ROSRUN = "/usr/bin/rosrun"

Result = subprocess.CompletedProcess[str]

SHOW = """#!/usr/bin/env python3
import os, sys
print("ran", sys.executable, sys.argv[1:], os.getpid(), flush=True)
"""


def make_exe(path: Path, text: str, mode: int = 0o755) -> Path:
    path.parent.mkdir(parents=True, exist_ok=True)
    path.write_text(text)
    path.chmod(mode)
    return path


@pytest.fixture(scope="module")
def ws(tmp_path_factory: pytest.TempPathFactory) -> Path:
    src = tmp_path_factory.mktemp("rosrun") / "src"
    pkg = src / "runpkg"
    pkg.mkdir(parents=True)
    (pkg / "package.xml").write_text('<package format="2"><name>runpkg</name><version>0.1.0</version></package>')
    make_exe(pkg / "scripts" / "show", SHOW)
    make_exe(pkg / "scripts" / "plain.py", "import sys\nprint('plain', sys.argv[1:])\n", 0o644)
    make_exe(pkg / "scripts" / "data.txt", "x\n", 0o644)
    make_exe(pkg / "scripts" / "twice", "#!/bin/sh\necho scripts-twice\n")
    make_exe(pkg / "nodes" / "twice", "#!/bin/sh\necho nodes-twice\n")
    make_exe(pkg / "build" / "built", "#!/bin/sh\necho built\n")
    make_exe(pkg / "nodes" / "shell_no_shebang", 'echo no-shebang "$@"\n')
    return src


def env_for(ws: Path, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_") and k != "CMAKE_PREFIX_PATH"}
    env["ROS_PACKAGE_PATH"] = str(ws)
    env.update(extra)
    return env


def rosrun(ws: Path, *args: str, input: str = "", exe: str | None = None, **extra: str) -> Result:
    return subprocess.run([exe or str(BIN / "rosrun"), *args], env=env_for(ws, **extra), capture_output=True,
                          text=True, input=input, timeout=30)


def test_runs_with_args_in_the_same_process(ws: Path) -> None:
    proc = subprocess.Popen([str(BIN / "rosrun"), "runpkg", "show", "a", "b c", "__name:=x", "_p:=1"],
                            env=env_for(ws), stdout=subprocess.PIPE, text=True)
    out, _ = proc.communicate(timeout=30)
    # python scripts run with kame's interpreter, whatever their shebang; exec keeps the PID
    assert out == f"ran {KAME_PY} ['a', 'b c', '__name:=x', '_p:=1'] {proc.pid}\n"
    assert proc.returncode == 0


def test_paths_prefix_and_shell_scripts(ws: Path) -> None:
    assert rosrun(ws, "runpkg", "scripts/show", "1").stdout.startswith(f"ran {KAME_PY} ['1'] ")
    prefixed = rosrun(ws, "--prefix", "echo PFX", "runpkg", "show", "z")
    assert prefixed.stdout == f"PFX {KAME_PY} {ws / 'runpkg/scripts/show'} z\n"
    assert rosrun(ws, "runpkg", "shell_no_shebang", "q").stdout == "no-shebang q\n"


def test_non_executable_python_file_runs_with_a_note(ws: Path) -> None:
    result = rosrun(ws, "runpkg", "plain.py", "x")
    assert (result.returncode, result.stdout) == (0, "plain ['x']\n")
    assert "not executable" in result.stderr and "chmod +x" in result.stderr


def test_errors(ws: Path) -> None:
    missing = rosrun(ws, "runpkg", "nope")
    assert (missing.returncode, missing.stdout) == (3, f"[rosrun] Couldn't find executable named nope below "
                                                       f"{ws / 'runpkg'}\n")
    data = rosrun(ws, "runpkg", "data.txt")
    assert data.returncode == 3
    assert data.stdout.splitlines()[1:] == ["[rosrun] Found the following, but they're either not files,",
                                            "[rosrun] or not executable:",
                                            f"[rosrun]   {ws / 'runpkg/scripts/data.txt'}"]
    assert rosrun(ws, "runpkg", "built").returncode == 3  # build/ is not searched
    unknown = rosrun(ws, "nopkg", "x")
    assert (unknown.returncode, unknown.stdout, unknown.stderr) == (
        2, "", "[rospack] Error: package 'nopkg' not found\n")
    usage = rosrun(ws, "runpkg")
    assert (usage.returncode, usage.stdout.splitlines()[0]) == (
        0, "Usage: rosrun [--prefix cmd] [--debug] PACKAGE EXECUTABLE [ARGS]")
    assert rosrun(ws, "runpkg", "dir/").stdout == "Invalid filename:  dir/\n"


def test_non_unique_menu(ws: Path) -> None:
    result = rosrun(ws, "runpkg", "twice", input="2\n")
    assert result.stdout == ("[rosrun] You have chosen a non-unique executable, please pick one of the following:\n"
                             "scripts-twice\n")
    assert result.stderr == f"1) {ws / 'runpkg/nodes/twice'}\n2) {ws / 'runpkg/scripts/twice'}\n#? "


def test_catkin_devel_relay_wins(ws: Path, tmp_path: Path) -> None:
    devel = tmp_path / "devel"
    (devel / "lib" / "runpkg").mkdir(parents=True)
    (devel / ".catkin").write_text(str(ws))
    make_exe(devel / "lib" / "runpkg" / "show", "#!/bin/sh\necho relay \"$@\"\n")
    result = rosrun(ws, "runpkg", "show", "1", CMAKE_PREFIX_PATH=str(devel))
    assert result.stdout == "relay 1\n"


def test_entry_points(ws: Path, tmp_path: Path) -> None:
    site = tmp_path / "site"
    (site / "epdemo").mkdir(parents=True)
    (site / "epdemo" / "__init__.py").write_text("")
    (site / "epdemo" / "cli.py").write_text("import sys\ndef main():\n    print('ep', sys.argv)\n    return 4\n")
    dist = site / "epdemo-0.1.dist-info"
    dist.mkdir()
    (dist / "METADATA").write_text("Metadata-Version: 2.1\nName: epdemo\nVersion: 0.1\n")
    (dist / "entry_points.txt").write_text("[kame.rosrun]\nrunpkg/hello = epdemo.cli:main\n\n"
                                           "[console_scripts]\nepdemo_tool = epdemo.cli:main\n")
    grouped = rosrun(ws, "runpkg", "hello", "x", PYTHONPATH=str(site))
    assert (grouped.returncode, grouped.stdout) == (4, "ep ['hello', 'x']\n")
    script = rosrun(ws, "epdemo", "epdemo_tool", "y", PYTHONPATH=str(site))
    assert (script.returncode, script.stdout, script.stderr) == (4, "ep ['epdemo_tool', 'y']\n", "")


@pytest.mark.skipif(not (os.path.exists(REAL_ROSRUN) and os.path.exists("/usr/bin/rospack")),
                    reason="Debian's rosrun is not installed")
@pytest.mark.parametrize("args", [
    ("runpkg", "nope"), ("runpkg", "data.txt"), ("runpkg", "built"), ("nopkg", "x"), ("runpkg", "scripts/data.txt"),
    ("runpkg",), ("-h",), ("runpkg", "dir/"), ("--prefix", "echo PFX", "runpkg", "shell_no_shebang", "1"),
    ("runpkg", "twice"),
], ids=" ".join)
def test_same_as_real_rosrun(ws: Path, args: tuple[str, ...]) -> None:
    ours, theirs = rosrun(ws, *args, input="1\n"), rosrun(ws, *args, input="1\n", exe=REAL_ROSRUN)
    assert (ours.returncode, ours.stdout, ours.stderr) == (theirs.returncode, theirs.stdout, theirs.stderr)


@pytest.mark.parametrize("exe", ["talker", "talker.py"])  # ros_tutorials installs both names
def test_rospy_tutorials_talker(tmp_path: Path, exe: str) -> None:
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    env = ros_env(tmp_path, uri)
    master = Proc([str(BIN / "rosmaster"), "--core", "-p", str(port)], env)
    try:
        wait_for_master(uri, proc=master)
        talker = Proc([str(BIN / "rosrun"), "rospy_tutorials", exe], env)
        try:
            assert "hello world" in talker.wait_line("hello world", timeout=20)
        finally:
            out, err = talker.stop()
        assert talker.popen.returncode in (0, -2), out + err
    finally:
        master.stop()
