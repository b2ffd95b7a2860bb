"""Topics through shared memory between kame nodes (kame.protocol.shmros, kame.net.shm)."""

from __future__ import annotations

import os
import signal
import subprocess
import sys
import textwrap
import threading
import time
from pathlib import Path
from typing import Any

import pytest

from kame.net import shm
from kame.net.stream import Sender
from kame.node.node import Node
from kame.node.topics import Publication, serialize_frame
from sensor_msgs.msg import Image

from ..support import ros_env, wait_until

IMAGE = ("sensor_msgs/Image", Image._md5sum, Image._full_text)



def image(seq: int, size: int) -> Image:
    return Image(height=1, width=size, encoding="mono8", step=size, data=bytes([seq % 251]) * size)


def images_to(node: Node, topic: str, queue_size: int | None = None, shared_memory: bool = True,
              gate: threading.Event | None = None) -> list[tuple[int, int, int]]:
    """(first byte, size, header seq) of each image `node` receives on `topic`."""
    got: list[tuple[int, int, int]] = []

    def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
        if gate is not None:
            gate.wait(10)
        for frame in frames:
            msg = Image._from_buffer(frame)
            got.append((msg.data[0] if msg.data else -1, len(msg.data), msg.header.seq))

    node.subscribe(topic, *IMAGE, deliver, queue_size, shared_memory=shared_memory)
    return got


def connected(pub: Publication) -> bool:
    return len(pub.links) == 1


@pytest.mark.parametrize("mode", ["1", "always"])
def test_messages_of_every_size_arrive_in_order_through_shared_memory(make_node: Any, monkeypatch: Any,
                                                                      mode: str) -> None:
    monkeypatch.setenv("KAME_SHM", mode)
    talker, listener = make_node("/shm_talker"), make_node("/shm_listener")
    pub = talker.advertise("/shm_images", *IMAGE, queue_size=200)
    got = images_to(listener, "/shm_images")
    assert wait_until(lambda: connected(pub))
    assert isinstance(pub.links[0].sender, shm.ShmSender)
    # small (inline) and large messages interleaved; 3 MB ones outgrow the first ring
    sizes = [10, 100_000, 20, 3_000_000, 1_500_000, 0, 700_000] * 10
    for seq, size in enumerate(sizes):
        msg = image(seq, size)
        msg.header.seq = seq
        pub.publish_frame(serialize_frame(msg))
    assert wait_until(lambda: len(got) == len(sizes), 30)
    assert got == [(seq % 251 if size else -1, size, seq) for seq, size in enumerate(sizes)]
    link = listener.subscriptions["/shm_images"].links[talker.uri]
    assert link.header.get("kame_shm") == "1"


def test_borrowed_buffers_may_be_reused_once_publish_returns(make_node: Any, monkeypatch: Any) -> None:
    monkeypatch.setenv("KAME_SHM", "always")
    talker, listener = make_node("/shm_borrow_talker"), make_node("/shm_borrow_listener")
    pub = talker.advertise("/shm_borrow", *IMAGE, queue_size=100)
    got = images_to(listener, "/shm_borrow")
    assert wait_until(lambda: connected(pub))
    frames = [b"".join(serialize_frame(image(seq, 600_000))) for seq in range(40)]
    buffer = bytearray(len(frames[0]))
    for frame in frames:
        buffer[:] = frame  # the publisher's one buffer, rewritten for every message
        pub.publish_frame([buffer], borrowed=True)
    assert wait_until(lambda: len(got) == 40, 30)
    assert [first for first, _, _ in got] == [seq % 251 for seq in range(40)]


@pytest.mark.parametrize("opt_out", ["environment", "hint"])
def test_opting_out_keeps_plain_tcpros(make_node: Any, monkeypatch: Any, opt_out: str) -> None:
    if opt_out == "environment":
        monkeypatch.setenv("KAME_SHM", "0")
    else:
        monkeypatch.setenv("KAME_SHM", "always")
    talker, listener = make_node("/tcp_talker_" + opt_out), make_node("/tcp_listener_" + opt_out)
    pub = talker.advertise("/tcp_images", *IMAGE, queue_size=10)
    got = images_to(listener, "/tcp_images", shared_memory=opt_out == "environment")
    assert wait_until(lambda: connected(pub))
    assert type(pub.links[0].sender) is Sender
    pub.publish_frame(serialize_frame(image(7, 1_000_000)))
    assert wait_until(lambda: len(got) == 1)
    assert got == [(7, 1_000_000, 0)]
    assert "kame_shm" not in listener.subscriptions["/tcp_images"].links[talker.uri].header


def test_a_slow_subscriber_costs_only_its_oldest_messages(make_node: Any, monkeypatch: Any) -> None:
    monkeypatch.setenv("KAME_SHM", "1")
    talker, listener = make_node("/shm_fast"), make_node("/shm_slow")
    pub = talker.advertise("/shm_slow_topic", *IMAGE, queue_size=2)
    gate = threading.Event()
    got = images_to(listener, "/shm_slow_topic", gate=gate)
    assert wait_until(lambda: connected(pub))
    started = time.monotonic()
    for seq in range(60):
        msg = image(seq, 500_000)
        msg.header.seq = seq
        pub.publish_frame(serialize_frame(msg))
    publishing = time.monotonic() - started
    sender = pub.links[0].sender
    assert sender.dropped > 0  # the ring filled up and the backlog kept only the newest
    gate.set()
    assert wait_until(lambda: got and got[-1][2] == 59)
    seqs = [seq for _, _, seq in got]
    assert seqs == sorted(seqs) and len(seqs) < 60
    assert publishing < 10  # never waited for the subscriber (a generous bound: no timing claim)


def test_latched_message_reaches_a_late_shared_memory_subscriber(make_node: Any, monkeypatch: Any) -> None:
    monkeypatch.setenv("KAME_SHM", "always")
    talker = make_node("/shm_latcher")
    pub = talker.advertise("/shm_latched", *IMAGE, latch=True)
    pub.publish_frame(serialize_frame(image(1, 200_000)))
    pub.publish_frame(serialize_frame(image(2, 300_000)))
    got = images_to(make_node("/shm_late"), "/shm_latched")
    assert wait_until(lambda: len(got) == 1)
    assert got == [(2, 300_000, 0)]


def test_sweep_removes_segments_of_ended_processes_only() -> None:
    ended = subprocess.Popen([sys.executable, "-c", "pass"])
    ended.wait()
    namespace = os.stat("/proc/self/ns/pid").st_ino
    stale = Path(shm.SHM_DIR) / f"kame.{namespace}.{ended.pid}.00ff"
    live = Path(shm.SHM_DIR) / f"kame.{namespace}.{os.getpid()}.00ff"
    stale.write_bytes(b"x")
    live.write_bytes(b"x")
    try:
        assert stale.name in shm.sweep()
        assert not stale.exists() and live.exists()
    finally:
        stale.unlink(missing_ok=True)
        live.unlink(missing_ok=True)


PUBLISHER = """
import sys, time
from kame.node.node import Node, NodeConfig
from kame.node.topics import serialize_frame
from sensor_msgs.msg import Image
node = Node(NodeConfig(sys.argv[3].split(":=")[1], sys.argv[1], "127.0.0.1"))
pub = node.advertise(sys.argv[2], Image._type, Image._md5sum, Image._full_text, queue_size=5)
frame = serialize_frame(Image(height=1, width=2000000, step=2000000, encoding="mono8", data=bytes(2000000)))
while True:
    pub.publish_frame(frame)
    time.sleep(0.005)
"""

SUBSCRIBER = """
import sys, threading
from kame.node.node import Node, NodeConfig
from sensor_msgs.msg import Image
node = Node(NodeConfig(sys.argv[3].split(":=")[1], sys.argv[1], "127.0.0.1"))
count = [0]
def deliver(frames, header):
    count[0] += len(frames)
    if count[0] == 5:
        print("receiving", flush=True)
node.subscribe(sys.argv[2], Image._type, Image._md5sum, Image._full_text, deliver)
threading.Event().wait()
"""


def segments_of(pid: int) -> list[str]:
    return [name for name in os.listdir(shm.SHM_DIR) if name.startswith("kame.") and name.split(".")[2] == str(pid)]


@pytest.mark.parametrize("killed", ["publisher", "subscriber"])
def test_no_segment_is_left_when_either_side_is_killed(master_uri: str, tmp_path: Path, killed: str) -> None:
    env = {**ros_env(tmp_path, master_uri), "KAME_SHM": "1"}
    topic = f"/killed_{killed}"
    logs = {role: open(tmp_path / f"{role}.err", "w") for role in ("publisher", "subscriber")}
    procs = {role: subprocess.Popen([sys.executable, "-c", textwrap.dedent(code), master_uri, topic,
                                     f"__name:=/{role}_{killed}"], env=env,
                                    stdout=subprocess.PIPE, stderr=logs[role], text=True)
             for role, code in (("publisher", PUBLISHER), ("subscriber", SUBSCRIBER))}
    try:
        sub_out = procs["subscriber"].stdout
        assert sub_out is not None
        line: list[str] = []
        reader = threading.Thread(target=lambda: line.append(sub_out.readline()), daemon=True)
        reader.start()
        reader.join(60)
        assert line == ["receiving\n"], {role: (tmp_path / f"{role}.err").read_text() for role in logs}
        victim, survivor = procs[killed], procs["subscriber" if killed == "publisher" else "publisher"]
        victim.send_signal(signal.SIGKILL)
        victim.wait()
        publisher_pid = procs["publisher"].pid
        # the subscriber unlinked each segment once mapped; the publisher unlinks those it
        # announced to a subscriber that never took them
        assert wait_until(lambda: not segments_of(publisher_pid))
        assert survivor.poll() is None
    finally:
        for proc in procs.values():
            if proc.poll() is None:
                proc.send_signal(signal.SIGKILL)
            proc.wait()
            if proc.stdout is not None:
                proc.stdout.close()
        for log in logs.values():
            log.close()
    assert not segments_of(procs["publisher"].pid)
