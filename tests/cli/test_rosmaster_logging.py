"""The master's buffered file log: one write per flush, the same lines as logging's own path."""

from __future__ import annotations

import logging
import logging.handlers
import sys
from pathlib import Path

from kame.cli import rosmaster


def _log_through(handler: logging.Handler, name: str) -> None:
    log = logging.getLogger(name)
    log.propagate = False
    log.setLevel(logging.DEBUG)
    log.addHandler(handler)
    try:
        for i in range(2500):  # fills the 1000-record buffer twice over
            log.info("registerPublisher %s -> %s", ["/n", f"/t{i}", "t/T"], [1, "ok & <fine>"])
        log.debug("ünïcødé %d", 1)
        log.warning("a warning flushes at once")
        log.info("after the warning")
        handler.flush()
    finally:
        log.removeHandler(handler)
        handler.close()


def _strip_time(text: str) -> list[str]:
    return [line.split(" ", 1)[0] + line.split(": ", 1)[1] for line in text.splitlines()]


def test_batched_log_writes_what_logging_writes(tmp_path: Path) -> None:
    batched = rosmaster.setup_file_logging(tmp_path / "a" / "master.log", "test_rosmaster_logging.a")
    logging.getLogger("test_rosmaster_logging.a").removeHandler(batched)
    assert isinstance(batched, rosmaster._BatchedMemoryHandler)
    _log_through(batched, "test_rosmaster_logging.a2")
    stock_target = logging.FileHandler(tmp_path / "b.log")
    stock_target.setFormatter(rosmaster._Formatter(rosmaster.LOG_FORMAT))
    _log_through(logging.handlers.MemoryHandler(1000, logging.WARNING, stock_target), "test_rosmaster_logging.a2")
    stock_target.close()
    got = (tmp_path / "a" / "master.log").read_text()
    want = (tmp_path / "b.log").read_text()
    assert len(got.splitlines()) == 2503
    assert _strip_time(got) == _strip_time(want)


def test_formatter_writes_what_logging_formatter_writes() -> None:
    ours, stock = rosmaster._Formatter(rosmaster.LOG_FORMAT), logging.Formatter(rosmaster.LOG_FORMAT)
    try:
        raise ValueError("boom")
    except ValueError:
        exc_info = sys.exc_info()
    records = [
        logging.LogRecord("kame.master", logging.INFO, "f.py", 1, "registerPublisher %s -> %s",
                          (["/n", "/t", "t/T"], [1, "ok"]), None),
        logging.LogRecord("kame.master", logging.WARNING, "f.py", 1, "no args: 100%", (), None),
        logging.LogRecord("kame.master", logging.ERROR, "f.py", 1, "%(who)s failed", ({"who": "x"},), None),
        logging.LogRecord("kame.master", logging.ERROR, "f.py", 1, "failed", (), exc_info),
        logging.LogRecord("kame.master", logging.INFO, "f.py", 1, "here", (), None, sinfo="Stack (most recent):"),
    ]
    for record in records:
        assert ours.format(record) == stock.format(record)
    assert ours.format(records[0]).startswith("[kame.master][INFO] ")
