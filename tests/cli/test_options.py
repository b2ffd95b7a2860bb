"""kame.cli._options.OptionParser: argparse that prints and collects as optparse does, held
against the standard library's optparse with the same options."""

from __future__ import annotations

import contextlib
import io
import optparse
from typing import Any

import pytest

from kame.cli._options import OptionParser

OPTIONS: list[tuple[tuple[str, ...], dict[str, Any]]] = [
    (("-b", "--bag"), {"dest": "bag", "default": None, "help": "echo messages from .bag file", "metavar": "BAGFILE"}),
    (("-p",), {"dest": "plot", "default": False, "action": "store_true", "help": "echo in a plotting friendly format"}),
    (("--filter",), {"dest": "filter_expr", "default": None, "metavar": "FILTER-EXPRESSION",
                     "help": "Python expression to filter messages that are printed. Expression can use Python "
                             "builtins as well as m (the message) and topic (the topic name)."}),
    (("-c", "--clear"), {"dest": "clear", "default": False, "action": "store_true", "help": "clear screen"}),
    (("-n",), {"dest": "msg_count", "default": None, "metavar": "COUNT", "help": "number of messages to echo"}),
    (("-r", "--rate"), {"dest": "rate", "default": None, "type": float, "help": "rate"}),
    (("-1", "--once"), {"dest": "once", "default": False, "action": "store_true", "help": "publish one message"}),
    (("-w", "--window"), {"dest": "window_size", "default": -1, "help": "window size, in # of messages"}),
    (("--verbose",), {"dest": "verbose", "default": False, "action": "store_true"}),
    (("--version2",), {"dest": "v2", "default": False, "action": "store_true", "help": "v"}),
]


def parse(kind: str, argv: list[str]) -> tuple[Any, str, str, Any]:
    usage = "usage: %prog echo [options] /topic"
    parser: Any = optparse.OptionParser(usage=usage, prog="rostopic") if kind == "optparse" else \
        OptionParser(usage=usage, prog="rostopic")
    add = parser.add_option if kind == "optparse" else parser.add_argument
    for flags, settings in OPTIONS:
        add(*flags, **settings)
    out, err = io.StringIO(), io.StringIO()
    result = status = None
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        try:
            if kind == "optparse":
                values, rest = parser.parse_args(argv)
                result = (rest, vars(values))
            else:
                parsed = parser.parse_args(argv)
                result = (parsed.args, {k: v for k, v in vars(parsed).items() if k != "args"})
        except SystemExit as exc:
            status = exc.code
    return status, out.getvalue(), err.getvalue(), result


@pytest.mark.parametrize("argv", [
    ["-h"], ["-n"], ["--bogus"], ["-x", "/t"], ["/a", "-p", "/b", "-n", "3"], ["-r", "x"], ["--rate"],
    ["--clear=1"], ["--ver"], ["/t", "--", "-5", "-p"], ["-n5", "--bag=f.bag", "/t"], ["-5"], ["-1", "/x"],
    ["--window", "3", "a"], ["-p", "x", "y", "-c"], ["--verb", "-r", "2.5", "t"],
])
def test_same_as_optparse(argv: list[str], monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("COLUMNS", raising=False)
    assert parse("argparse", argv) == parse("optparse", argv)


def test_error_shows_usage_and_the_tools_words(capsys: pytest.CaptureFixture[str]) -> None:
    parser = OptionParser("usage: %prog echo [options] /topic", prog="rostopic")
    with pytest.raises(SystemExit) as exited:
        parser.error("topic must be specified")
    assert exited.value.code == 2
    assert capsys.readouterr().err == ("Usage: rostopic echo [options] /topic\n\n"
                                       "rostopic: error: topic must be specified\n")


def test_an_option_taking_the_words_after_it_is_optparses_list_callback(monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.delenv("COLUMNS", raising=False)

    def take_list(option: Any, opt_str: str, value: Any, parser: optparse.OptionParser) -> None:
        taken = []
        for arg in parser.rargs:
            if arg.startswith("-") and len(arg) > 1:
                break
            taken.append(arg)
        del parser.rargs[:len(taken)]
        getattr(parser.values, option.dest).extend(taken)

    old = optparse.OptionParser(usage="rosbag play BAGFILE1 [BAGFILE2 ...]", prog="rosbag")
    old.add_option("--topics", dest="topics", default=[], callback=take_list, action="callback", help="topics")
    old.add_option("-q", dest="quiet", default=False, action="store_true", help="quiet")
    new = OptionParser(usage="rosbag play BAGFILE1 [BAGFILE2 ...]", prog="rosbag")
    new.add_argument("--topics", dest="topics", default=[], nargs="*", action="extend", help="topics")
    new.add_argument("-q", dest="quiet", default=False, action="store_true", help="quiet")
    assert new.format_help() == old.format_help()
    argv = ["a.bag", "--topics", "/x", "/y", "-q", "b.bag", "--topics", "/z"]
    values, rest = old.parse_args(list(argv))
    parsed = new.parse_args(argv)
    assert (parsed.args, parsed.topics, parsed.quiet) == (rest, values.topics, values.quiet)
