"""The master's per-change log line: the records it makes are the records log.info makes."""

from __future__ import annotations

import logging

import pytest

from kame.master import server

_TIMES = ("created", "msecs", "relativeCreated")
_SOURCE = ("pathname", "filename", "module", "lineno", "funcName")


class _Keep(logging.Handler):
    def __init__(self) -> None:
        super().__init__()
        self.records: list[logging.LogRecord] = []

    def emit(self, record: logging.LogRecord) -> None:
        self.records.append(record)


@pytest.mark.parametrize("srcfile", [None, "keep"])
def test_change_records_equal_log_info_records(monkeypatch: pytest.MonkeyPatch, srcfile: str | None) -> None:
    if srcfile is None:
        monkeypatch.setattr(logging, "_srcfile", None)  # as in the rosmaster process
    keep = _Keep()
    server.log.addHandler(keep)
    level = server.log.level
    server.log.setLevel(logging.DEBUG)  # setLevel, not the attribute: it also clears the logger's cache
    server._change_template.clear()
    try:
        args = ("registerPublisher", ["/n", "/t", "t/T"], [1, "Registered [/n] as publisher of [/t]"])
        server._log_change(*args)
        server._log_change(*args)
        server.log.info(server._CHANGE, *args)
    finally:
        server.log.removeHandler(keep)
        server.log.setLevel(level)
    first, second, stock = keep.records
    # with source lines on, the line is log.info's own, named by where it is called
    skip = _TIMES if srcfile is None else _TIMES + _SOURCE
    if srcfile is not None:
        assert first.funcName == "_log_change"
    formatter = logging.Formatter("%(name)s %(levelname)s %(message)s %(pathname)s %(funcName)s")
    for record in (first, second):
        assert {k: v for k, v in vars(record).items() if k not in skip} == \
            {k: v for k, v in vars(stock).items() if k not in skip}
        assert 0 <= stock.created - record.created < 5
        assert record.msecs == int((record.created - int(record.created)) * 1000)
        if srcfile is None:
            assert formatter.format(record) == formatter.format(stock)
    assert first is not second and first.args is not None


@pytest.mark.parametrize("srcfile", [None, "keep"])
def test_no_change_record_when_info_is_off(monkeypatch: pytest.MonkeyPatch, srcfile: str | None) -> None:
    if srcfile is None:
        monkeypatch.setattr(logging, "_srcfile", None)
    keep = _Keep()
    server.log.addHandler(keep)
    level = server.log.level
    server.log.setLevel(logging.WARNING)
    try:
        server._log_change("registerPublisher", ["/n", "/t", "t/T"], [1, "Registered [/n] as publisher of [/t]"])
    finally:
        server.log.removeHandler(keep)
        server.log.setLevel(level)
    assert keep.records == []
