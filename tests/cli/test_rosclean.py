"""rosclean end to end: the installed console script on a temporary ROS_HOME, beside Debian's
real one (same sizes, prompts and removals)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

BIN = Path(sys.executable).parent
REAL = "/usr/bin/rosclean"

Result = subprocess.CompletedProcess[str]


def env_for(home: Path, **extra: str) -> dict[str, str]:
    env = {k: v for k, v in os.environ.items() if not k.startswith("ROS_")}
    env["ROS_HOME"] = str(home)
    env.update(extra)
    return env


def run(home: Path, *args: str, input: str = "", exe: str | None = None, **extra: str) -> Result:
    return subprocess.run([exe or str(BIN / "rosclean"), *args], env=env_for(home, **extra), capture_output=True,
                          text=True, input=input, timeout=30)


def fill(home: Path) -> None:
    run_dir = home / "log" / "0123-run"
    run_dir.mkdir(parents=True, exist_ok=True)
    (run_dir / "master.log").write_bytes(os.urandom(300_000))
    (run_dir / "rosout.log").write_text("x" * 5000)
    (home / "log" / "latest").unlink(missing_ok=True)
    (home / "log" / "latest").symlink_to(run_dir)
    (home / "rosmake").mkdir(exist_ok=True)


def test_check_and_purge(tmp_path: Path) -> None:
    home = tmp_path / "ros"
    assert run(home, "check").stdout == ""  # nothing when there are no logs
    fill(home)
    du = [subprocess.run(["du", "-sh", str(d)], capture_output=True, text=True).stdout.split()[0]
          for d in (home / "log", home / "rosmake")]
    assert run(home, "check").stdout == f"{du[0]} ROS node logs\n{du[1]} rosmake logs\n"
    asked = run(home, "purge", input="n\nn\n")
    assert asked.stdout == (
        "Purging ROS node logs.\nPLEASE BE CAREFUL TO VERIFY THE COMMAND BELOW!\nOkay to perform:\n\n"
        f"rm -rf {home / 'log'}\n(y/n)?\n"
        "Purging rosmake logs.\nPLEASE BE CAREFUL TO VERIFY THE COMMAND BELOW!\nOkay to perform:\n\n"
        f"rm -rf {home / 'rosmake'}\n(y/n)?\n")
    assert (home / "log").is_dir()
    run(home, "purge", input="maybe\ny\nn\n")
    assert not (home / "log").exists() and (home / "rosmake").exists()
    fill(home)
    assert run(home, "purge", "-y").stdout == "Purging ROS node logs.\nPurging rosmake logs.\n"
    assert not (home / "log").exists() and not (home / "rosmake").exists()


def test_end_of_input_answers_no(tmp_path: Path) -> None:
    fill(tmp_path)
    result = run(tmp_path, "purge", input="")
    assert result.returncode == 0 and (tmp_path / "log").is_dir()


def test_ros_log_dir_and_size(tmp_path: Path) -> None:
    logs = tmp_path / "elsewhere"
    old, new = logs / "old-run", logs / "new-run"
    for folder in (old, new):
        folder.mkdir(parents=True)
        (folder / "a.log").write_bytes(b"x" * 700_000)
    os.utime(old, (1_000_000, 1_000_000))
    home = tmp_path / "home"
    assert run(home, "check", ROS_LOG_DIR=str(logs)).stdout.endswith(" ROS node logs\n")
    below = run(home, "purge", "--size", "5", ROS_LOG_DIR=str(logs))
    assert below.stdout == ("Directory size of ROS node logs is 1 MB which is already below the requested "
                            "threshold of 5 MB.\n")
    cut = run(home, "purge", "-y", "--size", "1", ROS_LOG_DIR=str(logs))
    assert cut.stdout == "Purging ROS node logs until directory size is at most 1 MB (currently 1 MB).\n"
    assert not old.exists() and new.exists()


def test_usage(tmp_path: Path) -> None:
    bare = run(tmp_path)
    assert (bare.returncode, bare.stderr) == (
        2, "usage: rosclean [-h] {check,purge} ...\n"
           "rosclean: error: the following arguments are required: {check,purge}\n")


@pytest.mark.skipif(not os.path.exists(REAL), reason="Debian's rosclean is not installed")
def test_same_as_real_rosclean(tmp_path: Path) -> None:
    home = tmp_path / "ros"
    fill(home)
    for args, answers in ((("check",), ""), (("purge",), "n\nn\n"), (("purge", "--size", "1"), ""), (("-h",), ""),
                          (("purge", "-h"), ""), (("bogus",), ""), ((), "")):
        ours, theirs = run(home, *args, input=answers), run(home, *args, input=answers, exe=REAL)
        assert (ours.returncode, ours.stdout, ours.stderr) == (theirs.returncode, theirs.stdout, theirs.stderr), args
    ours = run(home, "purge", "-y")
    assert not (home / "log").exists()
    fill(home)
    theirs = run(home, "purge", "-y", exe=REAL)
    assert not (home / "log").exists()
    assert ours.stdout == theirs.stdout
