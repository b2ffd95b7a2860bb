"""kame's Node end to end on loopback: topics, latching, queue limits, services, bad peers, shutdown."""

from __future__ import annotations

import io
import logging
import socket
import struct
import threading
import time
import xmlrpc.client
from typing import Any

import pytest

from kame.node.master_proxy import MasterError
from kame.node.node import Node
from kame.node.services import ServiceError
from kame.node.topics import serialize_frame
from kame.protocol import tcpros
from std_msgs.msg import String

from ..support import free_port, wait_until

STRING = ("std_msgs/String", String._md5sum, String._full_text)


def collect(node: Node, topic: str, queue_size: int | None = None) -> tuple[list[str], threading.Event]:
    got: list[str] = []
    event = threading.Event()

    def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
        for frame in frames:
            got.append(String().deserialize(frame).data)
        event.set()

    node.subscribe(topic, *STRING, deliver, queue_size)
    return got, event



def test_publish_subscribe_in_order(make_node: Any) -> None:
    talker, listener = make_node("/talker"), make_node("/listener")
    pub = talker.advertise("/chatter", *STRING)
    got, _ = collect(listener, "/chatter")
    assert wait_until(lambda: len(pub.links) == 1)
    for i in range(1000):
        pub.publish_frame(serialize_frame(String(f"hello {i}")))
    assert wait_until(lambda: len(got) == 1000)
    assert got == [f"hello {i}" for i in range(1000)]


def test_late_subscriber_gets_the_latched_message(make_node: Any) -> None:
    talker = make_node("/latcher")
    pub = talker.advertise("/latched", *STRING, latch=True)
    pub.publish_frame(serialize_frame(String("first")))
    pub.publish_frame(serialize_frame(String("kept")))
    got, event = collect(make_node("/late"), "/latched")
    assert event.wait(5)
    assert got == ["kept"]


def test_large_messages_arrive_whole(make_node: Any) -> None:
    from sensor_msgs.msg import Image

    talker, listener = make_node("/camera"), make_node("/viewer")
    pub = talker.advertise("/image", "sensor_msgs/Image", Image._md5sum, Image._full_text, queue_size=2)
    images: list[Image] = []
    listener.subscribe("/image", "sensor_msgs/Image", Image._md5sum, Image._full_text,
                       lambda frames, h: images.extend(Image().deserialize(f) for f in frames))
    assert wait_until(lambda: len(pub.links) == 1)
    payload = bytes(range(256)) * (1920 * 1080 * 3 // 256)
    pub.publish_frame(serialize_frame(Image(height=1080, width=1920, encoding="rgb8", step=5760, data=payload)))
    assert wait_until(lambda: len(images) == 1, 10)
    assert images[0].data == payload and images[0].encoding == "rgb8"


def test_md5_mismatch_is_refused_with_the_real_text(make_node: Any) -> None:
    talker = make_node("/typed")
    talker.advertise("/typed_topic", *STRING)
    sock = socket.create_connection(("127.0.0.1", talker.tcpros_port), timeout=5)
    sock.sendall(tcpros.encode_header(tcpros.subscriber_header_fields(
        callerid="/wrong", topic="/typed_topic", type="std_msgs/Int32", md5sum="da5909fbe378aeaf85e547e830cc1bb7")))
    reply = sock.recv(65536)
    sock.close()
    assert tcpros.decode_header(reply) == {"error": "topic types do not match: [std_msgs/Int32] vs. [std_msgs/String]"}


def test_a_garbage_publisher_is_dropped_and_the_node_carries_on(make_node: Any, master_uri: str) -> None:
    # A fake publisher: answers requestTopic through a real node's XML-RPC, but its TCPROS
    # stream sends a valid header and then a 4 GB length prefix.
    listener = make_node("/victim")
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    liar = make_node("/liar")
    liar.advertise("/victim_topic", *STRING)
    liar.tcpros_port = server.getsockname()[1]  # requestTopic now points at the fake server

    def serve() -> None:
        conn, _ = server.accept()
        conn.recv(65536)
        conn.sendall(tcpros.encode_header(tcpros.publisher_reply_fields(
            callerid="/liar", topic="/victim_topic", spec=tcpros.TopicSpec(*STRING))))
        conn.sendall(struct.pack("<I", 0xFFFFFFFF) + b"xx")
        time.sleep(0.5)
        conn.close()

    threading.Thread(target=serve, daemon=True).start()
    got, _ = collect(listener, "/victim_topic")
    time.sleep(1.0)
    server.close()
    assert got == []
    # The node still works.
    pub = make_node("/honest").advertise("/after", *STRING)
    after, event = collect(listener, "/after")
    assert wait_until(lambda: len(pub.links) == 1)
    pub.publish_frame(serialize_frame(String("fine")))
    assert event.wait(5) and after == ["fine"]


def _fake_publisher(make_node: Any, name: str, topic: str, spec: tuple[str, str, str],
                    send: Any) -> tuple[socket.socket, threading.Event]:
    """A publisher whose requestTopic is a real node's but whose TCPROS stream is `send(conn)`;
    the event is set once we (the subscriber) hang up on it."""
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    fake = make_node(name)
    fake.advertise(topic, *spec)
    fake.tcpros_port = server.getsockname()[1]
    dropped = threading.Event()

    def serve() -> None:
        conn, _ = server.accept()
        with conn:
            conn.recv(65536)
            conn.sendall(tcpros.encode_header(tcpros.publisher_reply_fields(
                callerid=name, topic=topic, spec=tcpros.TopicSpec(*spec))))
            send(conn)
            conn.settimeout(30)
            if conn.recv(1) == b"":
                dropped.set()

    threading.Thread(target=serve, daemon=True).start()
    return server, dropped


def test_a_frame_longer_than_a_fixed_size_type_drops_the_publisher(make_node: Any,
                                                                    caplog: pytest.LogCaptureFixture) -> None:
    # A Twist is 48 bytes, always: a 1 GiB frame announced on it used to be buffered as it came.
    import logging

    from geometry_msgs.msg import Twist

    twist = ("geometry_msgs/Twist", Twist._md5sum, Twist._full_text)
    server, dropped = _fake_publisher(make_node, "/big_twister", "/twist", twist,
                                      lambda conn: conn.sendall(struct.pack("<I", (1 << 30) - 1) + b"\0" * 64))
    listener = make_node("/twist_listener")
    got: list[memoryview] = []
    with caplog.at_level(logging.ERROR, logger="kame.topics"):
        listener.subscribe("/twist", *twist, lambda frames, header: got.extend(frames))
        assert dropped.wait(10)
    server.close()
    assert got == []
    assert listener.subscriptions["/twist"].max_frame == 48
    assert [r.getMessage() for r in caplog.records if "frame of 1073741823 bytes refused (limit 48)" in r.getMessage()]


def test_a_publisher_that_stalls_mid_frame_is_dropped(make_node: Any, caplog: pytest.LogCaptureFixture,
                                                       monkeypatch: pytest.MonkeyPatch) -> None:
    import logging

    from kame.node import topics

    monkeypatch.setattr(topics, "STALL_TIMEOUT", 0.3)
    server, dropped = _fake_publisher(make_node, "/trickler", "/trickled", STRING,
                                      lambda conn: conn.sendall(struct.pack("<I", 1000) + b"x" * 10))
    listener = make_node("/trickle_listener")
    with caplog.at_level(logging.ERROR, logger="kame.topics"):
        got, _ = collect(listener, "/trickled")
        assert dropped.wait(10)
    server.close()
    assert got == []
    lines = [r.getMessage() for r in caplog.records if "/trickled" in r.getMessage()]
    assert len(lines) == 1 and "no byte for 0.3 s in the middle of a message" in lines[0]


@pytest.mark.parametrize("queue_size", [5, 0])
def test_a_slow_subscriber_loses_its_oldest_and_slows_no_one(make_node: Any, monkeypatch: pytest.MonkeyPatch,
                                                            queue_size: int) -> None:
    # One subscriber takes a second per message, another keeps up: the publisher keeps at most
    # queue_size frames for the slow one (without a queue_size: UNQUEUED_BACKLOG bytes, here
    # 2 MB; it used to keep them all), dropping the oldest, and the fast one gets everything.
    from kame.node import topics

    monkeypatch.setattr(topics, "UNQUEUED_BACKLOG", 2 << 20)
    pub = make_node("/burst_pub").advertise("/burst", *STRING, queue_size=queue_size)
    fast: list[str] = []
    fast_done = threading.Event()
    slow_calls = [0]
    release = threading.Event()

    def on_fast(frames: list[memoryview], header: dict[str, str]) -> None:
        fast.extend(String().deserialize(frame).data[:8] for frame in frames)
        if len(fast) >= 100:
            fast_done.set()

    def on_slow(frames: list[memoryview], header: dict[str, str]) -> None:
        slow_calls[0] += 1
        release.wait(1.0)  # a second per message, until the test is over

    make_node("/fast_sub").subscribe("/burst", *STRING, on_fast)
    make_node("/slow_sub").subscribe("/burst", *STRING, on_slow, queue_size=1)
    assert wait_until(lambda: len(pub.links) == 2)
    backlogs = []
    for i in range(100):  # 20 MB: far more than the slow subscriber's socket buffers hold
        pub.publish_frame(serialize_frame(String(f"{i:08d}" + "x" * 200_000)))
        backlogs.append((max(len(link.sender._backlog) for link in pub.links),
                         max(link.sender._backlog_bytes for link in pub.links)))
        time.sleep(0.005)
    assert fast_done.wait(20)
    release.set()
    assert fast == [f"{i:08d}" for i in range(100)]
    if queue_size:
        assert max(frames for frames, _ in backlogs) <= queue_size
    else:
        assert max(size for _, size in backlogs) <= (2 << 20) + 200_100
    slow_link = next(link for link in pub.links if link.callerid == "/slow_sub")
    assert slow_link.sender.dropped > 0 and slow_calls[0] < 20


def test_service_calls_persistent_and_not(make_node: Any) -> None:
    from std_srvs.srv import SetBool, SetBoolRequest, SetBoolResponse

    server_node, client_node = make_node("/srv_server"), make_node("/srv_client")

    def handle(data: bytes) -> tuple[bool, bytes | str]:
        request = SetBoolRequest().deserialize(data)
        if not request.data:
            return False, "refused"
        buff = io.BytesIO()
        SetBoolResponse(success=True, message="ok").serialize(buff)
        return True, buff.getvalue()

    server_node.advertise_service("/set", SetBool._type, SetBool._md5sum, handle)

    def request(value: bool) -> bytes:
        buff = io.BytesIO()
        SetBoolRequest(data=value).serialize(buff)
        return buff.getvalue()

    for persistent in (False, True):
        client = client_node.service_client("/set", SetBool._type, SetBool._md5sum, persistent)
        for _ in range(3):
            assert SetBoolResponse().deserialize(client.call(request(True))).message == "ok"
        with pytest.raises(ServiceError, match="responded with an error: refused"):
            client.call(request(False))
        client.close()
    missing = client_node.service_client("/nope", SetBool._type, SetBool._md5sum)
    with pytest.raises(MasterError):
        missing.call(request(True))


def test_shutdown_unregisters_everything(make_node: Any, master_uri: str) -> None:
    node = make_node("/short_lived")
    node.advertise("/a_topic", *STRING)
    node.subscribe("/b_topic", *STRING, lambda frames, header: None)
    node.advertise_service("/c_service", "std_srvs/Empty", "d41d8cd98f00b204e9800998ecf8427e",
                           lambda data: (True, b""))
    master = xmlrpc.client.ServerProxy(master_uri)
    assert master.lookupNode("/test", "/short_lived")[0] == 1
    node.shutdown("done")
    assert master.lookupNode("/test", "/short_lived")[0] == -1


def test_slave_api_answers_what_tools_ask(make_node: Any) -> None:
    node = make_node("/introspected")
    node.advertise("/out", *STRING)
    node.subscribe("/in", *STRING, lambda frames, header: None)
    proxy = xmlrpc.client.ServerProxy(node.uri)
    assert proxy.getPublications("/x") == [1, "publications", [["/out", "std_msgs/String"]]]
    assert proxy.getSubscriptions("/x") == [1, "subscriptions", [["/in", "std_msgs/String"]]]
    assert proxy.getPid("/x")[2] > 0
    assert proxy.requestTopic("/x", "/nope", [["TCPROS"]]) == [-1, "Not a publisher of [/nope]", []]
    assert proxy.requestTopic("/x", "/out", [["UDPROS"]]) == [0, "no supported protocol implementations", []]
    code, _, params = proxy.requestTopic("/x", "/out", [["TCPROS"]])
    assert code == 1 and params == ["TCPROS", "127.0.0.1", node.tcpros_port]
    assert proxy.getBusInfo("/x")[0] == 1
    with pytest.raises(xmlrpc.client.Fault, match='method "bogus" is not supported'):
        proxy.bogus("/x")


def test_bad_slave_api_arguments_are_refused_and_keep_the_connections(make_node: Any) -> None:
    # A publisherUpdate whose list is not a list of URLs used to replace the publisher set with
    # its garbage (a string became one "publisher" per character): the real publisher was
    # dropped and the subscription went quiet. rospy refuses such calls with -1; so do we.
    listener = make_node("/guarded")
    got, event = collect(listener, "/guarded_topic")
    pub = make_node("/guard_pub").advertise("/guarded_topic", *STRING)
    assert wait_until(lambda: len(pub.links) == 1)
    proxy = xmlrpc.client.ServerProxy(listener.uri)
    bad_updates: list[tuple[Any, Any, str]] = [
        ("/guarded_topic", "http://127.0.0.1:1/", "ERROR: param [publishers] must be a list"),
        ("/guarded_topic", 5, "ERROR: param [publishers] must be a list"),
        ("/guarded_topic", [5], "ERROR: param [publishers] must be a list of strings"),
        ("/guarded_topic", ["not a uri"], "ERROR: param [publishers] does not contain valid URLs [not a uri]"),
        ("/guarded_topic", ["http://"], "ERROR: param [publishers] does not contain valid URLs [http://]"),
        (["/guarded_topic"], [], "ERROR: parameter [topic] must be a non-empty string"),
        ("", [], "ERROR: parameter [topic] must be a non-empty string"),
        ("http://x:1/", [], "ERROR: parameter [topic] contains illegal chars"),
    ]
    for topic, publishers, text in bad_updates:
        assert proxy.publisherUpdate("/evil", topic, publishers) == [-1, text, 0]
    assert proxy.requestTopic("/evil", {"a": 1}, [["TCPROS"]]) == [
        -1, "ERROR: parameter [topic] must be a non-empty string", []]
    assert proxy.requestTopic("/evil", "/guarded_topic", "TCPROS") == [
        -1, "ERROR: parameter [protocols] must be specified and non-empty", []]
    assert proxy.paramUpdate("/evil", 5, 1) == [-1, "ERROR: parameter [parameter_key] must be a non-empty string", 0]
    assert proxy.paramUpdate("/evil", ["/a"], 1)[0] == -1
    assert proxy.publisherUpdate("/evil", "/guarded_topic") == [-1, "Error: bad call arity", 0]
    # Nothing above touched the subscription: the publisher is still connected and delivering.
    assert len(listener.subscriptions["/guarded_topic"].links) == 1
    assert len(pub.links) == 1
    pub.publish_frame(serialize_frame(String("still here")))
    assert event.wait(5) and got == ["still here"]


def test_a_handshake_trickling_in_is_cut_off(make_node: Any, monkeypatch: pytest.MonkeyPatch) -> None:
    # The handshake timeout was per recv: a byte every few seconds held the connection (a socket
    # and a thread) for as long as the claimed header took, up to 1 MiB of bytes. The whole
    # header must now arrive within HANDSHAKE_TIMEOUT.
    from kame.node import node as node_module

    monkeypatch.setattr(node_module, "HANDSHAKE_TIMEOUT", 0.5)
    talker = make_node("/trickled")
    pub = talker.advertise("/trickled_topic", *STRING)
    sock = socket.create_connection(("127.0.0.1", talker.tcpros_port), timeout=5)
    sock.sendall(struct.pack("<I", 1000))
    start = time.monotonic()
    closed = False
    while time.monotonic() - start < 6:
        try:
            sock.sendall(b"x")
            sock.settimeout(0.1)
            closed = sock.recv(100) == b""
        except TimeoutError:
            continue
        except OSError:
            closed = True
        if closed:
            break
    sock.close()
    assert closed and time.monotonic() - start < 5  # 0.5 s allowed; trickling all of it takes 100 s
    # and honest subscribers still get in
    got, event = collect(make_node("/after_trickle"), "/trickled_topic")
    assert wait_until(lambda: len(pub.links) == 1)
    pub.publish_frame(serialize_frame(String("ok")))
    assert event.wait(5) and got == ["ok"]


def test_a_refused_service_response_closes_the_persistent_connection(make_node: Any, master_uri: str) -> None:
    # A response refused for its size raised ServiceError but kept the persistent socket, so the
    # next call read its answer from the middle of the refused one: here the server's planted "evil".
    from kame.node import services

    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(4)
    connections: list[int] = []

    def serve() -> None:
        while True:
            try:
                conn, _ = server.accept()
            except OSError:
                return
            connections.append(1)
            conn.recv(65536)
            conn.sendall(tcpros.encode_header({"callerid": "/fake", "md5sum": "*", "type": "x/Y"}))
            calls = 0
            while conn.recv(65536):
                calls += 1
                if calls == 2:  # a refused size, then bytes that parse as a whole response
                    refused = struct.pack("<BI", 1, services.MAX_REQUEST + 1)
                    conn.sendall(refused + tcpros.encode_service_response(True, b"evil"))
                else:
                    conn.sendall(tcpros.encode_service_response(True, b"good"))
            conn.close()

    threading.Thread(target=serve, daemon=True).start()
    master = xmlrpc.client.ServerProxy(master_uri)
    port = server.getsockname()[1]
    assert master.registerService("/fake", "/fake_srv", f"rosrpc://127.0.0.1:{port}", "http://127.0.0.1:1/")[0] == 1
    try:
        client = make_node("/fake_client").service_client("/fake_srv", "x/Y", "*", persistent=True)
        assert client.call(b"1") == b"good"
        with pytest.raises(ServiceError, match="bytes refused"):
            client.call(b"2")
        assert client.call(b"3") == b"good"
        assert len(connections) == 2
        client.close()
    finally:
        master.unregisterService("/fake", "/fake_srv", f"rosrpc://127.0.0.1:{port}")
        server.close()


def test_a_lying_request_length_reserves_no_gigabyte(make_node: Any) -> None:
    # The service server read a request with recv(claimed size): a client claiming ~1 GiB and
    # sending three bytes made the node allocate ~1 GiB per connection.
    import tracemalloc

    node = make_node("/lied_to")
    node.advertise_service("/lied_srv", "std_srvs/Empty", "d41d8cd98f00b204e9800998ecf8427e", lambda data: (True, b""))
    tracemalloc.start()
    try:
        sock = socket.create_connection(("127.0.0.1", node.tcpros_port), timeout=5)
        sock.sendall(tcpros.encode_header(tcpros.service_client_header_fields(
            callerid="/liar", service="/lied_srv", md5sum="*")))
        sock.recv(65536)
        sock.sendall(struct.pack("<I", (1 << 30) - 1) + b"abc")
        time.sleep(0.5)
        _, peak = tracemalloc.get_traced_memory()
        sock.close()
    finally:
        tracemalloc.stop()
    assert peak < 64 << 20, peak


def test_a_flood_of_bad_connections_is_a_few_log_lines(make_node: Any, caplog: pytest.LogCaptureFixture) -> None:
    # Every bad connection attempt was a warning line: 3000 garbage or connect-and-close clients
    # gave 3000 lines. Connect-and-close (a port probe) is now silent, and the rest is throttled
    # to a line a second with a count.
    import logging

    talker = make_node("/flooded")
    pub = talker.advertise("/flooded_topic", *STRING)
    started = time.monotonic()
    with caplog.at_level(logging.WARNING, logger="kame.node"):
        for i in range(100):
            sock = socket.create_connection(("127.0.0.1", talker.tcpros_port), timeout=5)
            if i % 2:
                sock.sendall(b"\xde\xad\xbe\xef" * 4)  # a 4 GB header length
                try:
                    sock.recv(100)  # until the node hangs up
                except OSError:
                    pass
            sock.close()
        time.sleep(0.3)
    elapsed = time.monotonic() - started
    lines = [r.getMessage() for r in caplog.records if "bad TCPROS connection attempt" in r.getMessage()]
    # a line a second at most: 3 when the flood takes under two seconds, one more per extra
    # second a loaded machine makes it last (50 bad attempts would be 50 lines)
    assert 1 <= len(lines) <= max(3, 2 + int(elapsed)), (lines, elapsed)
    assert "connection header of" in lines[0] and "127.0.0.1:" in lines[0]
    got, event = collect(make_node("/after_flood"), "/flooded_topic")
    assert wait_until(lambda: len(pub.links) == 1)
    pub.publish_frame(serialize_frame(String("ok")))
    assert event.wait(5) and got == ["ok"]


def test_a_malformed_header_gets_an_error_header_naming_the_problem(make_node: Any) -> None:
    # A field without '=' used to close the connection without a word to the peer.
    talker = make_node("/told")
    talker.advertise("/told_topic", *STRING)
    body = b"".join(struct.pack("<I", len(f)) + f for f in (b"topic=/told_topic", b"callerid=/x", b"no_equals"))
    with socket.create_connection(("127.0.0.1", talker.tcpros_port), timeout=5) as sock:
        sock.sendall(struct.pack("<I", len(body)) + body)
        reply = b""
        while chunk := sock.recv(65536):
            reply += chunk
    fields = tcpros.decode_header(reply)
    assert fields == {"error": "malformed connection header: field without '=': b'no_equals'"}


def test_a_consumer_failure_that_ends_a_link_is_logged(make_node: Any, caplog: pytest.LogCaptureFixture) -> None:
    # An exception from a subscription's consumer (other than the transport's own errors) ended
    # the link to that publisher without a word: the subscription just went quiet.
    import logging

    def deliver(frames: list[memoryview], header: dict[str, str]) -> None:
        raise RuntimeError("consumer bug")

    listener = make_node("/failing_consumer")
    listener.subscribe("/consumed", *STRING, deliver)
    pub = make_node("/consumed_pub").advertise("/consumed", *STRING)
    assert wait_until(lambda: len(pub.links) == 1)
    with caplog.at_level(logging.ERROR, logger="kame.topics"):
        pub.publish_frame(serialize_frame(String("x")))
        assert wait_until(lambda: any("RuntimeError: consumer bug" in r.getMessage() for r in caplog.records))
    assert any("dropping the connection to /consumed_pub on /consumed" in r.getMessage() for r in caplog.records)


def test_a_failing_service_handler_is_logged_and_the_socket_closed(make_node: Any,
                                                                    caplog: pytest.LogCaptureFixture) -> None:
    # A node-level service handler's exception went to the handshake worker pool, which swallows
    # job errors: the client saw the connection close, and nothing was logged anywhere.
    import logging

    def handler(data: bytes) -> tuple[bool, bytes]:
        raise RuntimeError("handler bug")

    server = make_node("/buggy_server")
    server.advertise_service("/buggy", "std_srvs/Empty", "d41d8cd98f00b204e9800998ecf8427e", handler)
    client = make_node("/buggy_client").service_client("/buggy", "std_srvs/Empty", "d41d8cd98f00b204e9800998ecf8427e")
    with caplog.at_level(logging.ERROR, logger="kame.node"):
        start = time.monotonic()
        with pytest.raises(ServiceError, match="transport error"):
            client.call(b"", timeout=5)
        assert time.monotonic() - start < 4  # closed at once, not left to the 5 s timeout
        assert wait_until(lambda: any("RuntimeError: handler bug" in (r.exc_text or "") or
                                      "handler bug" in str(r.exc_info) for r in caplog.records))


def test_header_seq_numbers_are_unique_across_publishing_threads(make_node: Any) -> None:
    node = make_node("/seq_pub")
    publication = node.advertise("/seq", String._type, String._md5sum, String._full_text)
    taken: list[list[int]] = [[] for _ in range(4)]

    def take(into: list[int]) -> None:
        into.extend(publication.next_seq() for _ in range(5000))

    threads = [threading.Thread(target=take, args=(into,)) for into in taken]
    for thread in threads:
        thread.start()
    for thread in threads:
        thread.join()
    numbers = sorted(n for into in taken for n in into)
    assert numbers == list(range(1, 20001))


def _one_warning_about(make_node: Any, master_uri: str, caplog: pytest.LogCaptureFixture, ghost_uri: str,
                       topic: str) -> str:
    """The one warning a subscriber gives about the publisher /ghost registered at `ghost_uri`,
    after five failed attempts to reach it."""
    caplog.set_level(logging.DEBUG, logger="kame.topics")
    master = xmlrpc.client.ServerProxy(master_uri)
    assert master.registerPublisher("/ghost", topic, "std_msgs/String", ghost_uri)[0] == 1
    try:
        listener = make_node("/listener")
        collect(listener, topic)

        def attempts() -> int:
            return sum("connecting to" in r.getMessage() and "failed" in r.getMessage() for r in caplog.records)

        assert wait_until(lambda: attempts() >= 5, timeout=10), caplog.text
        warnings = [r.getMessage() for r in caplog.records if r.levelno == logging.WARNING]
        assert len(warnings) == 1, warnings
        return warnings[0]
    finally:
        master.unregisterPublisher("/ghost", topic, ghost_uri)


def test_a_publisher_at_an_unusable_address_is_one_warning_naming_it_and_the_fix(
        make_node: Any, master_uri: str, caplog: pytest.LogCaptureFixture) -> None:
    ghost_uri = "http://ghost.invalid:11311/"  # a name no machine resolves
    warning = _one_warning_about(make_node, master_uri, caplog, ghost_uri, "/unreachable")
    assert warning.startswith(f"cannot reach publisher /ghost of /unreachable at {ghost_uri}: "
                              "its name does not resolve on this machine."), warning
    assert "ROS_IP" in warning and "ROS_HOSTNAME" in warning


def test_a_dead_publisher_on_this_machine_is_reported_dead_not_as_an_address_problem(
        make_node: Any, master_uri: str, caplog: pytest.LogCaptureFixture) -> None:
    # A SIGKILLed local talker's registration: the advice was to set ROS_IP on its machine
    ghost_uri = f"http://127.0.0.1:{free_port()}/"  # nothing listens: the process is gone
    warning = _one_warning_about(make_node, master_uri, caplog, ghost_uri, "/orphaned")
    assert warning == (f"publisher /ghost of /orphaned is dead: nothing listens at {ghost_uri} on this machine any "
                       "more, so its process ended without unregistering (killed, or crashed); the master lists it "
                       "until `rosnode cleanup` removes it or it starts again")


def test_a_publisher_killed_mid_frame_costs_only_its_half_message(make_node: Any) -> None:
    # A publisher process dies (SIGKILL, power) half-way through a frame: the subscriber keeps the
    # whole messages before it, drops the half, and goes on hearing the topic's other publishers.
    server = socket.socket()
    server.bind(("127.0.0.1", 0))
    server.listen(1)
    dying = make_node("/dying_talker")
    dying.advertise("/mid", *STRING)
    dying.tcpros_port = server.getsockname()[1]

    def serve() -> None:
        conn, _ = server.accept()
        conn.recv(65536)
        conn.sendall(tcpros.encode_header(tcpros.publisher_reply_fields(
            callerid="/dying_talker", topic="/mid", spec=tcpros.TopicSpec(*STRING))))
        whole = struct.pack("<I", 5) + b"whole"
        conn.sendall(tcpros.encode_frame(whole) + struct.pack("<I", 100) + b"\x05\x00\x00\x00ha")
        conn.setsockopt(socket.SOL_SOCKET, socket.SO_LINGER, struct.pack("ii", 1, 0))
        conn.close()  # a reset, as from a killed process
        server.close()

    serving = threading.Thread(target=serve)
    serving.start()
    listener = make_node("/mid_listener")
    got, _ = collect(listener, "/mid")
    serving.join(10)
    assert wait_until(lambda: got == ["whole"])
    pub = make_node("/living_talker").advertise("/mid", *STRING)
    assert wait_until(lambda: any(link.callerid == "/mid_listener" for link in pub.links), 10)
    pub.publish_frame(serialize_frame(String("still heard")))
    assert wait_until(lambda: got == ["whole", "still heard"], 10)


def test_a_publisher_update_during_registration_is_not_undone_by_its_answer(make_node: Any, master_uri: str,
                                                                            monkeypatch: pytest.MonkeyPatch) -> None:
    """A latched publisher registering while a subscriber's registerSubscriber is on its way: the
    master answers the subscriber with the publishers it had (not that one) and sends it a
    publisherUpdate with both, which may arrive first. The older answer must not drop the newer
    publisher (it did: tf_echo never heard a static_transform_publisher started beside it)."""
    early, late = make_node("/early"), make_node("/late_static")
    early_pub = early.advertise("/tf_static_like", *STRING, latch=True)
    early_pub.publish_frame(serialize_frame(String("from early")))
    listener = make_node("/echo")
    real_call = listener.master.call

    def racing_call(method: str, *args: Any) -> Any:
        answer = real_call(method, *args)
        if method == "registerSubscriber":  # the answer is on its way back when the latecomer registers
            late_pub = late.advertise("/tf_static_like", *STRING, latch=True)
            late_pub.publish_frame(serialize_frame(String("from late")))
            # ... and the master's publisherUpdate (both publishers) reaches the node first
            sub = listener.subscriptions["/tf_static_like"]
            assert wait_until(lambda: sub.updates == 1, timeout=10)
            assert late.uri not in [str(uri) for uri in answer]
        return answer

    monkeypatch.setattr(listener.master, "call", racing_call)
    got, _ = collect(listener, "/tf_static_like")
    assert wait_until(lambda: sorted(got) == ["from early", "from late"], timeout=10), got
    assert set(listener.subscriptions["/tf_static_like"].links) == {early.uri, late.uri}
