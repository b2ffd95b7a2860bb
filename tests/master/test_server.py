"""The master over real sockets on 127.0.0.1: normal use, notifications, and hostile clients."""

from __future__ import annotations

import http.client
import socket
import threading
import time
import xmlrpc.client
from collections.abc import Iterator
from dataclasses import dataclass

import pytest

from kame.master.server import MasterServer
from kame.net.http_server import ServerLimits

from ..support import FakeNode, LoopThread, SilentPeer

LIMITS = ServerLimits(max_body=1024 * 1024, max_header=8192, max_connections=40, idle_timeout=0.5,
                      request_timeout=0.5)


@dataclass
class Running:
    server: MasterServer
    uri: str
    loop: LoopThread

    def proxy(self) -> xmlrpc.client.ServerProxy:
        return xmlrpc.client.ServerProxy(self.uri)


@pytest.fixture
def master() -> Iterator[Running]:
    loop = LoopThread()
    server = MasterServer("127.0.0.1", 0, "127.0.0.1", LIMITS, notify_timeout=0.5)
    uri = loop.run(server.start())
    try:
        yield Running(server, uri, loop)
    finally:
        loop.run(server.close())
        loop.close()


def still_serves(m: Running) -> None:
    assert m.proxy().getParam("/check", "/nothing")[0] == -1
    assert m.proxy().getUri("/check") == [1, "", m.uri]


def raw(m: Running, data: bytes, read: bool = True, timeout: float = 3.0) -> bytes:
    with socket.create_connection(("127.0.0.1", m.server.port), timeout=timeout) as s:
        s.sendall(data)
        if not read:
            return b""
        chunks = []
        while True:
            try:
                chunk = s.recv(65536)
            except ConnectionResetError:
                break
            if not chunk:
                break
            chunks.append(chunk)
        return b"".join(chunks)


def post(body: bytes, extra: str = "") -> bytes:
    return (f"POST / HTTP/1.1\r\nHost: x\r\nContent-Type: text/xml\r\n{extra}Content-length: {len(body)}\r\n"
            "Connection: close\r\n\r\n").encode() + body


def test_basic_calls(master: Running) -> None:
    p = master.proxy()
    assert p.getUri("/n") == [1, "", master.uri]
    assert p.registerPublisher("/n", "/t", "std_msgs/String", "http://127.0.0.1:1/")[0] == 1
    assert p.getSystemState("/n")[2][0] == [["/t", ["/n"]]]
    assert p.setParam("/n", "/d", {"a": {"b": xmlrpc.client.Binary(b"\x00")}}) == [1, "parameter /d set", 0]
    assert p.getParam("/n", "/d")[2] == {"a": {"b": xmlrpc.client.Binary(b"\x00")}}


def test_rpc2_path_and_keep_alive(master: Running) -> None:
    conn = http.client.HTTPConnection("127.0.0.1", master.server.port, timeout=3)
    body = xmlrpc.client.dumps(("/n",), "getPid").encode()
    for path in ("/", "/RPC2", "/"):
        conn.request("POST", path, body, {"Content-Type": "text/xml"})
        r = conn.getresponse()
        assert r.status == 200
        assert xmlrpc.client.loads(r.read())[0][0][0] == 1
    assert master.server.http.connection_count == 1
    conn.request("POST", "/other", body)
    assert conn.getresponse().status == 404
    conn.close()
    conn = http.client.HTTPConnection("127.0.0.1", master.server.port, timeout=3)
    conn.request("GET", "/")
    assert conn.getresponse().status == 501
    conn.close()


def test_xmlrpcpp_request(master: Running) -> None:
    body = (b'<?xml version="1.0"?>\r\n<methodCall><methodName>registerSubscriber</methodName>\r\n<params>'
            b"<param><value>/cppnode</value></param><param><value>/chatter</value></param>"
            b"<param><value>std_msgs/String</value></param><param><value>http://127.0.0.1:2/</value></param>"
            b"</params></methodCall>\r\n")
    head = (b"POST / HTTP/1.1\r\nUser-Agent: XMLRPC++ 0.7\r\nHost: 127.0.0.1:1\r\nContent-Type: text/xml\r\n"
            b"Content-length: %d\r\n\r\n" % len(body))
    with socket.create_connection(("127.0.0.1", master.server.port), timeout=3) as s:
        s.sendall(head + body)
        data = b""
        while b"</methodResponse>" not in data:
            data += s.recv(65536)
    head_out, _, payload = data.partition(b"\r\n\r\n")
    assert head_out.startswith(b"HTTP/1.1 200 OK") and b"Content-length: " in head_out
    assert xmlrpc.client.loads(payload)[0][0] == [1, "Subscribed to [/chatter]", []]


def test_multicall(master: Running) -> None:
    mc = xmlrpc.client.MultiCall(master.proxy())
    mc.setParam("/n", "x", 1)
    mc.getParam("/n", "x")
    assert list(mc()) == [[1, "parameter /x set", 0], [1, "Parameter [/x]", 1]]


def test_bad_calls_get_ros_answers(master: Running) -> None:
    p = master.proxy()
    with pytest.raises(xmlrpc.client.Fault) as e:
        p.getBusInfo("/n")
    assert e.value.faultCode == 1
    assert e.value.faultString == "<class 'Exception'>:method \"getBusInfo\" is not supported"
    assert p.getParam() == [-1, "missing required caller_id parameter", 0]
    assert p.getParam("/n") == [-1, "Error: bad call arity", 0]
    assert p.getParam(["/n"], "k") == [-1, "caller_id must be a string", 0]
    assert p.registerPublisher("/n", "a b", "p/T", "http://h:1/") == [
        -1, "ERROR: parameter [topic] contains illegal chars", []]
    still_serves(master)


@pytest.mark.parametrize("body", [
    b"garbage", b"<methodCall><methodName>getPid", b"<methodCall><params/></methodCall>",
    b"<methodCall><methodName>getPid</methodName><params><param><value><nil/></value></param></params>"
    b"</methodCall>",
    b'<?xml version="1.0"?><!DOCTYPE x [<!ENTITY a "aaaaaaaaaa"><!ENTITY b "&a;&a;&a;&a;&a;&a;">]>'
    b"<methodCall><methodName>&b;</methodName></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param>" + b"<value><array><data>" * 5000,
])
def test_malformed_xml_is_a_fault(master: Running, body: bytes) -> None:
    reply = raw(master, post(body))
    assert reply.startswith(b"HTTP/1.1 200 OK")
    with pytest.raises(xmlrpc.client.Fault) as e:
        xmlrpc.client.loads(reply.partition(b"\r\n\r\n")[2])
    assert e.value.faultCode == 1
    still_serves(master)


def test_huge_body_is_refused_without_reading_it(master: Running) -> None:
    reply = raw(master, b"POST / HTTP/1.1\r\nContent-Length: 500000000\r\n\r\n<methodCall>")
    assert reply.startswith(b"HTTP/1.1 413 ")
    with socket.create_connection(("127.0.0.1", master.server.port), timeout=3) as s:
        s.sendall(b"POST / HTTP/1.1\r\nContent-Length: 2000000\r\n\r\n")
        try:
            s.sendall(b"x" * 2_000_000)  # the master closes while we are still sending
        except OSError:
            pass
    still_serves(master)


def test_bad_http_is_refused(master: Running) -> None:
    assert raw(master, b"NONSENSE\r\n\r\n").startswith(b"HTTP/1.1 400 ")
    assert raw(master, b"POST / HTTP/1.1\r\nContent-Length: x\r\n\r\n").startswith(b"HTTP/1.1 400 ")
    assert raw(master, b"POST / HTTP/1.1\r\nTransfer-Encoding: chunked\r\n\r\n").startswith(b"HTTP/1.1 411 ")
    assert raw(master, b"POST / HTTP/1.1\r\nX: " + b"a" * 10000).startswith(b"HTTP/1.1 431 ")
    still_serves(master)


def test_silent_and_slow_clients_are_dropped(master: Running) -> None:
    silent = socket.create_connection(("127.0.0.1", master.server.port), timeout=3)
    slow = socket.create_connection(("127.0.0.1", master.server.port), timeout=3)
    slow.sendall(b"POST / HTTP/1.1\r\nContent-Length: 100\r\n\r\n<metho")
    t0 = time.monotonic()
    assert silent.recv(100) == b""  # closed by the master after idle_timeout
    assert slow.recv(100).startswith(b"HTTP/1.1 408 ")
    assert time.monotonic() - t0 < 3
    silent.close()
    slow.close()
    still_serves(master)


def test_connection_flood(master: Running) -> None:
    flood = [socket.create_connection(("127.0.0.1", master.server.port), timeout=3) for _ in range(200)]
    try:
        still_serves(master)
        assert master.server.http.connection_count <= LIMITS.max_connections
    finally:
        for s in flood:
            s.close()


def test_concurrent_clients(master: Running) -> None:
    errors: list[BaseException] = []

    def client(i: int) -> None:
        try:
            p = master.proxy()
            for j in range(30):
                assert p.registerPublisher(f"/n{i}", f"/t{j}", "p/T", f"http://127.0.0.1:{1000 + i}/")[0] == 1
                assert p.lookupNode("/x", f"/n{i}")[2] == f"http://127.0.0.1:{1000 + i}/"
        except BaseException as e:
            errors.append(e)

    threads = [threading.Thread(target=client, args=(i,)) for i in range(20)]
    for t in threads:
        t.start()
    for t in threads:
        t.join(30)
    assert errors == []
    pubs = master.proxy().getSystemState("/x")[2][0]
    assert len(pubs) == 30 and all(len(nodes) == 20 for _, nodes in pubs)


def test_notifications_reach_nodes(master: Running) -> None:
    node, other = FakeNode(), FakeNode()
    try:
        p = master.proxy()
        p.registerSubscriber("/sub", "/t", "p/T", node.uri)
        p.registerPublisher("/pub", "/t", "p/T", "http://127.0.0.1:9/")
        assert node.wait_calls(1)[0] == ("publisherUpdate", ("/master", "/t", ["http://127.0.0.1:9/"]))
        p.subscribeParam("/sub", node.uri, "/watched")
        p.setParam("/setter", "/watched", {"x": 1})
        p.deleteParam("/setter", "/watched")
        was_set = ("paramUpdate", ("/master", "/watched/", {"x": 1}))
        deleted = ("paramUpdate", ("/master", "/watched/", {}))
        # a node's notifications not yet sent are coalesced, the newest value of a key winning: on a
        # busy machine the set may be folded into the delete that follows it
        assert node.wait_calls(3)[1:] in ([was_set, deleted], [deleted])
        # a second node taking the name: the first is told to shut down
        p.registerPublisher("/dup", "/u", "p/T", other.uri)
        p.registerPublisher("/dup", "/u", "p/T", "http://127.0.0.1:10/")
        assert other.wait_calls(1) == [
            ("shutdown", ("/master", "[/dup] Reason: new node registered with same name"))]
    finally:
        node.close()
        other.close()


def test_dead_node_does_not_stall_anyone(master: Running) -> None:
    dead, alive = SilentPeer(), FakeNode()
    try:
        p = master.proxy()
        p.registerSubscriber("/dead", "/t", "p/T", dead.uri)
        p.registerSubscriber("/alive", "/t", "p/T", alive.uri)
        t0 = time.monotonic()
        for i in range(20):
            assert p.registerPublisher(f"/pub{i}", "/t", "p/T", f"http://127.0.0.1:{2000 + i}/")[0] == 1
        assert time.monotonic() - t0 < 1.0
        # the live node hears the final state promptly even though the dead one hangs
        deadline = time.monotonic() + 3
        while time.monotonic() < deadline:
            if alive.calls and len(alive.calls[-1][1][2]) == 20:  # type: ignore[arg-type]
                break
            time.sleep(0.02)
        assert len(alive.calls[-1][1][2]) == 20  # type: ignore[arg-type]
        # pending updates to the dead node were coalesced, not queued one per change
        assert master.server.notifier is not None
        assert len(master.server.notifier._pending.get(dead.uri, {})) <= 1
        still_serves(master)
    finally:
        dead.close()
        alive.close()


def test_unanswerable_values_are_refused_when_set(master: Running) -> None:
    # rosmaster stores them and then faults every getParam that reaches them, '/' included.
    body = (b"<methodCall><methodName>setParam</methodName><params><param><value>/n</value></param>"
            b"<param><value>big</value></param><param><value><i8>99999999999</i8></value></param></params>"
            b"</methodCall>")
    assert b"cannot set parameter [/big]: 99999999999 does not fit a 32-bit signed integer" in raw(master, post(body))
    code, _, tree = master.proxy().getParam("/n", "/")
    assert code == 1 and "big" not in tree
    still_serves(master)


def test_shutdown_call_stops_it(master: Running) -> None:
    assert master.proxy().shutdown("/n", "bye") == [1, "shutdown", 0]
    master.loop.run(master.server.wait_shutdown(), timeout=2)
