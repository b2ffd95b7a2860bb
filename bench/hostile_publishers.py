"""A subscriber under hostile publishers (issue 34): its peak memory above its idle size.

    .venv/bin/python bench/hostile_publishers.py [--cycles 200] [--drippers 10] [--seconds 30]
        [--ref SRC]   # also kame's sources at SRC (as bench/run.sh --ab exports a revision's)

A kame master and one subscriber of std_msgs/String, run by kame and by Debian's rospy
(/usr/bin/python3, when it can import rospy); the publishers are fake, each a kame Node's
registration whose TCPROS port is a socket this script serves by hand:
- "announce": publishers that answer each connection with a valid header and a frame that
  announces 64 MiB, send ten bytes of it and close, until --cycles connections were served
  (or 120 s passed). 25 of them, since a subscriber may back off from each one that keeps
  dropping it, as kame's does.
- "drip": --drippers publishers, each announcing a 64 MiB frame and sending a byte a second of
  it for --seconds.
- "garbled": one publisher that answers every connection with a header that is not one (a
  field without '='), for --seconds: how often the subscriber tries again, and how many lines
  it writes on stderr meanwhile.
Printed per run: the cycles served and their time, the subscriber's resident memory (VmRSS) when
idle, its peak (VmHWM) above that, and its VmRSS at the end. The goal (issue 34): a peak at most
100 MB above idle.
"""

from __future__ import annotations

import argparse
import os
import socket
import struct
import subprocess
import sys
import textwrap
import threading
import time
from collections.abc import Callable
from pathlib import Path

from bench_procs import free_port, stop

SUBSCRIBER = """
import rospy
from std_msgs.msg import String
rospy.init_node('hostile_target')
rospy.Subscriber('/hostile', String, lambda msg: None, queue_size=10)
print('ready', flush=True)
rospy.spin()
"""

ANNOUNCE = struct.pack("<I", 64 << 20) + b"0123456789"
GARBAGE = struct.pack("<I", 8) + struct.pack("<I", 4) + b"abcd"  # a header whose one field has no '='


def status_kb(pid: int, key: str) -> int:
    with open(f"/proc/{pid}/status") as f:
        return next(int(line.split()[1]) for line in f if line.startswith(key + ":"))


class FakePublisher:
    """A registered publisher of /hostile whose connections get `answer(conn)`."""

    def __init__(self, name: str, master_uri: str, answer: Callable[[socket.socket, bytes], None]) -> None:
        """`answer(conn, header)` once the subscriber's header is read; `header` is a valid reply."""
        from kame.node.node import Node, NodeConfig

        self.server = socket.socket()
        self.server.bind(("127.0.0.1", 0))
        self.server.listen(16)
        self.node = Node(NodeConfig(name, master_uri, "127.0.0.1"))
        self.node.tcpros_port = self.server.getsockname()[1]
        self.answer = answer
        self.served = 0
        self.thread = threading.Thread(target=self._serve, daemon=True)
        self.thread.start()
        from std_msgs.msg import String

        self.node.advertise("/hostile", "std_msgs/String", String._md5sum, String._full_text)

    def _serve(self) -> None:
        while True:
            try:
                conn, _ = self.server.accept()
            except OSError:
                return
            self.served += 1
            threading.Thread(target=self._answer, args=(conn,), daemon=True).start()

    def _answer(self, conn: socket.socket) -> None:
        from kame.protocol import tcpros
        from std_msgs.msg import String

        try:
            conn.settimeout(10)
            conn.recv(65536)
            self.answer(conn, tcpros.encode_header(tcpros.publisher_reply_fields(
                callerid=self.node.name, topic="/hostile", spec=tcpros.TopicSpec("std_msgs/String", String._md5sum))))
        except OSError:
            pass
        finally:
            conn.close()

    def close(self) -> None:
        self.node.shutdown("bench over")
        self.server.shutdown(socket.SHUT_RDWR)
        self.server.close()


def announce_and_close(conn: socket.socket, header: bytes) -> None:
    conn.sendall(header + ANNOUNCE)


def garble(conn: socket.socket, header: bytes) -> None:
    conn.sendall(GARBAGE)


def dripper(seconds: float) -> Callable[[socket.socket, bytes], None]:
    def drip(conn: socket.socket, header: bytes) -> None:
        conn.sendall(header + ANNOUNCE[:4])
        end = time.monotonic() + seconds
        while time.monotonic() < end:
            conn.sendall(b"x")
            time.sleep(1.0)
    return drip


def run(python: str, env: dict[str, str], master_uri: str, case: str, options: argparse.Namespace) -> str:
    errors = open(Path(env["ROS_HOME"]) / f"{case}-stderr.txt", "w+")
    subscriber = subprocess.Popen([python, "-c", textwrap.dedent(SUBSCRIBER)], env=env, text=True,
                                  stdout=subprocess.PIPE, stderr=errors)
    fakes: list[FakePublisher] = []
    try:
        assert subscriber.stdout is not None and subscriber.stdout.readline().strip() == "ready"
        time.sleep(1.0)
        idle = status_kb(subscriber.pid, "VmRSS")
        start = time.monotonic()
        if case == "announce":
            fakes = [FakePublisher(f"/announcer{i}", master_uri, announce_and_close) for i in range(25)]
            while sum(f.served for f in fakes) < options.cycles and time.monotonic() - start < 120:
                time.sleep(0.1)
            what = f"{sum(f.served for f in fakes)} cycles in {time.monotonic() - start:.0f} s"
        elif case == "drip":
            fakes = [FakePublisher(f"/dripper{i}", master_uri, dripper(options.seconds))
                     for i in range(options.drippers)]
            time.sleep(options.seconds)
            what = f"{options.drippers} drippers for {options.seconds:.0f} s"
        else:
            errors.seek(0, os.SEEK_END)
            lines_before = errors.tell()
            fakes = [FakePublisher("/garbler", master_uri, garble)]
            time.sleep(options.seconds)
            errors.flush()
            errors.seek(lines_before)
            lines = len(errors.read().splitlines())
            what = f"garbled replies for {options.seconds:.0f} s: {fakes[0].served} connections, {lines} stderr lines"
        peak = status_kb(subscriber.pid, "VmHWM")
        for fake in fakes:
            fake.close()
        fakes = []
        time.sleep(2.0)
        end = status_kb(subscriber.pid, "VmRSS")
        return (f"{what}: idle {idle / 1024:.0f} MB, peak +{(peak - idle) / 1024:.0f} MB, "
                f"2 s after the publishers left {end / 1024:.0f} MB")
    finally:
        for fake in fakes:
            fake.close()
        stop(subscriber)
        errors.close()


def main() -> None:
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--cycles", type=int, default=200)
    parser.add_argument("--drippers", type=int, default=10)
    parser.add_argument("--seconds", type=float, default=30.0)
    parser.add_argument("--ref", help="a kame src/ folder to run as `ref` (its nodes on this checkout's master)")
    parser.add_argument("--only", default="ref,kame,rospy", help="which of ref, kame and rospy to run")
    parser.add_argument("--cases", default="announce,drip,garbled", help="which of announce, drip and garbled")
    options = parser.parse_args()
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    home = Path("/tmp") / f"kame-hostile-bench-{os.getpid()}"
    home.mkdir(parents=True, exist_ok=True)
    env = dict(os.environ, ROS_MASTER_URI=uri, ROS_HOME=str(home), ROS_HOSTNAME="127.0.0.1", KAME_SHM="0")
    system_env = {k: v for k, v in env.items() if k != "PYTHONPATH"}
    master = subprocess.Popen([sys.executable, "-m", "kame.cli.rosmaster", "--core", "-p", str(port)], env=env,
                              stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
    impls = {"kame": (sys.executable, env), "rospy": ("/usr/bin/python3", system_env)}
    if options.ref:
        impls["ref"] = (sys.executable, dict(env, PYTHONPATH=options.ref))
    try:
        deadline = time.monotonic() + 20
        while True:
            try:
                socket.create_connection(("127.0.0.1", port), timeout=1).close()
                break
            except OSError:
                if time.monotonic() > deadline:
                    raise
                time.sleep(0.05)
        print(f"load average {os.getloadavg()[0]:.1f}", flush=True)
        for name in options.only.split(","):
            if name not in impls:
                continue
            python, impl_env = impls[name]
            if subprocess.run([python, "-c", "import rospy"], env=impl_env, capture_output=True).returncode:
                print(f"{name}: cannot import rospy, left out", flush=True)
                continue
            for case in options.cases.split(","):
                print(f"{name:5} {case:8} {run(python, impl_env, uri, case, options)}", flush=True)
    finally:
        stop(master)


if __name__ == "__main__":
    main()
