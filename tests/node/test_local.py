"""Intra-process topics: a node's subscription to its own publication (kame.node.local)."""

from __future__ import annotations

import threading
import xmlrpc.client
from typing import Any

import pytest

from kame.node.node import Node
from kame.node.topics import serialize_frame
from std_msgs.msg import String

from ..support import wait_until

STRING = ("std_msgs/String", String._md5sum, String._full_text)



class Received:
    """What a subscription got: message objects as published, and messages that came as bytes."""

    def __init__(self, gate: threading.Event | None = None) -> None:
        self.objects: list[Any] = []
        self.frames: list[str] = []
        self.headers: list[dict[str, str]] = []
        self.gate = gate

    def deliver_messages(self, msgs: list[Any], header: dict[str, str]) -> None:
        if self.gate is not None:
            self.gate.wait(10)
        self.objects.extend(msgs)
        self.headers.append(header)

    def deliver(self, frames: list[memoryview], header: dict[str, str]) -> None:
        self.frames.extend(String._from_buffer(frame).data for frame in frames)
        self.headers.append(header)

    def subscribe(self, node: Node, topic: str, queue_size: int | None = None) -> None:
        node.subscribe(topic, *STRING, self.deliver, queue_size, message_class=String,
                       deliver_messages=self.deliver_messages)


def test_a_node_hears_its_own_messages_as_the_same_objects(make_node: Any) -> None:
    node = make_node("/nodelet")
    pub = node.advertise("/own", *STRING, queue_size=10, headers={"extra": "yes"})
    got = Received()
    got.subscribe(node, "/own")
    assert wait_until(lambda: len(pub.links) == 1)
    sent = [String(f"m{i}") for i in range(5)]
    for msg in sent:
        pub.publish_message(msg)
    assert wait_until(lambda: len(got.objects) == 5)
    assert all(a is b for a, b in zip(got.objects, sent, strict=True))
    assert got.headers[0]["callerid"] == "/nodelet" and got.headers[0]["extra"] == "yes"
    bus = xmlrpc.client.ServerProxy(node.uri).getBusInfo("/test")[2]
    assert sorted((row[2], row[3]) for row in bus) == [("i", "INTRAPROCESS"), ("o", "INTRAPROCESS")]


def test_bytes_published_in_the_node_arrive_as_bytes(make_node: Any) -> None:
    node = make_node("/relay")
    pub = node.advertise("/relayed", *STRING, queue_size=10)
    got = Received()
    got.subscribe(node, "/relayed")
    assert wait_until(lambda: len(pub.links) == 1)
    pub.publish_frame(serialize_frame(String("as bytes")))
    pub.publish_message(String("as object"))
    assert wait_until(lambda: len(got.frames) + len(got.objects) == 2)
    assert got.frames == ["as bytes"] and [m.data for m in got.objects] == ["as object"]


def test_a_slow_callback_keeps_the_newest_queue_size_and_never_blocks_the_publisher(make_node: Any) -> None:
    node = make_node("/slow_nodelet")
    pub = node.advertise("/slow_own", *STRING, queue_size=3)
    gate = threading.Event()
    got = Received(gate)
    got.subscribe(node, "/slow_own")
    assert wait_until(lambda: len(pub.links) == 1)
    for i in range(50):
        pub.publish_message(String(str(i)))
    gate.set()
    assert wait_until(lambda: got.objects and got.objects[-1].data == "49")
    data = [int(m.data) for m in got.objects]
    # what the callback took before the gate (at most a queue's worth), then the newest 3
    assert data == sorted(data) and len(data) <= 6
    assert pub.links[0].sender.dropped >= 44


def test_a_late_subscriber_in_the_node_gets_the_latched_object(make_node: Any) -> None:
    node = make_node("/latching_nodelet")
    pub = node.advertise("/own_latched", *STRING, latch=True)
    latched = String("kept")
    pub.publish_message(String("first"))
    pub.publish_message(latched)
    got = Received()
    got.subscribe(node, "/own_latched")
    assert wait_until(lambda: len(got.objects) == 1)
    assert got.objects[0] is latched


def test_intraprocess_can_be_turned_off(make_node: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    monkeypatch.setenv("KAME_INTRAPROCESS", "0")
    node = make_node("/plain_node")
    pub = node.advertise("/plain_own", *STRING, queue_size=10)
    got = Received()
    got.subscribe(node, "/plain_own")
    assert wait_until(lambda: len(pub.links) == 1)
    pub.publish_message(String("over TCPROS"))
    assert wait_until(lambda: got.frames == ["over TCPROS"])
    assert got.objects == [] and pub.links[0].transport == "TCPROS"


def test_unadvertising_ends_the_link_and_advertising_again_makes_a_new_one(make_node: Any) -> None:
    node = make_node("/readvertiser")
    got = Received()
    got.subscribe(node, "/again")
    pub = node.advertise("/again", *STRING, queue_size=10)
    assert wait_until(lambda: len(pub.links) == 1)
    node.unadvertise("/again")
    assert wait_until(lambda: node.subscriptions["/again"].connection_count == 0)
    pub = node.advertise("/again", *STRING, queue_size=10)
    assert wait_until(lambda: len(pub.links) == 1)
    pub.publish_message(String("second life"))
    assert wait_until(lambda: [m.data for m in got.objects] == ["second life"])


def test_unsubscribing_in_the_node_ends_the_publications_link(make_node: Any) -> None:
    node = make_node("/unsubscriber")
    pub = node.advertise("/dropped", *STRING, queue_size=10)
    got = Received()
    got.subscribe(node, "/dropped")
    assert wait_until(lambda: len(pub.links) == 1)
    node.unsubscribe("/dropped")
    assert pub.links == [] and pub.local_links == 0
    pub.publish_message(String("nobody"))
    assert got.objects == []


def test_a_link_says_it_is_connected_only_once_the_publication_sends_to_it(make_node: Any,
                                                                          monkeypatch: pytest.MonkeyPatch) -> None:
    # actionlib's wait_for_server takes a connected link for one that hears the result: a result
    # published while the link said connected but the publication had not taken it yet was lost
    node = make_node("/waiter")
    pub = node.advertise("/result", *STRING, queue_size=10)
    taking, go_on = threading.Event(), threading.Event()
    add_link = pub.add_link

    def held_add_link(*args: Any, **kwargs: Any) -> bool:
        taking.set()
        go_on.wait(10)
        return add_link(*args, **kwargs)

    monkeypatch.setattr(pub, "add_link", held_add_link)
    got = Received()
    got.subscribe(node, "/result")
    assert taking.wait(10)
    sub = node.subscriptions["/result"]
    assert sub.connection_count == 0
    go_on.set()
    assert wait_until(lambda: sub.connection_count == 1)
    pub.publish_message(String("the result"))
    assert wait_until(lambda: [m.data for m in got.objects] == ["the result"])
