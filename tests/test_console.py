"""roscpp's console line (kame.console) as the ports of C++ programs print it: rosconsole's
default format, each line wrapped in its severity's colour to a terminal or not, NO_COLOR off."""

from __future__ import annotations

import pytest

from kame.cli._console import console
from kame.console import roscpp_colour, roscpp_line

STAMP = 1795311549_578038800


@pytest.mark.parametrize(("severity", "colour"), [("DEBUG", "\033[32m"), ("INFO", "\033[0m"), ("WARN", "\033[33m"),
                                                  ("ERROR", "\033[31m"), ("FATAL", "\033[31m")])
def test_a_line_is_rosconsoles_default_format_in_its_severitys_colour(severity: str, colour: str) -> None:
    plain = f"[{severity:>5}] [1795311549.578038800]: Subscribing to /chatter"
    assert roscpp_line(severity, "Subscribing to /chatter", STAMP, colour=True) == f"{colour}{plain}\033[0m"
    assert roscpp_line(severity, "Subscribing to /chatter", STAMP, colour=False) == plain


def test_the_nanoseconds_keep_their_leading_zeros() -> None:
    assert roscpp_line("INFO", "x", 12_000_000_007, colour=False) == "[ INFO] [12.000000007]: x"


def test_no_color_set_to_anything_turns_the_colours_off() -> None:
    assert roscpp_colour({}) and roscpp_colour({"TERM": "dumb"})
    assert not roscpp_colour({"NO_COLOR": ""}) and not roscpp_colour({"NO_COLOR": "1"})


def test_a_tool_writes_info_to_stdout_and_the_rest_to_stderr(capsys: pytest.CaptureFixture[str],
                                                             monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("NO_COLOR", raising=False)
    console("INFO", "Opening a.bag")
    console("FATAL", "Error opening file: a.bag")
    out, err = capsys.readouterr()
    assert out.startswith("\033[0m[ INFO] [") and out.endswith("]: Opening a.bag\033[0m\n")
    assert err.startswith("\033[31m[FATAL] [") and err.endswith("]: Error opening file: a.bag\033[0m\n")
    monkeypatch.setenv("NO_COLOR", "1")
    console("WARN", "plain")
    assert capsys.readouterr().err.startswith("[ WARN] [")
