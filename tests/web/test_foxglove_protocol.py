"""Foxglove's ws-protocol as kame.foxglove_bridge.protocol reads and writes it (bytes and JSON in,
values out), what the bridge offers (kame.foxglove_bridge.graph), and the hub's peer gate."""

from __future__ import annotations

import json
import struct
from typing import Any

import pytest

from kame.foxglove_bridge import protocol as wsp
from kame.foxglove_bridge.graph import Offer, SystemState, compile_whitelist


def test_client_requests_are_read() -> None:
    assert wsp.parse_text('{"op":"subscribe","subscriptions":[{"id":0,"channelId":3},{"id":1,"channelId":4}]}') \
        == wsp.Subscribe(((0, 3), (1, 4)))
    assert wsp.parse_text('{"op":"unsubscribe","subscriptionIds":[1]}') == wsp.Unsubscribe((1,))
    assert wsp.parse_text('{"op":"advertise","channels":[{"id":2,"topic":"/a","encoding":"ros1",'
                          '"schemaName":"std_msgs/String"}]}') \
        == wsp.ClientAdvertise((wsp.ClientChannel(2, "/a", "ros1", "std_msgs/String"),))
    assert wsp.parse_text('{"op":"unadvertise","channelIds":[2]}') == wsp.ClientUnadvertise((2,))
    assert wsp.parse_text('{"op":"getParameters","parameterNames":["/a"],"id":"x"}') == wsp.GetParameters(("/a",), "x")
    assert wsp.parse_text('{"op":"setParameters","parameters":[{"name":"/a","value":1},'
                          '{"name":"/b","value":"AAE=","type":"byte_array"},{"name":"/c"}]}') \
        == wsp.SetParameters((("/a", 1), ("/b", b"\x00\x01"), ("/c", None)), None)
    assert wsp.parse_text('{"op":"subscribeParameterUpdates","parameterNames":["/a"]}') \
        == wsp.ParameterUpdates(("/a",), True)
    assert wsp.parse_text('{"op":"unsubscribeParameterUpdates","parameterNames":["/a"]}') \
        == wsp.ParameterUpdates(("/a",), False)
    assert wsp.parse_text('{"op":"subscribeConnectionGraph"}') == wsp.ConnectionGraphUpdates(True)
    assert wsp.parse_binary(b"\x01\x07\x00\x00\x00abc") == wsp.ClientMessageData(7, b"abc")
    assert wsp.parse_binary(struct.pack("<BIII", 2, 5, 9, 4) + b"ros1" + b"\x01\x02") \
        == wsp.ServiceCallRequest(5, 9, "ros1", b"\x01\x02")


@pytest.mark.parametrize(("frame", "error"), [
    ("[", "not JSON"),
    ("[1]", "a text message must be a JSON object with an 'op'"),
    ("[" * 100_000, "not JSON: nested too deeply"),
    ('{"op":"fly"}', "unknown op 'fly'"),
    ('{"op":"subscribe"}', "subscribe: missing field 'subscriptions'"),
    ('{"op":"subscribe","subscriptions":[{"id":-1,"channelId":1}]}',
     "subscribe: id must be an unsigned 32-bit integer"),
    ('{"op":"subscribe","subscriptions":[{"id":true,"channelId":1}]}', "subscribe: id must be an unsigned 32-bit"),
    ('{"op":"unsubscribe","subscriptionIds":[4294967296]}', "unsubscribe: subscriptionIds must be an unsigned"),
    ('{"op":"advertise","channels":[{"id":1,"topic":5,"encoding":"ros1","schemaName":"a/B"}]}',
     "advertise: field 'topic' has the wrong type"),
    ('{"op":"getParameters","parameterNames":[1]}', "getParameters: 'parameterNames' must be a list of strings"),
    ('{"op":"getParameters","parameterNames":[],"id":3}', "getParameters: field 'id' has the wrong type"),
    ('{"op":"setParameters","parameters":[{"name":"/a","value":"%","type":"byte_array"}]}',
     "a byte_array parameter's value is not base64"),
    ('{"op":"setParameters","parameters":[{"name":"/a","value":"x","type":"float64"}]}',
     "a float64 parameter's value must be a number"),
    ('{"op":"setParameters","parameters":[{"name":"/a","value":1,"type":"uint9"}]}', "unknown parameter type"),
])
def test_malformed_text_is_the_clients_fault(frame: str, error: str) -> None:
    with pytest.raises(wsp.ProtocolError, match="^" + error.replace("(", r"\(").replace("[", r"\[")):
        wsp.parse_text(frame)


@pytest.mark.parametrize(("frame", "error"), [
    (b"", "an empty binary message"),
    (b"\x01\x00", "client message data shorter than its header"),
    (b"\x02" + b"\x00" * 8, "service call request shorter than its header"),
    (struct.pack("<BIII", 2, 1, 1, 99) + b"ros1", "service call request: its encoding runs past the message"),
    (struct.pack("<BIII", 2, 1, 1, 1) + b"\xff", "service call request: its encoding is not UTF-8"),
    (b"\x07", "unknown binary opcode 7"),
])
def test_malformed_binary_is_the_clients_fault(frame: bytes, error: str) -> None:
    with pytest.raises(wsp.ProtocolError, match="^" + error):
        wsp.parse_binary(frame)


def test_server_frames() -> None:
    assert wsp.message_data_header(3, 0x0102030405060708) == b"\x01\x03\x00\x00\x00\x08\x07\x06\x05\x04\x03\x02\x01"
    assert wsp.time_message(5) == b"\x02" + (5).to_bytes(8, "little")
    assert wsp.service_call_response(1, 2, "ros1", b"\xaa") == struct.pack("<BIII", 3, 1, 2, 4) + b"ros1\xaa"
    channel = wsp.Channel(1, "/chatter", "std_msgs/String", "string data\n")
    assert json.loads(wsp.advertise([channel])) == {"op": "advertise", "channels": [
        {"id": 1, "topic": "/chatter", "encoding": "ros1", "schemaName": "std_msgs/String",
         "schema": "string data\n", "schemaEncoding": "ros1msg"}]}
    service = json.loads(wsp.advertise_services([wsp.ServiceInfo(4, "/add", "pkg/Add", "int64 a", "int64 sum")]))
    assert service["services"][0]["request"] == {"encoding": "ros1", "schemaName": "pkg/AddRequest",
                                                 "schemaEncoding": "ros1msg", "schema": "int64 a"}
    assert service["services"][0]["responseSchema"] == "int64 sum"
    assert json.loads(wsp.status(wsp.ERROR, "no")) == {"op": "status", "level": 2, "message": "no"}


@pytest.mark.parametrize(("value", "parameter"), [
    (3, {"name": "/p", "value": 3}),
    (2.0, {"name": "/p", "value": 2.0, "type": "float64"}),
    ([1.0, 2.5], {"name": "/p", "value": [1.0, 2.5], "type": "float64_array"}),
    (b"\x00\x01", {"name": "/p", "value": "AAE=", "type": "byte_array"}),
    ({"a": [1, "x"], "b": True}, {"name": "/p", "value": {"a": [1, "x"], "b": True}}),
    (None, {"name": "/p"}),
])
def test_parameters_both_ways(value: Any, parameter: dict[str, Any]) -> None:
    assert wsp.to_parameter("/p", value) == parameter
    assert wsp.from_parameter(parameter.get("value"), parameter.get("type")) == value


def state(publishers: dict[str, list[str]], types: dict[str, str], services: dict[str, list[str]] | None = None
          ) -> SystemState:
    return SystemState(publishers, {}, services or {}, types)


def test_the_offer_follows_the_graph() -> None:
    topics, bad = compile_whitelist(["/turtle1/.*", "/cam(era"])
    assert bad == ["/cam(era"]
    offer = Offer(topics, compile_whitelist([".*"])[0], {"turtlesim/Pose": "float32 x"}.get)
    changes, unknown = offer.update_channels(state({"/turtle1/pose": ["/t"], "/turtle1/odd": ["/t"],
                                                    "/rosout": ["/t"]},
                                                   {"/turtle1/pose": "turtlesim/Pose", "/turtle1/odd": "no/Def",
                                                    "/rosout": "rosgraph_msgs/Log"}))
    assert [(c.id, c.topic, c.schema_name, c.schema) for c in changes.added] == [(1, "/turtle1/pose", "turtlesim/Pose",
                                                                                  "float32 x")]
    assert unknown == ["no/Def"]
    changes, unknown = offer.update_channels(state({}, {}))
    assert changes.removed == [1] and unknown == []
    changes, _ = offer.update_channels(state({"/turtle1/pose": ["/t"]}, {"/turtle1/pose": "turtlesim/Pose"}))
    assert [c.id for c in changes.added] == [2]  # a channel id is never reused


def test_services_and_the_connection_graph() -> None:
    offer = Offer([], compile_whitelist(["/spawn"])[0], lambda _: None)
    first = state({"/a": ["/n"]}, {"/a": "x/Y"}, {"/spawn": ["/t"], "/kill": ["/t"]})
    assert offer.services_to_describe(first) == ["/spawn"]
    added = offer.update_services(first, {"/spawn": wsp.ServiceInfo(0, "/spawn", "turtlesim/Spawn", "a", "b")}).added
    assert [(s.id, s.name) for s in added] == [(1, "/spawn")]
    assert offer.update_services(state({}, {}), {}).removed == [1]
    assert offer.graph_update(first) == ({"/a": ["/n"]}, {}, {"/spawn": ["/t"], "/kill": ["/t"]}, [], [])
    assert offer.graph_update(first) is None
    assert offer.graph_update(state({}, {})) == ({}, {}, {}, ["/a"], ["/kill", "/spawn"])


def test_the_hub_asks_the_peer_allowlist() -> None:
    from kame.net import peers
    from kame.net.websocket_hub import WebSocketHub

    class Handler:
        def opened(self, client: object) -> None: ...

        def received(self, client: object, message: str | bytes) -> None: ...

        def closed(self, client: object) -> None: ...

    class Connection:
        def __init__(self, address: tuple[str, int]) -> None:
            self.remote_address = address

        def respond(self, status: int, text: str) -> tuple[int, str]:
            return status, text

    hub = WebSocketHub("127.0.0.1", 0, wsp.SUBPROTOCOL, Handler(), "foxglove_bridge", 1000, 1000)
    try:
        peers.configure("10.1.0.0/16")
        refused = hub._admit(Connection(("203.0.113.7", 4000)), None)  # type: ignore[arg-type]
        assert refused == (403, "not in the allowed peers\n")
        assert hub._admit(Connection(("10.1.2.3", 4000)), None) is None  # type: ignore[arg-type]
        assert hub._admit(Connection(("127.0.0.1", 4000)), None) is None  # type: ignore[arg-type]
    finally:
        peers.configure(None)
        hub.close()


def test_the_hub_bounds_what_a_client_sends() -> None:
    from websockets.exceptions import ConnectionClosedError
    from websockets.sync.client import connect

    from kame.net.websocket_hub import HubClient, WebSocketHub

    class Echo:
        def opened(self, client: HubClient) -> None: ...

        def received(self, client: HubClient, message: str | bytes) -> None:
            client.send_control(message)

        def closed(self, client: HubClient) -> None: ...

    hub = WebSocketHub("127.0.0.1", 0, wsp.SUBPROTOCOL, Echo(), "foxglove_bridge", 1000, 1000)
    try:
        with connect(f"ws://127.0.0.1:{hub.port}", subprotocols=[wsp.SUBPROTOCOL]) as ws:  # type: ignore[list-item]
            assert ws.subprotocol == wsp.SUBPROTOCOL
            ws.send(b"x" * 1000)
            assert ws.recv(timeout=10) == b"x" * 1000
            ws.send(b"x" * 1001)
            with pytest.raises(ConnectionClosedError) as closed:
                ws.recv(timeout=10)
            assert closed.value.rcvd is not None and closed.value.rcvd.code == 1009  # message too big
    finally:
        hub.close()


def _json_values() -> Any:
    from hypothesis import strategies as st

    scalars = (st.none() | st.booleans() | st.integers(-(2**40), 2**40) | st.floats(allow_nan=False)
               | st.text(max_size=8))
    return st.recursive(scalars, lambda inner: st.lists(inner, max_size=4)
                        | st.dictionaries(st.sampled_from(["op", "id", "channelId", "subscriptions", "channels",
                                                          "topic", "encoding", "schemaName", "parameterNames",
                                                          "parameters", "name", "value", "type", "subscriptionIds",
                                                          "channelIds"]), inner, max_size=5), max_leaves=12)


def test_any_frame_is_a_request_or_the_clients_fault() -> None:
    """Whatever a client sends, the parser answers with a request or a ProtocolError (a status),
    never another exception that would end its connection."""
    from hypothesis import given
    from hypothesis import strategies as st

    ops = st.sampled_from(["subscribe", "unsubscribe", "advertise", "unadvertise", "getParameters", "setParameters",
                           "subscribeParameterUpdates", "subscribeConnectionGraph", "bogus"])

    @given(st.one_of(st.text(max_size=40), _json_values().map(json.dumps),
                     st.builds(lambda op, rest: json.dumps({**rest, "op": op}) if isinstance(rest, dict) else op,
                               ops, _json_values())))
    def text(frame: str) -> None:
        try:
            wsp.parse_text(frame)
        except wsp.ProtocolError:
            pass

    @given(st.binary(max_size=40))
    def binary(frame: bytes) -> None:
        try:
            wsp.parse_binary(frame)
        except wsp.ProtocolError:
            pass

    text()
    binary()
