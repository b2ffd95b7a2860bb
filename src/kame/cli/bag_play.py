# ruff: noqa: E501  (option help texts are rosbag's, one option per line)
"""rosbag play: republish a bag's messages with their original timing.

- Messages are published as the bytes in the bag, with the connection's type, md5sum,
  message_definition and latching; nothing is deserialized.
- Timing: message time t is published at wall start + (t - t0) / rate, the pause time
  excluded, where t0 is the first message played (as rosbag's view begin: --topics and -s
  never make the player wait for messages it does not play). -s and -u count from the start
  of the whole bag. --clock publishes /clock (rosgraph_msgs/Clock) at --hz while waiting.
- In a terminal, space toggles pause and `s` publishes one message while paused; the status
  line is rewritten in place with `\\r` unless -q.
"""

from __future__ import annotations

import heapq
import os
import select
import sys
import threading
import time
from collections.abc import Iterator
from typing import TYPE_CHECKING, Any

from kame import names
from kame.bag.errors import BagError
from kame.bag.reader import BagReader, MessageView, open_reader
from kame.cli._console import console
from kame.cli._node import ToolNode
from kame.cli._options import OptionParser
from kame.node.topics import Publication, serialize_payload

if TYPE_CHECKING:
    from kame.bag.mcap_file import McapReader


def parser() -> OptionParser:
    p = OptionParser(usage="rosbag play BAGFILE1 [BAGFILE2 BAGFILE3 ...]",
                              description="Play back the contents of one or more bag files in a time-synchronized fashion.")
    p.add_argument("-p", "--prefix", dest="prefix", default="", type=str, help="prefix all output topics")
    p.add_argument("-q", "--quiet", dest="quiet", default=False, action="store_true", help="suppress console output")
    p.add_argument("-i", "--immediate", dest="immediate", default=False, action="store_true", help="play back all messages without waiting")
    p.add_argument("--pause", dest="pause", default=False, action="store_true", help="start in paused mode")
    p.add_argument("--queue", dest="queue", default=100, type=int, action="store", help="use an outgoing queue of size SIZE (defaults to 100)")
    p.add_argument("--clock", dest="clock", default=False, action="store_true", help="publish the clock time")
    p.add_argument("--hz", dest="freq", default=100, type=float, action="store", help="use a frequency of HZ when publishing clock time (default: 100)")
    p.add_argument("-d", "--delay", dest="delay", default=0.2, type=float, action="store", help="sleep SEC seconds after every advertise call (to allow subscribers to connect)")
    p.add_argument("-r", "--rate", dest="rate", default=1.0, type=float, action="store", help="multiply the publish rate by FACTOR")
    p.add_argument("-s", "--start", dest="start", default=0.0, type=float, action="store", help="start SEC seconds into the bag files")
    p.add_argument("-u", "--duration", dest="duration", default=None, type=float, action="store", help="play only SEC seconds from the bag files")
    p.add_argument("--skip-empty", dest="skip_empty", default=None, type=float, action="store", help="skip regions in the bag with no messages for more than SEC seconds")
    p.add_argument("-l", "--loop", dest="loop", default=False, action="store_true", help="loop playback")
    p.add_argument("-k", "--keep-alive", dest="keep_alive", default=False, action="store_true", help="keep alive past end of bag (useful for publishing latched topics)")
    p.add_argument("--try-future-version", dest="try_future", default=False, action="store_true", help="still try to open a bag file, even if the version is not known to the player")
    p.add_argument("--topics", dest="topics", default=[], nargs="*", action="extend", help="topics to play back")
    p.add_argument("--pause-topics", dest="pause_topics", default=[], nargs="*", action="extend", help="topics to pause playback on")
    p.add_argument("--bags", help="bags files to play back from", dest="bags", default=[], nargs="*", action="extend")
    p.add_argument("--wait-for-subscribers", dest="wait_for_subscribers", default=False, action="store_true", help="wait for at least one subscriber on each topic before publishing")
    p.add_argument("--rate-control-topic", dest="rate_control_topic", default="", type=str, help="watch the given topic, and if the last publish was more than <rate-control-max-delay> ago, wait until the topic publishes again to continue playback")
    p.add_argument("--rate-control-max-delay", dest="rate_control_max_delay", default=1.0, type=float, help="maximum time difference from <rate-control-topic> before pausing")
    return p


class Keyboard:
    """Single keys from a terminal on stdin (cbreak mode), restored on close."""

    def __init__(self, stop: threading.Event) -> None:
        self.stop = stop  # without a terminal, read() is a wait that stopping ends at once
        self.fd = -1
        self.saved: Any = None
        try:
            if sys.stdin.isatty():
                import termios
                import tty

                self.fd = sys.stdin.fileno()
                self.saved = termios.tcgetattr(self.fd)
                tty.setcbreak(self.fd)
        except (OSError, ValueError, ImportError):
            self.fd = -1

    def read(self, timeout: float) -> str | None:
        if self.fd < 0:
            if timeout > 0:
                self.stop.wait(timeout)
            return None
        ready, _, _ = select.select([self.fd], [], [], max(timeout, 0))
        if not ready:
            return None
        return os.read(self.fd, 1).decode(errors="replace")

    def close(self) -> None:
        if self.fd >= 0 and self.saved is not None:
            import termios

            termios.tcsetattr(self.fd, termios.TCSADRAIN, self.saved)
            self.fd = -1


def _merged(readers: list[BagReader | McapReader], topics: list[str], start: tuple[int, int] | None,
            end: tuple[int, int] | None) -> Iterator[MessageView]:
    """The messages to play in time order, their data as views of the bag's chunks (no copies)."""
    streams = []
    for reader in readers:
        conns = reader.connections_for(topics) if topics else None
        streams.append(reader.message_views(conns, start, end))
    if len(streams) == 1:
        return streams[0]
    return heapq.merge(*streams, key=lambda m: (m[1], m[2]))


def _ns(t: tuple[int, int]) -> int:
    return t[0] * 1_000_000_000 + t[1]


class Player:
    def __init__(self, tool: ToolNode, options: Any, readers: list[BagReader | McapReader]) -> None:
        self.tool = tool
        self.node = tool.node
        self.options = options
        self.readers = readers
        self.stop = tool.stop
        self.pubs: dict[str, Publication] = {}
        self.paused = bool(options.pause)
        self.clock: Publication | None = None
        self.keyboard = Keyboard(self.stop)
        starts = [r.start_time for r in readers if r.start_time is not None]
        ends = [r.end_time for r in readers if r.end_time is not None]
        self.bag_start = _ns(min(starts)) if starts else 0
        self.bag_end = _ns(max(ends)) if ends else 0
        self.view_start = self.bag_start  # the first message played, once known
        self.view_end = self.bag_end
        self.last_status = 0.0

    def advertise(self) -> None:
        for reader in self.readers:
            for conn in reader.connections.values():
                if self.options.topics and conn.topic not in self.options.topics:
                    continue
                topic = names.canonicalize(self.options.prefix + conn.topic) if self.options.prefix else conn.topic
                if topic in self.pubs:
                    continue
                latch = conn.header.get("latching", "0") == "1"
                self.pubs[conn.topic] = self.node.advertise(topic, conn.datatype, conn.md5sum, conn.msg_def, latch=latch,
                                                            queue_size=self.options.queue,
                                                            on_connect=lambda link: self.tool.notify())
        if self.options.clock:
            from rosgraph_msgs.msg import Clock

            self.clock = self.node.advertise("/clock", Clock._type, Clock._md5sum, Clock._full_text,
                                             queue_size=self.options.queue)

    def publish_clock(self, bag_ns: int) -> None:
        if self.clock is None:
            return
        from kame.client.clock import Time
        from rosgraph_msgs.msg import Clock

        self.clock.publish_payload(serialize_payload(Clock(clock=Time(*divmod(bag_ns, 1_000_000_000)))))

    def status(self, bag_ns: int, force: bool = False) -> None:
        if self.options.quiet:
            return
        now = time.monotonic()
        if not force and now - self.last_status < 0.1:
            return
        self.last_status = now
        state = "[PAUSED ]" if self.paused else "[RUNNING]"
        text = (f"\r {state}  Bag Time: {bag_ns / 1e9:13.6f}   Duration: {(bag_ns - self.view_start) / 1e9:.6f} / "
                f"{(self.view_end - self.view_start) / 1e9:.6f}               \r")
        sys.stdout.write(text)
        sys.stdout.flush()

    def wait_until(self, target: float, bag_ns: int, clock_from: int) -> tuple[float, bool]:
        """Sleep until wall time `target` (monotonic), handling keys, /clock and pause. Returns
        the (possibly shifted by pausing) target and whether a step was requested."""
        period = 1.0 / self.options.freq if self.options.freq > 0 else 0.01
        while not self.stop.is_set():
            now = time.monotonic()
            if self.paused:
                self.status(bag_ns)
                key = self.keyboard.read(0.1)
                target += time.monotonic() - now
                if key == " ":
                    self.paused = False
                elif key == "s":
                    return target, True
                continue
            remaining = target - now
            if remaining <= 0:
                return target, False
            if self.clock is not None:
                elapsed_wall = now - (target - (bag_ns - clock_from) / 1e9 / self.options.rate)
                self.publish_clock(clock_from + int(elapsed_wall * self.options.rate * 1e9))
            self.status(bag_ns - int(remaining * self.options.rate * 1e9))
            key = self.keyboard.read(min(remaining, period, 0.1))
            if key == " ":
                self.paused = True
                self.status(bag_ns, force=True)
        return target, False

    def selected_end(self, end_ns: int | None) -> int:
        """The end of the played view for the status line: the last chunk holding a selected
        topic (an upper bound with --topics), cut at -u."""
        ends = []
        for reader in self.readers:
            ids = {c.id for c in reader.connections_for(self.options.topics)} if self.options.topics else None
            ends += [_ns(info.end) for info in reader.chunk_infos if ids is None or not ids.isdisjoint(info.counts)]
        last = max(ends, default=self.bag_end)
        return min(last, end_ns) if end_ns is not None else last

    def play_once(self) -> None:
        opts = self.options
        initial_ns = self.bag_start + int(opts.start * 1e9)
        end_ns = initial_ns + int(opts.duration * 1e9) if opts.duration is not None else None
        start_t = divmod(initial_ns, 1_000_000_000)
        end_t = divmod(end_ns, 1_000_000_000) if end_ns is not None else None
        self.view_end = self.selected_end(end_ns)
        wall0 = time.monotonic()
        start_ns = prev_ns = -1
        for conn, secs, nsecs, data, _, _ in _merged(self.readers, opts.topics, start_t, end_t):
            if self.stop.is_set():
                return
            t_ns = secs * 1_000_000_000 + nsecs
            if start_ns < 0:  # timing counts from the first message played, as rosbag's view begin
                start_ns = prev_ns = self.view_start = t_ns
                wall0 = time.monotonic()
            if opts.skip_empty and (t_ns - prev_ns) / 1e9 > opts.skip_empty:
                wall0 -= (t_ns - prev_ns) / 1e9 / opts.rate
            if not opts.immediate:
                target = wall0 + (t_ns - start_ns) / 1e9 / opts.rate
                shifted, _step = self.wait_until(target, t_ns, prev_ns)
                wall0 += shifted - target
            pub = self.pubs.get(conn.topic)
            if pub is not None:
                pub.publish_payload(data)  # a view of the bag's chunk (immutable bytes): sent with no copy
            if self.clock is not None:
                self.publish_clock(t_ns)
            prev_ns = t_ns
            self.status(t_ns)
            if opts.pause_topics and conn.topic in opts.pause_topics:
                self.paused = True

    def run(self) -> None:
        try:
            self.advertise()
            sys.stdout.write(f"\nWaiting {self.options.delay:g} seconds after advertising topics...")
            sys.stdout.flush()
            self.stop.wait(max(self.options.delay, 0.0))
            sys.stdout.write(" done.\n\nHit space to toggle paused, or 's' to step.\n")
            sys.stdout.flush()
            if self.options.wait_for_subscribers:
                self.tool.wait_until(lambda: all(p.links for p in self.pubs.values()))
            while not self.stop.is_set():
                self.play_once()
                if not self.options.loop:
                    break
            if not self.options.quiet:
                sys.stdout.write("\n")
            if self.options.keep_alive:
                self.stop.wait()
            if not self.stop.is_set():
                sys.stdout.write("Done.\n")
            sys.stdout.flush()
        finally:
            self.keyboard.close()


def main(argv: list[str]) -> int:
    p = parser()
    ros = names.parse_args(["rosbag", *argv])
    options = p.parse_args([a for a in argv if ":=" not in a])
    args = options.args
    bags = [*args, *options.bags]
    if not bags:
        p.error("You must specify at least 1 bag file to play back.")
    if options.rate <= 0:
        p.error("Invalid rate")
    readers = []
    for path in bags:
        console("INFO", f"Opening {path}")
        try:
            readers.append(open_reader(path))
        except (BagError, OSError) as exc:
            console("FATAL", f"Error opening file: {path}" if isinstance(exc, OSError) else str(exc))
            return 1
    tool = ToolNode(ros.special, f"play_{int(time.time() * 1000)}")
    node = tool.node
    try:
        if not tool.wait_for_master():
            return 0
        Player(tool, options, readers).run()
    except BagError as exc:  # damage past the index, found while playing: rosbag's player says it and ends
        sys.stdout.write("\n")
        console("FATAL", str(exc))
        return 1
    finally:
        node.shutdown("rosbag play exiting")
        for reader in readers:
            reader.close()
    return 0
