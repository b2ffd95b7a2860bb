# ruff: noqa: E501  (option help texts are rosbag's, one option per line)
"""rosbag record: subscribe to topics and write what arrives, as raw bytes, to a bag.

- Messages are never deserialized: the subscription delivers TCPROS frames and their
  connection header, which becomes the bag's connection record (one connection per
  topic and publisher, with callerid and latching, as the C++ recorder makes them).
- The subscriber threads only queue (bytes, time); one writer thread owns the bag, so a
  slow disk never stalls the sockets. The queue is bounded by -b MB (256); when full the
  oldest messages are dropped with a warning, as rosbag does.
- The file, not the sockets, is what costs (1 kHz small + 30 Hz 6 MB images on a VM: copying
  into ever new page-cache pages took ~4 s of CPU per 10 s, the sockets ~1 s), so the bag
  writer drops what it has written from the page cache behind itself (drop_behind) and
  takes large messages by reference (owned), with no copy into the chunk.
- Ctrl-C (or SIGTERM) stops subscribing, drains the queue, closes the bag and renames
  `name.bag.active` to `name.bag`. What arrives is handed to the kernel at least every
  FLUSH_INTERVAL (the open chunk is streamed), so a killed recorder loses at most that much:
  `rosbag reindex name.bag.active` indexes everything else, the torn last chunk included.
- A write that fails (a full disk) ends the recording with one error line; the bag is closed
  with what reached the disk (and renamed) when there is room for its index, else left as
  `.active` for `rosbag reindex`.
- -a, -e and --node find topics by asking the master once a second.
"""

from __future__ import annotations

import collections
import contextlib
import datetime
import os
import re
import threading
import time
from typing import TYPE_CHECKING, Any

from kame import names
from kame.bag.writer import BagWriter
from kame.cli._console import console
from kame.cli._node import ToolNode
from kame.cli._options import OptionParser
from kame.node.master_proxy import MasterError
from kame.node.node import Node

if TYPE_CHECKING:
    from kame.bag.mcap_file import McapWriter

FLUSH_INTERVAL = 0.5  # seconds: at most this much is lost when the recorder is killed


class RecordingFailed(Exception):
    """The bag cannot be opened or written (no such folder, no permission, a full disk)."""


def _size_arg(value: str) -> float:
    return float(value)


def _duration_arg(value: str) -> float:
    mult = 1.0
    if value.endswith("m"):
        mult, value = 60.0, value[:-1]
    elif value.endswith("h"):
        mult, value = 3600.0, value[:-1]
    elif value.endswith("s"):
        value = value[:-1]
    return float(value) * mult


def parser() -> OptionParser:
    p = OptionParser(usage="rosbag record TOPIC1 [TOPIC2 TOPIC3 ...]",
                              description="Record a bag file with the contents of specified topics.")
    p.add_argument("-a", "--all", dest="all", default=False, action="store_true", help="record all topics")
    p.add_argument("-e", "--regex", dest="regex", default=False, action="store_true", help="match topics using regular expressions")
    p.add_argument("-x", "--exclude", dest="exclude_regex", default="", action="store",
                 help="exclude topics matching the follow regular expression (subtracts from -a or regex)")
    p.add_argument("-q", "--quiet", dest="quiet", default=False, action="store_true", help="suppress console output")
    p.add_argument("-p", "--publish", dest="publish", default=False, action="store_true",
                 help="Publish a msg when the record begin")
    p.add_argument("-o", "--output-prefix", dest="prefix", default=None, action="store", help="prepend PREFIX to beginning of bag name")
    p.add_argument("-O", "--output-name", dest="name", default=None, action="store", help="record to bag with name NAME.bag")
    p.add_argument("--split", dest="split", default=False, action="store_true",
                 help="split the bag when maximum size or duration is reached")
    p.add_argument("--max-splits", dest="max_splits", type=int, action="store", help="Keep a maximum of N bag files")
    p.add_argument("--size", dest="size", type=float, action="store", help="record a bag of maximum size SIZE MB")
    p.add_argument("--duration", dest="duration", type=str, action="store",
                 help="record a bag of maximum duration DURATION in seconds, unless 'm', or 'h' is appended.")
    p.add_argument("-b", "--buffsize", dest="buffsize", default=256, type=int, action="store",
                 help="use an internal buffer of SIZE MB (Default: 256, 0 = infinite)")
    p.add_argument("--chunksize", dest="chunksize", default=768, type=int, action="store",
                 help="Advanced. Record to chunks of SIZE KB (Default: 768)")
    p.add_argument("-l", "--limit", dest="num", default=0, type=int, action="store", help="only record NUM messages on each topic")
    p.add_argument("--node", dest="node", type=str, action="store", help="record all topics subscribed to by a specific node")
    p.add_argument("-j", "--bz2", dest="compression", default="none", action="store_const", const="bz2", help="use BZ2 compression")
    p.add_argument("--lz4", dest="compression", action="store_const", const="lz4", help="use LZ4 compression")
    p.add_argument("--mcap", dest="mcap", default=False, action="store_true",
                   help="record to MCAP (name.mcap; zstd, or --lz4; kame's, needs the web extra)")
    p.add_argument("--tcpnodelay", dest="tcpnodelay", action="store_true", help="Use the TCP_NODELAY transport hint when subscribing to topics.")
    p.add_argument("--udp", dest="udp", action="store_true", help="Use the UDP transport hint when subscribing to topics.")
    p.add_argument("--repeat-latched", dest="repeat_latched", action="store_true",
                 help="Repeat latched msgs at the start of each new bag file.")
    return p


def _stamp() -> str:
    return datetime.datetime.now().strftime("%Y-%m-%d-%H-%M-%S")


class BagNamer:
    """Output names: `-O name` -> name.bag, `-o pre` -> pre_<stamp>.bag, else <stamp>.bag;
    with --split an `_N` before `.bag`."""

    def __init__(self, prefix: str | None, name: str | None, split: bool, suffix: str = ".bag") -> None:
        self.prefix = prefix
        self.name = name
        self.split = split
        self.suffix = suffix  # .mcap with --mcap
        self.index = 0

    def next(self) -> str:
        if self.name:
            base = self.name.removesuffix(self.suffix)
        elif self.prefix:
            base = self.prefix.removesuffix(self.suffix)
            base = f"{base}_{_stamp()}"
        else:
            base = _stamp()
        if self.split:
            base = f"{base}_{self.index}"
        self.index += 1
        return base + self.suffix


# -a, -e and --node: a new topic sends no event, so the master is asked again once a second, as rosbag does
MASTER_POLL_PERIOD = 1.0


class Recorder:
    def __init__(self, node: Node, options: Any, topics: list[str], stop: threading.Event) -> None:
        self.node = node
        self.options = options
        self.stop = stop
        self.explicit = topics
        self.queue: collections.deque[tuple[tuple[str, str], dict[str, str], int, bytes]] = collections.deque()
        self.queued_bytes = 0
        self.limit_bytes = options.buffsize * 1024 * 1024 if options.buffsize > 0 else 0
        self.cond = threading.Condition()
        self.subscribed: set[str] = set()
        self.counts: dict[str, int] = {}
        self.dropped = 0
        self.namer = BagNamer(options.prefix, options.name, bool(options.split), ".mcap" if options.mcap else ".bag")
        self.max_size = int(options.size * 1024 * 1024) if options.split and options.size else 0
        self.max_duration = _duration_arg(options.duration) if options.duration else 0.0
        self.exclude = re.compile(options.exclude_regex) if options.exclude_regex else None
        self.regexes = [re.compile(t) for t in topics] if options.regex else []
        self.done_topics: set[str] = set()
        self.finished = threading.Event()
        self.failed = False

    # ------------------------------------------------------------------ subscribing

    def wants(self, topic: str) -> bool:
        if self.exclude is not None and self.exclude.search(topic):
            return False
        if self.options.all:
            return True
        if self.regexes:
            return any(r.fullmatch(topic) for r in self.regexes)
        return topic in self.explicit

    def subscribe(self, topic: str) -> None:
        if topic in self.subscribed:
            return
        self.subscribed.add(topic)
        if not self.options.quiet:
            console("INFO", f"Subscribing to {topic}")
        def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
            self.deliver(topic, frames, header)

        self.node.subscribe(topic, "*", "*", "", deliver, tcp_nodelay=bool(self.options.tcpnodelay))

    def poll_master(self) -> None:
        try:
            if self.options.node:
                node_name = names.canonicalize(self.options.node if names.is_global(self.options.node)
                                               else "/" + self.options.node)
                _, subs, _ = self.node.master.call("getSystemState")
                for topic, nodes in subs:
                    if node_name in nodes and self.wants_node_topic(topic):
                        self.subscribe(topic)
                return
            for topic, _type in self.node.master.call("getPublishedTopics", ""):
                if self.wants(topic):
                    self.subscribe(topic)
        except (OSError, MasterError):
            pass

    def wants_node_topic(self, topic: str) -> bool:
        return self.exclude is None or not self.exclude.search(topic)

    # ------------------------------------------------------------------ receiving

    def deliver(self, topic: str, frames: list[memoryview], header: dict[str, str]) -> None:
        now = time.time_ns()
        key = (topic, header.get("callerid", ""))
        limit = self.options.num
        with self.cond:
            for frame in frames:
                if limit:
                    n = self.counts.get(topic, 0)
                    if n >= limit:
                        break
                    self.counts[topic] = n + 1
                    if n + 1 >= limit:
                        self.done_topics.add(topic)
                data = bytes(frame)
                self.queue.append((key, header, now, data))
                self.queued_bytes += len(data)
                while self.limit_bytes and self.queued_bytes > self.limit_bytes and len(self.queue) > 1:
                    _, _, _, old = self.queue.popleft()
                    self.queued_bytes -= len(old)
                    self.dropped += 1
                    if self.dropped == 1 or self.dropped % 100 == 0:
                        console("WARN", f"rosbag record buffer exceeded.  Dropping oldest queued message ({self.dropped} so far).")
            self.cond.notify()
        if limit and self.explicit and all(t in self.done_topics for t in self.explicit):
            self.stop.set()

    # ------------------------------------------------------------------ writing

    def _open(self) -> tuple[BagWriter | McapWriter, str]:
        path = self.namer.next()
        try:  # no folder is made for it, as with rosbag's recorder
            writer: BagWriter | McapWriter
            if self.options.mcap:
                from kame.bag.mcap_file import McapWriter

                compression = "lz4" if self.options.compression == "lz4" else "zstd"
                writer = McapWriter(path + ".active", compression, self.options.chunksize * 1024)
            else:
                writer = BagWriter(path + ".active", "w", self.options.compression, self.options.chunksize * 1024,
                                   drop_behind=True)
        except OSError as exc:
            raise RecordingFailed(f"Error opening file: {path}.active") from exc
        if not self.options.quiet:
            console("INFO", f"Recording to '{path}'.")
        return writer, path

    def _close(self, writer: BagWriter | McapWriter, path: str) -> None:
        try:
            writer.close()
            os.replace(path + ".active", path)
        except OSError as exc:
            raise RecordingFailed(f"cannot close {path}.active: {exc.strerror or exc}") from exc

    def write_loop(self) -> None:
        """Write what the subscriptions queue until stopped; a bag that cannot be opened or
        written is said once (rosbag's `Error writing: ...`) and ends the recording."""
        try:
            self._write_until_stopped()
        except RecordingFailed as exc:
            console("ERROR", f"Error writing: {exc}")
            self.failed = True
            self.stop.set()
        finally:
            self.finished.set()

    def stop_writing(self) -> None:
        """Ends the writer's wait: it writes what is queued, closes the bag and returns."""
        self.stop.set()
        with self.cond:
            self.cond.notify_all()

    def _duration_up(self, opened: float) -> bool:
        return bool(self.max_duration) and time.monotonic() - opened >= self.max_duration

    def _wait_limit(self, opened: float, flushed: float | None) -> float | None:
        """How long the writer may wait for a message: until the unflushed chunk is due (when
        `flushed` is given) or the duration is up, whichever is first; None: no limit."""
        due = [t for t in (flushed + FLUSH_INTERVAL if flushed is not None else None,
                           opened + self.max_duration if self.max_duration else None) if t is not None]
        return max(min(due) - time.monotonic(), 0.0) if due else None

    def _write_until_stopped(self) -> None:
        writer, path = self._open()
        conns: dict[tuple[str, str], int] = {}
        opened = flushed = time.monotonic()
        unflushed = False
        written: list[str] = [path]
        try:
            while True:
                with self.cond:
                    # woken by a message or by stop_writing, or when the open chunk is due on
                    # disk (FLUSH_INTERVAL after something was written) or --duration is up, so an
                    # idle bag is split or closed on time, as rosbag's checkDuration does
                    while not self.queue and not self.stop.is_set() and not self._duration_up(opened):
                        if not self.cond.wait(self._wait_limit(opened, flushed if unflushed else None)):
                            break
                    if not self.queue and self.stop.is_set():
                        break
                    batch = list(self.queue)
                    self.queue.clear()
                    self.queued_bytes = 0
                for key, header, now, data in batch:
                    conn_id = conns.get(key)
                    if conn_id is None:
                        conn_id = conns[key] = writer.add_connection(key[0], header)
                    secs, nsecs = divmod(now, 1_000_000_000)
                    try:
                        writer.write(conn_id, secs, nsecs, data, owned=True)
                    except OSError as exc:
                        raise RecordingFailed(f"cannot write {path}.active: {exc.strerror or exc}") from exc
                unflushed = unflushed or bool(batch)
                if unflushed and time.monotonic() - flushed >= FLUSH_INTERVAL:
                    try:
                        writer.write_pending()
                    except OSError as exc:
                        raise RecordingFailed(f"cannot write {path}.active: {exc.strerror or exc}") from exc
                    flushed = time.monotonic()
                    unflushed = False
                if self.options.split and ((self.max_size and writer.size >= self.max_size) or self._duration_up(opened)):
                    self._close(writer, path)
                    if self.options.max_splits and len(written) >= self.options.max_splits:
                        old = written.pop(0)
                        if os.path.exists(old):
                            os.remove(old)
                    writer, path = self._open()
                    written.append(path)
                    conns = {}
                    opened = time.monotonic()
                elif not self.options.split and self._duration_up(opened):
                    self.stop.set()
        except BaseException:
            with contextlib.suppress(RecordingFailed):  # keep what reached the disk, if it lets us
                self._close(writer, path)
            raise
        self._close(writer, path)


def main(argv: list[str]) -> int:
    p = parser()
    ros = names.parse_args(["rosbag", *argv])
    options = p.parse_args([a for a in argv if ":=" not in a])
    args = options.args
    if not options.all and not args and not options.node:
        p.error("You must specify a topic name or else use the '-a' option.")
    if options.all and options.num:
        p.error("Specifying a count is not valid with automatic topic subscription.")
    if options.prefix and options.name:
        p.error("Can't set both prefix and name.")
    if options.mcap and options.compression == "bz2":
        p.error("MCAP has no BZ2 compression: use --lz4, or none of them for zstd.")
    if options.split and not options.size and not options.duration:
        p.error("Split specified without giving a maximum duration or size")
    if options.size is not None and options.size <= 0:
        p.error("Split size must be 0 or positive")
    tool = ToolNode(ros.special, f"record_{int(time.time() * 1000)}")
    node, stop, namespace = tool.node, tool.stop, tool.namespace
    topics = [names.resolve(t, tool.caller_id, {}) if not options.regex else t for t in args]
    topics = [names.ns_join(namespace, t) if not names.is_global(t) and not options.regex else t for t in topics]
    recorder = Recorder(node, options, topics, stop)
    writer_thread = threading.Thread(target=recorder.write_loop, name="rosbag-writer")
    try:
        if not tool.wait_for_master():
            return 0
        auto = options.all or options.regex or bool(options.node)
        if not auto:
            for topic in topics:
                recorder.subscribe(topic)
        writer_thread.start()
        if auto:
            while not stop.is_set():
                recorder.poll_master()
                stop.wait(MASTER_POLL_PERIOD)
        else:
            stop.wait()  # set by Ctrl-C/SIGTERM, a shutdown request, -l reached, --duration or a write error
    finally:
        recorder.stop_writing()
        node.shutdown("rosbag record exiting")
        if writer_thread.is_alive():
            writer_thread.join()
    return 1 if recorder.failed else 0
