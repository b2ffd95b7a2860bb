"""Where a message can be dropped, and that each drop is counted there: the publisher's queue
(a socket's Sender, a shared-memory ShmSender, an intra-process LocalSender) and the
subscriber's queue, with a subscriber forced slow. Every message published is either dropped
by the publisher's queue or received, and every one received is either dropped by the
subscription's queue or handed to the callback; getBusStats reports the same counts."""

from __future__ import annotations

import socket
import threading
import xmlrpc.client
from typing import Any

import pytest

from kame.node.node import Node
from kame.node.topics import Publication, Subscription, serialize_frame
from kame.protocol import tcpros
from std_msgs.msg import String

from ..support import wait_until

STRING = ("std_msgs/String", String._md5sum, String._full_text)
TRANSPORTS = ["tcpros", "shm", "intraprocess"]



class Gated:
    """A callback that blocks on its first call until the gate opens, then counts messages."""

    def __init__(self) -> None:
        self.gate = threading.Event()
        self.entered = threading.Event()
        self.count = 0

    def deliver(self, frames: list[Any], header: dict[str, str]) -> None:
        self.entered.set()
        self.gate.wait(20)
        self.count += len(frames)


def pair(make_node: Any, monkeypatch: pytest.MonkeyPatch, transport: str, name: str,
         pub_queue: int, sub_queue: int | None) -> tuple[Node, Publication, Subscription, Gated]:
    monkeypatch.setenv("KAME_SHM", "always" if transport == "shm" else "0")
    talker = make_node(f"/{name}_pub")
    listener = talker if transport == "intraprocess" else make_node(f"/{name}_sub")
    pub = talker.advertise(f"/{name}", *STRING, queue_size=pub_queue)
    slow = Gated()
    sub = listener.subscribe(f"/{name}", *STRING, slow.deliver, sub_queue, message_class=String,
                             deliver_messages=slow.deliver)
    assert wait_until(lambda: len(pub.links) == 1 and sub.connection_count == 1, timeout=20)
    kind = {"tcpros": "Sender", "shm": "ShmSender", "intraprocess": "LocalSender"}[transport]
    assert type(pub.links[0].sender).__name__ == kind
    return listener, pub, sub, slow


def publish(pub: Publication, count: int, size: int) -> None:
    for i in range(count):
        msg = String(f"{i:06d}" + "x" * size)
        pub.publish_message(msg)


def bus_stats(node: Node) -> tuple[list[Any], list[Any]]:
    """This node's publication rows and subscription rows, from its getBusStats."""
    stats: Any = xmlrpc.client.ServerProxy(node.uri).getBusStats("/test")
    pubs, subs, _ = stats[2]
    return [row for _, _, rows in pubs for row in rows], [row for _, rows in subs for row in rows]


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_a_full_publisher_queue_drops_and_counts_its_oldest(make_node: Any, monkeypatch: pytest.MonkeyPatch,
                                                           transport: str) -> None:
    # 100 messages of 200 kB to a subscriber stuck in its first callback: more than socket
    # buffers (or a grown ring) hold, so the publisher's queue of 3 drops.
    listener, pub, sub, slow = pair(make_node, monkeypatch, transport, f"pubq_{transport}", 3, None)
    publish(pub, 1, 0)
    assert slow.entered.wait(10)
    publish(pub, 99, 200_000)
    sender = pub.links[0].sender
    assert sender.dropped > 0
    slow.gate.set()
    link = next(iter(sub.links.values()))
    assert wait_until(lambda: sender.dropped + link.messages_received == 100, timeout=20)
    assert link.dropped == 0
    assert wait_until(lambda: slow.count == link.messages_received, timeout=20)
    pub_rows, _ = bus_stats(pub.node)  # type: ignore[arg-type]  # the talker: a Node
    assert [(row[2], row[4]) for row in pub_rows] == [(100, sender.dropped)]
    _, sub_rows = bus_stats(listener)
    assert [(row[2], row[3]) for row in sub_rows] == [(link.messages_received, 0)]


@pytest.mark.parametrize("transport", TRANSPORTS)
def test_a_full_subscriber_queue_drops_and_counts_its_oldest(make_node: Any, monkeypatch: pytest.MonkeyPatch,
                                                            transport: str) -> None:
    # 200 small messages while the callback is stuck: they all reach the subscriber (the
    # publisher's queue is 1000), whose queue of 1 keeps the newest of each batch.
    listener, pub, sub, slow = pair(make_node, monkeypatch, transport, f"subq_{transport}", 1000, 1)
    publish(pub, 1, 0)
    assert slow.entered.wait(10)
    publish(pub, 199, 0)
    sender = pub.links[0].sender
    link = next(iter(sub.links.values()))
    slow.gate.set()
    assert wait_until(lambda: link.messages_received == 200, timeout=20)
    assert sender.dropped == 0
    assert wait_until(lambda: slow.count + link.dropped == 200, timeout=20)
    assert link.dropped >= 190
    _, sub_rows = bus_stats(listener)
    assert [(row[2], row[3]) for row in sub_rows] == [(200, link.dropped)]


@pytest.mark.parametrize("transport", ["tcpros", "shm"])
def test_a_subscriber_behind_drops_nothing_that_its_queue_holds(make_node: Any, monkeypatch: pytest.MonkeyPatch,
                                                               transport: str) -> None:
    # 5,000 small messages wait in the socket while the callback is stuck; each read then takes
    # at most queue_size of them, so none is dropped. Reads sized by a mean frame size (which
    # starts high, and stopped short of the real size) took more and dropped the excess.
    _, pub, sub, slow = pair(make_node, monkeypatch, transport, f"fits_{transport}", 10_000, 1000)
    publish(pub, 1, 0)
    assert slow.entered.wait(10)
    publish(pub, 4999, 0)
    slow.gate.set()
    link = next(iter(sub.links.values()))
    assert wait_until(lambda: link.messages_received == 5000 and slow.count + link.dropped == 5000, timeout=20)
    assert (slow.count, link.dropped, pub.links[0].sender.dropped) == (5000, 0, 0)


def test_a_stream_read_with_the_handshake_is_handed_on_queue_size_at_a_time(make_node: Any) -> None:
    # A publisher already flowing when the subscriber's header read comes: 3,000 messages right
    # behind its header, in one send, arrive with it (the read takes up to 64 KiB). They were
    # handed on as one batch, and a queue_size of 1000 dropped 2,000 of them.
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    fake = make_node("/flowing_pub")
    fake.advertise("/flowing", *STRING)
    fake.tcpros_port = server.getsockname()[1]
    done = threading.Event()

    def serve() -> None:
        conn, _ = server.accept()
        with conn:
            conn.recv(65536)
            header = tcpros.encode_header(tcpros.publisher_reply_fields(
                callerid="/flowing_pub", topic="/flowing", spec=tcpros.TopicSpec(*STRING)))
            conn.sendall(header + b"".join(serialize_frame(String(f"{i:06d}"))[0] for i in range(3000)))
            done.wait(20)

    threading.Thread(target=serve, daemon=True).start()
    got: list[str] = []
    sub = make_node("/flowing_sub").subscribe("/flowing", *STRING,
                                              lambda frames, header: got.extend(String._from_buffer(f).data
                                                                                for f in frames), 1000)
    try:
        assert wait_until(lambda: len(got) + sum(link.dropped for link in sub.links.values()) >= 3000, timeout=20)
        link = next(iter(sub.links.values()))
        assert (link.messages_received, link.dropped) == (3000, 0)
        assert got == [f"{i:06d}" for i in range(3000)]
    finally:
        done.set()
        server.close()
