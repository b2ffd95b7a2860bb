"""A Node owns its threads: shutdown ends and joins every one, whatever each was waiting on;
the slave API decides a call's arity from the handler's signature, so a handler's own
TypeError is logged with its traceback; tcp_nodelay and buff_size reach the sockets."""

from __future__ import annotations

import socket
import threading
import xmlrpc.client
from typing import Any

import pytest

from kame.node.topics import serialize_frame
from std_msgs.msg import String

from ..support import free_port, wait_until

STRING = ("std_msgs/String", String._md5sum, String._full_text)



def _empty_response(data: bytes) -> tuple[bool, bytes | str]:
    return True, b""


def test_shutdown_leaves_no_thread_of_the_node_running(make_node: Any, master_uri: str) -> None:
    before = set(threading.enumerate())
    talker, listener = make_node("/owned_talker"), make_node("/owned_listener")
    # a connected topic: the talker's handshake worker, the listener's receiver
    pub = talker.advertise("/owned_chatter", *STRING)
    got: list[int] = []
    listener.subscribe("/owned_chatter", *STRING, lambda frames, header: got.append(len(frames)))
    assert wait_until(lambda: pub.links)
    # a persistent service connection: a worker answering on it until the client goes
    talker.advertise_service("/owned_service", "std_srvs/Empty", "d41d8cd98f00b204e9800998ecf8427e",
                             _empty_response)
    client = listener.service_client("/owned_service", "std_srvs/Empty", "d41d8cd98f00b204e9800998ecf8427e",
                                     persistent=True)
    client.call(b"")
    # an XML-RPC client that keeps its connection open: a connection thread of the slave API
    keep_alive = xmlrpc.client.ServerProxy(talker.uri)
    assert keep_alive.getPid("/test")[0] == 1
    # a TCPROS connection that never sends its header: a worker reading it (for up to 10 s)
    silent = socket.create_connection(("127.0.0.1", talker.tcpros_port))
    # a publisher the master lists but nobody serves: the listener retries with a growing delay
    master = xmlrpc.client.ServerProxy(master_uri)
    ghost_uri = f"http://127.0.0.1:{free_port()}/"
    master.registerPublisher("/ghost", "/owned_ghost", "std_msgs/String", ghost_uri)
    try:
        listener.subscribe("/owned_ghost", *STRING, lambda frames, header: None)
        assert wait_until(lambda: any(t.name == "kame-connect/owned_ghost" for t in threading.enumerate()))
        started = set(threading.enumerate()) - before
        assert {t.name for t in started} >= {"kame-sub/owned_chatter", "kame-handshake", "kame-xmlrpc-conn",
                                             "kame-connect/owned_ghost"}
        listener.shutdown("test over")
        talker.shutdown("test over")
        stray = [t.name for t in set(threading.enumerate()) - before]
        assert stray == []
    finally:
        master.unregisterPublisher("/ghost", "/owned_ghost", ghost_uri)
        silent.close()
        client.close()


def test_a_handlers_own_type_error_is_logged_once_not_taken_for_arity(
        make_node: Any, caplog: pytest.LogCaptureFixture) -> None:
    node = make_node("/arity")
    calls: list[tuple[str, Any]] = []

    def broken(key: str, value: Any) -> None:
        calls.append((key, value))
        len(value)  # an int has no len(): a TypeError inside the callback

    node.on_param_update.append(broken)
    proxy = xmlrpc.client.ServerProxy(node.uri)
    code, text, _ = proxy.paramUpdate("/master", "/some_key", 3)
    assert code == 0 and "has no len()" in text
    assert calls == [("/some_key", 3)]
    failures = [r for r in caplog.records if "paramUpdate failed" in r.getMessage()]
    assert len(failures) == 1 and failures[0].exc_info is not None
    assert failures[0].exc_info[0] is TypeError
    # a call with the wrong number of arguments is still refused as such, without calling anything
    assert proxy.paramUpdate("/master", "/some_key") == [-1, "Error: bad call arity", 0]
    assert calls == [("/some_key", 3)]


def _nodelay(sock: socket.socket) -> bool:
    return bool(sock.getsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY))


@pytest.mark.parametrize(("subscriber_asks", "publisher_default"), [(True, False), (False, False), (False, True)])
def test_tcp_nodelay_goes_in_the_header_and_onto_the_publishers_socket(
        make_node: Any, subscriber_asks: bool, publisher_default: bool) -> None:
    talker, listener = make_node("/nodelay_talker"), make_node("/nodelay_listener")
    pub = talker.advertise("/nodelay", *STRING, tcp_nodelay=publisher_default)
    sub = listener.subscribe("/nodelay", *STRING, lambda frames, header: None, tcp_nodelay=subscriber_asks)
    assert wait_until(lambda: pub.links and sub.connection_count)
    (link,) = sub.links.values()
    assert link.sock is not None
    # the subscriber's own side, and what the publisher set on its side because of the header
    assert _nodelay(link.sock) is subscriber_asks
    assert _nodelay(pub.links[0].sender.sock) is subscriber_asks  # the header says "0" or "1"


def test_a_subscriber_header_without_tcp_nodelay_gets_the_publishers_choice(make_node: Any) -> None:
    from kame.net.handshake import read_header, write_header

    talker = make_node("/nodelay_default")
    pub = talker.advertise("/nodelay_default", *STRING, tcp_nodelay=True)
    with socket.create_connection(("127.0.0.1", talker.tcpros_port)) as sock:
        write_header(sock, {"callerid": "/raw", "topic": "/nodelay_default", "type": STRING[0], "md5sum": STRING[1]})
        assert "error" not in read_header(sock, 5.0)
        assert wait_until(lambda: pub.links)
        assert _nodelay(pub.links[0].sender.sock)


def test_buff_size_is_what_each_read_asks_for(make_node: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    from kame.net import stream

    asked: list[int] = []
    real_init = stream.Receiver.__init__

    def recording_init(self: Any, *args: Any, **kwargs: Any) -> None:
        asked.append(kwargs["chunk_size"])
        real_init(self, *args, **kwargs)

    monkeypatch.setattr(stream.Receiver, "__init__", recording_init)
    talker, listener = make_node("/buff_talker"), make_node("/buff_listener")
    pub = talker.advertise("/buff", *STRING)
    got: list[str] = []
    listener.subscribe("/buff", *STRING, lambda frames, header: got.extend(
        String().deserialize(f).data for f in frames), buff_size=8192)
    assert wait_until(lambda: pub.links)
    assert asked == [8192]
    big = "x" * 100_000  # larger than buff_size: still arrives whole
    pub.publish_frame(serialize_frame(String(data=big)))
    assert wait_until(lambda: got)
    assert got == [big]
