"""run_command: a child run to its end with its output, or killed by its PID on the deadline."""

from __future__ import annotations

import sys

from kame.net.command import run_command


def test_output_and_status_of_a_child_that_ends() -> None:
    result = run_command([sys.executable, "-c", "import sys; print('out'); print('err', file=sys.stderr); sys.exit(3)"])
    assert result.returncode == 3
    assert "out" in result.output and "err" in result.output


def test_a_child_that_aborts_is_reported_not_fatal() -> None:
    result = run_command([sys.executable, "-c", "import os; print('before', flush=True); os.abort()"])
    assert result.returncode == -6  # SIGABRT ended the child, not us
    assert "before" in result.output


def test_a_child_past_its_deadline_is_killed() -> None:
    result = run_command([sys.executable, "-c", "print('started', flush=True); import time; time.sleep(60)"],
                         timeout=2.0)
    assert result.returncode is None
    assert "started" in result.output
