"""Foxglove's WebSocket protocol (ws-protocol, subprotocol foxglove.websocket.v1), sans-IO.

Text frames are JSON objects with an "op"; binary frames start with an opcode byte and carry
little-endian ids and times. `parse_text`/`parse_binary` turn a client's frame into one of the
request values below or raise ProtocolError (the client's fault: its text goes back to it as a
status message, and the connection stays). The encoders make the server's frames; a message's
data is never re-encoded: `message_data_header` is the 13 bytes that go in front of its TCPROS
bytes.

Parameters: ROS's XML-RPC values as ws-protocol values (`to_parameter`/`from_parameter`): binary
is a base64 string of type byte_array, a float is marked float64 (an integral one would read as
an integer otherwise), lists and dicts nest, as Noetic's foxglove_bridge converts them.
"""

from __future__ import annotations

import base64
import binascii
import json
import struct
from dataclasses import dataclass
from typing import Any

SUBPROTOCOL = "foxglove.websocket.v1"
ROS1_ENCODING = "ros1"
ROS1_SCHEMA_ENCODING = "ros1msg"

# server binary opcodes
MESSAGE_DATA = 1
TIME = 2
SERVICE_CALL_RESPONSE = 3
# client binary opcodes
CLIENT_MESSAGE_DATA = 1
SERVICE_CALL_REQUEST = 2

INFO, WARNING, ERROR = 0, 1, 2  # status levels

CAPABILITIES = ("clientPublish", "parameters", "parametersSubscribe", "services", "connectionGraph", "time")

_MESSAGE_DATA = struct.Struct("<BIQ")
_TIME = struct.Struct("<BQ")
_CALL = struct.Struct("<BIII")  # opcode, service id, call id, encoding length
_U32 = 0xFFFFFFFF


class ProtocolError(Exception):
    """A client's frame that is not ws-protocol: malformed, an unknown op, a wrong type."""


@dataclass(frozen=True)
class Channel:
    id: int
    topic: str
    schema_name: str
    schema: str
    encoding: str = ROS1_ENCODING
    schema_encoding: str = ROS1_SCHEMA_ENCODING


@dataclass(frozen=True)
class ServiceInfo:
    id: int
    name: str
    type: str
    request_schema: str
    response_schema: str


@dataclass(frozen=True)
class Subscribe:
    subscriptions: tuple[tuple[int, int], ...]  # (subscription id, channel id)


@dataclass(frozen=True)
class Unsubscribe:
    subscription_ids: tuple[int, ...]


@dataclass(frozen=True)
class ClientChannel:
    id: int
    topic: str
    encoding: str
    schema_name: str


@dataclass(frozen=True)
class ClientAdvertise:
    channels: tuple[ClientChannel, ...]


@dataclass(frozen=True)
class ClientUnadvertise:
    channel_ids: tuple[int, ...]


@dataclass(frozen=True)
class GetParameters:
    names: tuple[str, ...]
    request_id: str | None


@dataclass(frozen=True)
class SetParameters:
    parameters: tuple[tuple[str, Any], ...]  # (name, ROS value; None: delete)
    request_id: str | None


@dataclass(frozen=True)
class ParameterUpdates:
    names: tuple[str, ...]
    subscribe: bool


@dataclass(frozen=True)
class ConnectionGraphUpdates:
    subscribe: bool


@dataclass(frozen=True)
class ClientMessageData:
    channel_id: int
    data: bytes


@dataclass(frozen=True)
class ServiceCallRequest:
    service_id: int
    call_id: int
    encoding: str
    data: bytes


Request = (Subscribe | Unsubscribe | ClientAdvertise | ClientUnadvertise | GetParameters | SetParameters
           | ParameterUpdates | ConnectionGraphUpdates | ClientMessageData | ServiceCallRequest)


# ------------------------------------------------------------------ the client's frames


def _field(message: dict[str, Any], name: str, kind: type | tuple[type, ...], op: str) -> Any:
    if name not in message:
        raise ProtocolError(f"{op}: missing field '{name}'")
    value = message[name]
    if not isinstance(value, kind) or (isinstance(value, bool) and kind is not bool):
        raise ProtocolError(f"{op}: field '{name}' has the wrong type")
    return value


def _uint(value: Any, what: str, op: str) -> int:
    if not isinstance(value, int) or isinstance(value, bool) or not 0 <= value <= _U32:
        raise ProtocolError(f"{op}: {what} must be an unsigned 32-bit integer")
    return value


def _uints(message: dict[str, Any], name: str, op: str) -> tuple[int, ...]:
    return tuple(_uint(v, name, op) for v in _field(message, name, list, op))


def _strings(message: dict[str, Any], name: str, op: str) -> tuple[str, ...]:
    values = _field(message, name, list, op)
    if not all(isinstance(v, str) for v in values):
        raise ProtocolError(f"{op}: '{name}' must be a list of strings")
    return tuple(values)


def _request_id(message: dict[str, Any], op: str) -> str | None:
    value = message.get("id")
    if value is not None and not isinstance(value, str):
        raise ProtocolError(f"{op}: field 'id' has the wrong type")
    return value


def parse_text(text: str) -> Request:
    try:
        message = json.loads(text)
    except ValueError as exc:
        raise ProtocolError(f"not JSON: {exc}") from None
    except RecursionError:  # arrays in arrays, deeper than the parser goes
        raise ProtocolError("not JSON: nested too deeply") from None
    if not isinstance(message, dict) or not isinstance(message.get("op"), str):
        raise ProtocolError("a text message must be a JSON object with an 'op'")
    op: str = message["op"]
    if op == "subscribe":
        pairs = []
        for entry in _field(message, "subscriptions", list, op):
            if not isinstance(entry, dict):
                raise ProtocolError("subscribe: each subscription must be an object")
            pairs.append((_uint(entry.get("id"), "id", op), _uint(entry.get("channelId"), "channelId", op)))
        return Subscribe(tuple(pairs))
    if op == "unsubscribe":
        return Unsubscribe(_uints(message, "subscriptionIds", op))
    if op == "advertise":
        channels = []
        for entry in _field(message, "channels", list, op):
            if not isinstance(entry, dict):
                raise ProtocolError("advertise: each channel must be an object")
            channels.append(ClientChannel(_uint(entry.get("id"), "id", op), _field(entry, "topic", str, op),
                                          _field(entry, "encoding", str, op), _field(entry, "schemaName", str, op)))
        return ClientAdvertise(tuple(channels))
    if op == "unadvertise":
        return ClientUnadvertise(_uints(message, "channelIds", op))
    if op == "getParameters":
        return GetParameters(_strings(message, "parameterNames", op), _request_id(message, op))
    if op == "setParameters":
        parameters = []
        for entry in _field(message, "parameters", list, op):
            if not isinstance(entry, dict):
                raise ProtocolError("setParameters: each parameter must be an object")
            parameters.append((_field(entry, "name", str, op), from_parameter(entry.get("value"), entry.get("type"))))
        return SetParameters(tuple(parameters), _request_id(message, op))
    if op in ("subscribeParameterUpdates", "unsubscribeParameterUpdates"):
        return ParameterUpdates(_strings(message, "parameterNames", op), op.startswith("subscribe"))
    if op in ("subscribeConnectionGraph", "unsubscribeConnectionGraph"):
        return ConnectionGraphUpdates(op.startswith("subscribe"))
    raise ProtocolError(f"unknown op '{op}'")


def parse_binary(data: bytes) -> Request:
    if not data:
        raise ProtocolError("an empty binary message")
    opcode = data[0]
    if opcode == CLIENT_MESSAGE_DATA:
        if len(data) < 5:
            raise ProtocolError("client message data shorter than its header")
        (channel_id,) = struct.unpack_from("<I", data, 1)
        return ClientMessageData(channel_id, bytes(data[5:]))
    if opcode == SERVICE_CALL_REQUEST:
        if len(data) < _CALL.size:
            raise ProtocolError("service call request shorter than its header")
        _, service_id, call_id, length = _CALL.unpack_from(data)
        end = _CALL.size + length
        if end > len(data):
            raise ProtocolError("service call request: its encoding runs past the message")
        try:
            encoding = bytes(data[_CALL.size:end]).decode()
        except UnicodeDecodeError:
            raise ProtocolError("service call request: its encoding is not UTF-8") from None
        return ServiceCallRequest(service_id, call_id, encoding, bytes(data[end:]))
    raise ProtocolError(f"unknown binary opcode {opcode}")


# ------------------------------------------------------------------ the server's frames


def _json(message: dict[str, Any]) -> str:
    return json.dumps(message, separators=(",", ":"))


def server_info(name: str, capabilities: list[str], session_id: str, use_sim_time: bool) -> str:
    return _json({"op": "serverInfo", "name": name, "capabilities": capabilities,
                  "supportedEncodings": [ROS1_ENCODING], "metadata": {"ROS_DISTRO": "noetic",
                                                                       "use_sim_time": str(use_sim_time).lower()},
                  "sessionId": session_id})


def status(level: int, message: str) -> str:
    return _json({"op": "status", "level": level, "message": message})


def advertise(channels: list[Channel]) -> str:
    return _json({"op": "advertise", "channels": [
        {"id": c.id, "topic": c.topic, "encoding": c.encoding, "schemaName": c.schema_name, "schema": c.schema,
         "schemaEncoding": c.schema_encoding} for c in channels]})


def unadvertise(channel_ids: list[int]) -> str:
    return _json({"op": "unadvertise", "channelIds": channel_ids})


def advertise_services(services: list[ServiceInfo]) -> str:
    def schema(name: str, text: str) -> dict[str, str]:
        return {"encoding": ROS1_ENCODING, "schemaName": name, "schemaEncoding": ROS1_SCHEMA_ENCODING, "schema": text}

    return _json({"op": "advertiseServices", "services": [
        {"id": s.id, "name": s.name, "type": s.type,
         "request": schema(f"{s.type}Request", s.request_schema),
         "response": schema(f"{s.type}Response", s.response_schema),
         "requestSchema": s.request_schema, "responseSchema": s.response_schema} for s in services]})


def unadvertise_services(service_ids: list[int]) -> str:
    return _json({"op": "unadvertiseServices", "serviceIds": service_ids})


def parameter_values(parameters: list[tuple[str, Any]], request_id: str | None) -> str:
    message: dict[str, Any] = {"op": "parameterValues",
                               "parameters": [to_parameter(name, value) for name, value in parameters]}
    if request_id is not None:
        message["id"] = request_id
    return _json(message)


def service_call_failure(service_id: int, call_id: int, message: str) -> str:
    return _json({"op": "serviceCallFailure", "serviceId": service_id, "callId": call_id, "message": message})


def connection_graph_update(published: dict[str, list[str]], subscribed: dict[str, list[str]],
                            services: dict[str, list[str]], removed_topics: list[str],
                            removed_services: list[str]) -> str:
    return _json({"op": "connectionGraphUpdate",
                  "publishedTopics": [{"name": t, "publisherIds": ids} for t, ids in sorted(published.items())],
                  "subscribedTopics": [{"name": t, "subscriberIds": ids} for t, ids in sorted(subscribed.items())],
                  "advertisedServices": [{"name": s, "providerIds": ids} for s, ids in sorted(services.items())],
                  "removedTopics": removed_topics, "removedServices": removed_services})


def message_data_header(subscription_id: int, timestamp_ns: int) -> bytes:
    return _MESSAGE_DATA.pack(MESSAGE_DATA, subscription_id, timestamp_ns)


def time_message(timestamp_ns: int) -> bytes:
    return _TIME.pack(TIME, timestamp_ns)


def service_call_response(service_id: int, call_id: int, encoding: str, payload: bytes) -> bytes:
    name = encoding.encode()
    return _CALL.pack(SERVICE_CALL_RESPONSE, service_id, call_id, len(name)) + name + payload


# ------------------------------------------------------------------ parameters


def to_parameter(name: str, value: Any) -> dict[str, Any]:
    """A ROS parameter value (None: not set) as a ws-protocol parameter."""
    parameter: dict[str, Any] = {"name": name}
    if isinstance(value, (bytes, bytearray)):
        parameter["value"], parameter["type"] = base64.b64encode(value).decode(), "byte_array"
        return parameter
    if isinstance(value, float):
        parameter["type"] = "float64"
    elif isinstance(value, list) and value and all(isinstance(v, float) for v in value):
        parameter["type"] = "float64_array"
    if value is not None:
        parameter["value"] = _plain(value)
    return parameter


def _plain(value: Any) -> Any:
    if isinstance(value, (bytes, bytearray)):
        return base64.b64encode(value).decode()
    if isinstance(value, dict):
        return {str(k): _plain(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_plain(v) for v in value]
    return value


def from_parameter(value: Any, kind: Any) -> Any:
    """A ws-protocol parameter's value as the ROS value to set (None: delete it)."""
    if kind == "byte_array":
        if not isinstance(value, str):
            raise ProtocolError("a byte_array parameter's value must be a base64 string")
        try:
            return base64.b64decode(value, validate=True)
        except binascii.Error:
            raise ProtocolError("a byte_array parameter's value is not base64") from None
    if kind == "float64":
        if not isinstance(value, (int, float)) or isinstance(value, bool):
            raise ProtocolError("a float64 parameter's value must be a number")
        return float(value)
    if kind == "float64_array":
        if not isinstance(value, list) or not all(isinstance(v, (int, float)) and not isinstance(v, bool)
                                                  for v in value):
            raise ProtocolError("a float64_array parameter's value must be a list of numbers")
        return [float(v) for v in value]
    if kind is not None:
        raise ProtocolError(f"unknown parameter type '{kind}'")
    return value
