"""rosmaster: the ROS master and parameter server (`rosmaster --core -p PORT -w N __log:=FILE`).

Options as in ros_comm's rosmaster. `-w` (notification worker threads there) is accepted and has
nothing to size here: notifications run concurrently per node with a timeout each (`-t`).
SIGINT or SIGTERM, or a `shutdown` XML-RPC call, stops it promptly.
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import logging.handlers
import os
import signal
import sys
import time
from collections.abc import Awaitable, Callable, Sequence
from pathlib import Path

from kame import names
from kame.master.server import NOTIFY_TIMEOUT, MasterServer
from kame.net import peers
from kame.net.address import host_addresses

DEFAULT_PORT = 11311
LOG_FORMAT = "[%(name)s][%(levelname)s] %(asctime)s: %(message)s"
_LEVELS = {"debug": logging.DEBUG, "info": logging.INFO, "warn": logging.WARNING, "error": logging.ERROR,
           "fatal": logging.CRITICAL}

ACHTUNG = """


ACHTUNG WARNING ACHTUNG WARNING ACHTUNG
WARNING ACHTUNG WARNING ACHTUNG WARNING


Standalone zenmaster has been deprecated, please use 'roscore' instead


ACHTUNG WARNING ACHTUNG WARNING ACHTUNG
WARNING ACHTUNG WARNING ACHTUNG WARNING

"""


def log_dir(env: os._Environ[str] | dict[str, str]) -> Path:
    """ROS_LOG_DIR, else ROS_HOME/log, else ~/.ros/log (spec §8.3)."""
    if env.get("ROS_LOG_DIR"):
        return Path(env["ROS_LOG_DIR"])
    return ros_home(env) / "log"


def ros_home(env: os._Environ[str] | dict[str, str]) -> Path:
    return Path(env["ROS_HOME"]) if env.get("ROS_HOME") else Path.home() / ".ros"


class _Formatter(logging.Formatter):
    """LOG_FORMAT with the timestamp text built once per second: strftime per record was the
    larger part of the master's per-call logging cost."""

    _second = -1
    _stamp = ""

    def format(self, record: logging.LogRecord) -> str:
        # logging.Formatter.format's steps for LOG_FORMAT, as one f-string: its %-style pass over
        # the record's __dict__ was a third of the cost of a registration's log line
        if record.exc_info or record.exc_text or record.stack_info or self._fmt != LOG_FORMAT:
            return super().format(record)
        record.message = record.getMessage()
        record.asctime = self.formatTime(record)
        return f"[{record.name}][{record.levelname}] {record.asctime}: {record.message}"

    def formatTime(self, record: logging.LogRecord, datefmt: str | None = None) -> str:
        second = int(record.created)
        if second != self._second:
            self._second, self._stamp = second, time.strftime("%Y-%m-%d %H:%M:%S", time.localtime(second))
        return f"{self._stamp},{int(record.msecs):03d}"


class _BatchedMemoryHandler(logging.handlers.MemoryHandler):
    """A MemoryHandler whose flush writes its records to the target file in one write: the
    stock flush hands them over one by one, and FileHandler flushes the file after each (a
    syscall per record, most of the master's logging cost under a registration storm)."""

    def flush(self) -> None:
        with self.lock:  # type: ignore[union-attr]
            target = self.target
            if not self.buffer or not isinstance(target, logging.FileHandler) or target.filters:
                super().flush()
                return
            try:
                text = "".join([target.format(r) + target.terminator for r in self.buffer])
            except Exception:
                super().flush()  # let the stock path report the record that cannot be formatted
                return
            with target.lock:  # type: ignore[union-attr]
                try:
                    if target.stream is None:
                        target.stream = target._open()
                    target.stream.write(text)
                    target.stream.flush()
                except Exception:
                    target.handleError(self.buffer[-1])
            self.buffer.clear()


def setup_file_logging(path: Path, logger: str = "kame") -> logging.handlers.MemoryHandler:
    """Log `logger`'s records to `path`, buffered: a registration must not wait for a disk write.

    The buffer is written out when full, on a warning, by `flush_periodically`, and at exit.
    """
    path.parent.mkdir(parents=True, exist_ok=True)
    target = logging.FileHandler(path)
    target.setFormatter(_Formatter(LOG_FORMAT))
    # nothing we log uses them, and each costs a lookup per record
    logging.logThreads = logging.logProcesses = logging.logMultiprocessing = False
    buffered = _BatchedMemoryHandler(1000, logging.WARNING, target)
    log = logging.getLogger(logger)
    log.setLevel(logging.DEBUG)
    log.addHandler(buffered)
    return buffered


async def flush_periodically(handler: logging.Handler, every: float = 1.0) -> None:
    while True:
        await asyncio.sleep(every)
        handler.flush()


async def serve(port: int, notify_timeout: float,
                on_started: Callable[[MasterServer, str], Awaitable[None]] | None = None,
                on_stopping: Callable[[], Awaitable[None]] | None = None) -> int:
    """Run a master on `port` until SIGINT/SIGTERM or a shutdown call; returns the exit status.

    `on_stopping` runs before the master closes, so what roscore started can still unregister."""
    host = host_addresses(os.environ)
    server = MasterServer(host.bind, port, host.advertised, notify_timeout=notify_timeout)
    try:
        uri = await server.start()
    except OSError as e:
        logging.getLogger("kame.master").error("cannot listen on port %d: %s", port, e)
        print(f"ERROR: Unable to start XML-RPC server, port {port} is already in use", file=sys.stderr)
        return 1
    loop = asyncio.get_running_loop()
    stop = asyncio.Event()
    for sig in (signal.SIGINT, signal.SIGTERM):
        loop.add_signal_handler(sig, stop.set)
    try:
        if on_started is not None:
            await on_started(server, uri)
        shutdown_call = asyncio.ensure_future(server.wait_shutdown())
        stop_signal = asyncio.ensure_future(stop.wait())
        await asyncio.wait([shutdown_call, stop_signal], return_when=asyncio.FIRST_COMPLETED)
        shutdown_call.cancel()
        stop_signal.cancel()
    finally:
        if on_stopping is not None:
            await on_stopping()  # a second Ctrl-C meanwhile only sets `stop` again
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.remove_signal_handler(sig)
        logging.getLogger("kame.master").info("stopping master...")
        await server.close()
    return 0


def parse_args(argv: Sequence[str]) -> tuple[argparse.Namespace, dict[str, str]]:
    ros = names.parse_args(argv)
    parser = argparse.ArgumentParser(prog="rosmaster", usage="usage: rosmaster [options]")
    parser.add_argument("--core", action="store_true", help="run as core")
    parser.add_argument("-p", "--port", type=int, default=DEFAULT_PORT, help="override port", metavar="PORT")
    parser.add_argument("-w", "--numworkers", type=int, default=3, metavar="NUM_WORKERS",
                        help="accepted for compatibility (notifications are concurrent per node)")
    parser.add_argument("-t", "--timeout", type=float, default=NOTIFY_TIMEOUT, metavar="TIMEOUT",
                        help="timeout of each notification to a node, in seconds")
    parser.add_argument("--master-logger-level", choices=sorted(_LEVELS), default=None,
                        help="set the master's logger level")
    parser.add_argument("--allowed-peers", metavar="PEERS", default=None,
                        help="only these addresses, networks (10.0.0.0/24) and host names, and this machine, may "
                             "connect to the master and to the nodes started here (sets KAME_ALLOWED_PEERS)")
    options = parser.parse_args(ros.argv)
    if ros.remappings or ros.params:
        parser.error(f"unrecognized arg: {next(iter({**ros.remappings, **ros.params}))}")
    try:
        peers.setup(options.allowed_peers)
    except ValueError as exc:
        parser.error(str(exc))
    return options, ros.special


def main(argv: Sequence[str] | None = None) -> int:
    options, special = parse_args(sys.argv[1:] if argv is None else argv)
    log_path = Path(special["log"]).absolute() if "log" in special else log_dir(os.environ) / "master.log"
    handler = setup_file_logging(log_path)
    # The master logs a line per registration and no format of ours names a source line: skip
    # the stack walk logging does for each record to find one (about a third of a record's cost).
    # Only here, in the master's own process: nodes' records carry their file and line to /rosout.
    logging._srcfile = None
    if options.master_logger_level:
        logging.getLogger("kame.master").setLevel(_LEVELS[options.master_logger_level])
    if not options.core:
        print(ACHTUNG, flush=True)
    logging.getLogger("kame.master").info("initialization complete, waiting for shutdown")

    async def run() -> int:
        flusher = asyncio.ensure_future(flush_periodically(handler))
        try:
            return await serve(options.port, options.timeout)
        finally:
            flusher.cancel()

    try:
        return asyncio.run(run())
    finally:
        handler.close()


if __name__ == "__main__":
    sys.exit(main())
