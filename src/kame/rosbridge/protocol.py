"""The rosbridge v2 protocol's frames, without I/O: what a client sent, and what we send back.

Rules:
- A text frame is one JSON object, a binary frame one CBOR object; either must carry a string
  "op". Anything else is a ProtocolError, answered with a status error (rosbridge's words where
  it has them) and never fatal to the connection.
- Fields are checked for their kind before use (`Fields`): a wrong kind is a ProtocolError
  naming the op and the field.
- Outgoing JSON is compact and strict (allow_nan=False: kame.rosbridge.conversion writes
  non-finite floats as null). A message longer than a subscription's fragment_size goes as
  "fragment" ops; the "png" compression is rosbridge's: the JSON's bytes as the pixels of an
  RGB image padded with newlines, PNG-encoded (Pillow), base64.
- Incoming fragments are put back together by `Defragmenter`, bounded in bytes and in messages
  being assembled at once (past that the oldest unfinished one is given up, as rosbridge's
  fragment_timeout would), so a client cannot make us hold more than it is allowed to send.
"""

from __future__ import annotations

import base64
import io
import json
import math
from dataclasses import dataclass, field
from typing import Any

import cbor2

STATUS_LEVELS = ("info", "warning", "error", "none")
DEFAULT_STATUS_LEVEL = "error"  # rosbridge's: only errors unless the client asks for more
COMPRESSIONS = ("none", "png", "cbor", "cbor-raw")
MAX_FRAGMENTS = 1000  # a message is cut into at most this many fragments, whatever fragment_size asks


class ProtocolError(ValueError):
    """A frame or op we cannot act on; `op` and `id` are echoed in the status we answer with."""

    def __init__(self, message: str, op: str = "", op_id: Any = None) -> None:
        super().__init__(message)
        self.op = op
        self.op_id = op_id


def decode_frame(data: str | bytes) -> dict[str, Any]:
    """The op object in a text (JSON) or binary (CBOR) frame."""
    try:
        value = json.loads(data) if isinstance(data, str) else cbor2.loads(data)
    except (ValueError, cbor2.CBORDecodeError, RecursionError) as exc:
        kind = "JSON" if isinstance(data, str) else "CBOR"
        raise ProtocolError(f"Unable to deserialize message from client: malformed {kind}: {exc}") from None
    if not isinstance(value, dict):
        raise ProtocolError("Received a rosbridge v2.0 incompatible message: not an object")
    op = value.get("op")
    if not isinstance(op, str):
        raise ProtocolError("Received a rosbridge v2.0 incompatible message: no 'op' string", op_id=value.get("id"))
    return value


class Fields:
    """Checked access to one op's fields."""

    def __init__(self, op: dict[str, Any]) -> None:
        self.op = op
        self.name = str(op.get("op", ""))
        self.id = op.get("id")

    def _error(self, text: str) -> ProtocolError:
        return ProtocolError(f"{self.name}: {text}", self.name, self.id)

    def string(self, key: str, default: str | None = None) -> str:
        value = self.op.get(key, default)
        if value is None:
            raise self._error(f"Expected a string field '{key}'")
        if not isinstance(value, str):
            raise self._error(f"Expected field '{key}' to be a string, got {type(value).__name__}")
        return value

    def number(self, key: str, default: float) -> float:
        value = self.op.get(key)
        if value is None:
            return default
        if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value) or value < 0:
            raise self._error(f"Expected field '{key}' to be a non-negative number")
        return float(value)

    def integer(self, key: str, default: int | None) -> int | None:
        value = self.op.get(key)
        if value is None:
            return default
        if isinstance(value, bool) or not isinstance(value, (int, float)) or value < 0 or value != int(value):
            raise self._error(f"Expected field '{key}' to be a non-negative integer")
        return int(value)

    def boolean(self, key: str, default: bool) -> bool:
        value = self.op.get(key, default)
        if not isinstance(value, bool):
            raise self._error(f"Expected field '{key}' to be a boolean")
        return value

    def compression(self) -> str:
        value = self.string("compression", "none")
        if value not in COMPRESSIONS:
            raise self._error(f"unknown compression '{value}' (one of {', '.join(COMPRESSIONS)})")
        return value


def encode_json(op: dict[str, Any]) -> str:
    return json.dumps(op, separators=(",", ":"), allow_nan=False)


def encode_cbor(op: dict[str, Any]) -> bytes:
    return cbor2.dumps(op)


def cbor_tag(number: int, payload: bytes) -> cbor2.CBORTag:
    return cbor2.CBORTag(number, payload)


def status(level: str, message: str, op_id: Any = None) -> dict[str, Any]:
    op: dict[str, Any] = {"op": "status", "level": level, "msg": message}
    if op_id is not None:
        op["id"] = op_id
    return op


def wants_status(client_level: str, level: str) -> bool:
    """Whether a client that set_level'd `client_level` gets a status of `level`."""
    return STATUS_LEVELS.index(level) >= STATUS_LEVELS.index(client_level)


def fragments(text: str, size: int, message_id: str) -> list[str]:
    """`text` as-is when it fits in `size` characters, else as "fragment" ops of that size (larger
    when that would make more than MAX_FRAGMENTS: a tiny fragment_size must not cost us a frame
    per character)."""
    if size <= 0 or len(text) <= size:
        return [text]
    size = max(size, -(-len(text) // MAX_FRAGMENTS))
    parts = [text[i:i + size] for i in range(0, len(text), size)]
    return [encode_json({"op": "fragment", "id": message_id, "data": part, "num": num, "total": len(parts)})
            for num, part in enumerate(parts)]


def png_compress(text: str) -> str:
    """rosbridge's png compression of a JSON frame: the "png" op carrying it."""
    from PIL import Image

    data = text.encode("utf-8")
    width = max(1, math.floor(math.sqrt(len(data) / 3.0)))
    height = max(1, math.ceil(len(data) / 3.0 / width))
    padded = data + b"\n" * (width * height * 3 - len(data))
    out = io.BytesIO()
    Image.frombytes("RGB", (width, height), padded).save(out, "png")
    return encode_json({"op": "png", "data": base64.b64encode(out.getvalue()).decode("ascii")})


@dataclass
class _Assembly:
    total: int
    parts: dict[int, str] = field(default_factory=dict)
    size: int = 0


class Defragmenter:
    """Incoming "fragment" ops put back together, within `max_bytes` and `max_messages` at once."""

    def __init__(self, max_bytes: int, max_messages: int = 16) -> None:
        self.max_bytes = max_bytes
        self.max_messages = max_messages
        self._assemblies: dict[str, _Assembly] = {}

    def add(self, op: dict[str, Any]) -> str | None:
        """The whole message once its last fragment is in; None while some are missing."""
        fields = Fields(op)
        message_id = op.get("id")
        if not isinstance(message_id, (str, int)) or isinstance(message_id, bool):
            raise ProtocolError("fragment: Expected an 'id'", "fragment", message_id)
        key = str(message_id)
        data = fields.string("data")
        num, total = fields.integer("num", None), fields.integer("total", None)
        if num is None or total is None or total == 0 or num >= total:
            raise ProtocolError("fragment: 'num' and 'total' must be integers with 0 <= num < total",
                                "fragment", message_id)
        assembly = self._assemblies.get(key)
        if assembly is None:
            if len(self._assemblies) >= self.max_messages:  # the oldest unfinished one is given up
                del self._assemblies[next(iter(self._assemblies))]
            assembly = self._assemblies[key] = _Assembly(total)
        if assembly.total != total:
            del self._assemblies[key]
            raise ProtocolError("fragment: 'total' changed within one message", "fragment", message_id)
        if num not in assembly.parts:
            assembly.size += len(data)
            if sum(a.size for a in self._assemblies.values()) > self.max_bytes:
                del self._assemblies[key]
                raise ProtocolError(f"fragment: message larger than {self.max_bytes} bytes", "fragment", message_id)
            assembly.parts[num] = data
        if len(assembly.parts) < assembly.total:
            return None
        del self._assemblies[key]
        return "".join(assembly.parts[i] for i in range(assembly.total))
