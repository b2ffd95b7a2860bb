"""XML-RPC bodies: encode and decode method calls, responses and faults (bytes in, values out).

Rules (ros1-interop spec §2):
- We write what Python's xmlrpc.client writes, byte for byte (`<int>`, `<string>`, `<boolean>`,
  `<double>`, `<base64>`, newline after each element), so our peers see what rospy sends.
- We read both that and XmlRpc++'s dialect: `<i4>`, untagged strings (`<value>x</value>`) and
  `<value></value>` for an empty string; `<i8>` too, as Python's reader does.
- `nil` is refused in both directions: ROS servers run without allow_none. Integers are 32-bit
  on encode (xmlrpc.client refuses more); decode takes any size, as xmlrpc.client does.
- Decoding uses expat directly. A DOCTYPE is refused outright, which shuts out entity
  declarations (billion laughs, external entities); element nesting is bounded so hostile input
  cannot build unbounded Python structures.
This is the master's hot path: encoding appends strings to one list, decoding is a flat event
loop over expat callbacks with a value stack, no per-element objects.
- Requests as ROS clients send them (a flat list of ASCII string/int/i4/boolean/double params,
  in xmlrpc.client's or XmlRpc++'s layout) are decoded by one regular expression per param
  instead of expat: about 5x cheaper. That path accepts a strict subset of what expat accepts
  (no entities, CDATA, comments, attributes, nesting, `]`, control characters or non-ASCII) and
  gives identical values; anything else, malformed input included, goes to the full parser.
"""

from __future__ import annotations

import binascii
import re
from collections.abc import Callable, Sequence
from typing import TypeAlias
from xml.parsers import expat

MAX_INT = 2**31 - 1
MIN_INT = -(2**31)
#: Deepest element nesting accepted. Each array or struct level costs three or four elements
#: (value, array, data / value, struct, member), so this allows about 60 levels of containers.
MAX_DEPTH = 256


class DateTime:
    """An XML-RPC `dateTime.iso8601` value, kept as its text so it round-trips unchanged.

    (A plain value class, not a dataclass: every node imports this module at start-up.)"""

    __slots__ = ("value",)

    def __init__(self, value: str) -> None:
        self.value = value

    def __eq__(self, other: object) -> bool:
        return isinstance(other, DateTime) and other.value == self.value

    def __hash__(self) -> int:
        return hash(self.value)

    def __repr__(self) -> str:
        return f"DateTime(value={self.value!r})"


Value: TypeAlias = "bool | int | float | str | bytes | DateTime | list[Value] | dict[str, Value]"


class XmlRpcError(Exception):
    """Base class of this module's errors."""


class MalformedError(XmlRpcError):
    """The bytes are not a well-formed XML-RPC message (the peer's fault)."""


class Fault(XmlRpcError):
    """An XML-RPC fault response."""

    def __init__(self, code: int, message: str) -> None:
        super().__init__(code, message)
        self.code = code
        self.message = message

    def __str__(self) -> str:
        return f"<Fault {self.code}: {self.message!r}>"


# ---------------------------------------------------------------------------------------- encode

_XML_DECL = "<?xml version='1.0'?>\n"


def _escape(s: str) -> str:
    if "&" in s:
        s = s.replace("&", "&amp;")
    if "<" in s:
        s = s.replace("<", "&lt;")
    if ">" in s:
        s = s.replace(">", "&gt;")
    return s


def _encode_value(v: object, out: list[str]) -> None:
    t = type(v)
    if t is str:
        out.append(f"<value><string>{_escape(v)}</string></value>\n")  # type: ignore[arg-type]
    elif t is int:
        if not MIN_INT <= v <= MAX_INT:  # type: ignore[operator]
            raise OverflowError("int exceeds XML-RPC limits")
        out.append(f"<value><int>{v}</int></value>\n")
    elif t is list or t is tuple:
        out.append("<value><array><data>\n")
        for item in v:  # type: ignore[attr-defined]
            _encode_value(item, out)
        out.append("</data></array></value>\n")
    elif t is dict:
        out.append("<value><struct>\n")
        for key, item in v.items():  # type: ignore[attr-defined]
            if type(key) is not str:
                raise TypeError("dictionary key must be string")
            out.append(f"<member>\n<name>{_escape(key)}</name>\n")
            _encode_value(item, out)
            out.append("</member>\n")
        out.append("</struct></value>\n")
    elif t is bool:
        out.append("<value><boolean>1</boolean></value>\n" if v else "<value><boolean>0</boolean></value>\n")
    elif t is float:
        out.append(f"<value><double>{v!r}</double></value>\n")
    elif t is bytes or t is bytearray or t is memoryview:
        import base64  # here: few calls carry binary values (see _base64)

        encoded = base64.encodebytes(v).decode("ascii")  # type: ignore[arg-type]
        out.append(f"<value><base64>\n{encoded}</base64></value>\n")
    elif t is DateTime:
        out.append(f"<value><dateTime.iso8601>{_escape(v.value)}</dateTime.iso8601></value>\n")  # type: ignore[attr-defined]
    else:
        _encode_subclass(v, out)


def _encode_subclass(v: object, out: list[str]) -> None:
    # Exact-type dispatch above is the fast path; subclasses (IntEnum, str enums, OrderedDict,
    # user types deriving from builtins) are encoded as their base type.
    if v is None:
        raise TypeError("cannot marshal None unless allow_none is enabled")
    if isinstance(v, bool):
        _encode_value(bool(v), out)
    elif isinstance(v, int):
        _encode_value(int(v), out)
    elif isinstance(v, float):
        _encode_value(float(v), out)
    elif isinstance(v, str):
        _encode_value(str(v), out)
    elif isinstance(v, (bytes, bytearray)):
        _encode_value(bytes(v), out)
    elif isinstance(v, (list, tuple)):
        _encode_value(list(v), out)
    elif isinstance(v, dict):
        _encode_value(dict(v), out)
    else:
        raise TypeError(f"cannot marshal {type(v)} objects")


def _params(params: Sequence[object], out: list[str]) -> None:
    out.append("<params>\n")
    for p in params:
        out.append("<param>\n")
        _encode_value(p, out)
        out.append("</param>\n")
    out.append("</params>\n")


def encode_request(method: str, params: Sequence[object]) -> bytes:
    """A `methodCall` body, as xmlrpc.client.dumps(params, method) writes it."""
    out = [_XML_DECL, f"<methodCall>\n<methodName>{_escape(method)}</methodName>\n"]
    try:
        _params(params, out)
    except RecursionError:
        raise TypeError(_RECURSIVE) from None
    out.append("</methodCall>\n")
    return "".join(out).encode("utf-8", "xmlcharrefreplace")


_TRIPLE_HEAD = _XML_DECL + "<methodResponse>\n<params>\n<param>\n<value><array><data>\n"
_TRIPLE_TAIL = "</data></array></value>\n</param>\n</params>\n</methodResponse>\n"


_RECURSIVE = "cannot marshal recursive or too deeply nested values"


def encode_response(value: object) -> bytes:
    """A `methodResponse` body carrying one value."""
    try:
        return _encode_response(value)
    except RecursionError:
        raise TypeError(_RECURSIVE) from None


def _encode_response(value: object) -> bytes:
    if type(value) is list and len(value) == 3:
        # ROS's `[code, message, value]`, written without walking the outer list
        code, message, item = value
        if type(code) is int and type(message) is str and MIN_INT <= code <= MAX_INT:
            out = [_TRIPLE_HEAD, f"<value><int>{code}</int></value>\n",
                   f"<value><string>{_escape(message)}</string></value>\n"]
            _encode_value(item, out)
            out.append(_TRIPLE_TAIL)
            return "".join(out).encode("utf-8", "xmlcharrefreplace")
    out = [_XML_DECL, "<methodResponse>\n"]
    _params((value,), out)
    out.append("</methodResponse>\n")
    return "".join(out).encode("utf-8", "xmlcharrefreplace")


def encode_fault(code: int, message: str) -> bytes:
    """A `methodResponse` body carrying a fault."""
    out = [_XML_DECL, "<methodResponse>\n<fault>\n"]
    _encode_value({"faultCode": code, "faultString": message}, out)
    out.append("</fault>\n</methodResponse>\n")
    return "".join(out).encode("utf-8", "xmlcharrefreplace")


# ---------------------------------------------------------------------------------------- decode

# What a start tag does, keyed by (parent, tag); a pair missing here is a structure error. One
# dict lookup per element both validates the document shape and picks the action, so the value
# stack below can trust what it is given.
_VALUE, _SCALAR, _CONTAINER, _MEMBER, _NAME, _ONE_VALUE, _ROOT, _OTHER = range(8)
_SCALAR_TAGS = ("string", "int", "i4", "i8", "boolean", "double", "base64", "dateTime.iso8601")
_START: dict[tuple[str | None, str], int] = {
    (None, "methodCall"): _ROOT,
    (None, "methodResponse"): _ROOT,
    ("methodCall", "methodName"): _OTHER,
    ("methodCall", "params"): _OTHER,
    ("methodResponse", "params"): _OTHER,
    ("methodResponse", "fault"): _ONE_VALUE,
    ("params", "param"): _ONE_VALUE,
    ("param", "value"): _VALUE,
    ("data", "value"): _VALUE,
    ("member", "value"): _VALUE,
    ("fault", "value"): _VALUE,
    ("value", "array"): _CONTAINER,
    ("value", "struct"): _CONTAINER,
    ("array", "data"): _OTHER,
    ("struct", "member"): _MEMBER,
    ("member", "name"): _NAME,
    **{("value", tag): _SCALAR for tag in _SCALAR_TAGS},
}


def _boolean(text: str) -> bool:
    if text == "1":
        return True
    if text == "0":
        return False
    raise ValueError(f"bad boolean value {text!r}")


def _base64(text: str) -> bytes:
    import base64  # here: 0.15 MB in every node, for values that the ROS APIs seldom carry

    return base64.decodebytes(text.encode("ascii"))


_CONVERT: dict[str, Callable[[str], Value]] = {
    "int": int,
    "i4": int,
    "i8": int,
    "boolean": _boolean,
    "double": float,
    "base64": _base64,
    "dateTime.iso8601": DateTime,
}


class _Message:
    __slots__ = ("fault", "kind", "method", "params")

    def __init__(self, kind: str, method: str | None, params: list[Value], fault: bool) -> None:
        self.kind = kind  # "methodCall" or "methodResponse"
        self.method = method
        self.params = params
        self.fault = fault


def _refuse_dtd(_name: str, _sysid: str | None, _pubid: str | None, _internal: bool) -> None:
    raise MalformedError("DOCTYPE and entity declarations are not accepted")


def _decode(data: bytes) -> _Message:
    tags: list[str | None] = [None]  # open elements, innermost last
    stack: list[Value] = []  # decoded values and struct member names, in document order
    marks: list[int] = []  # stack length at each open param/fault/value/array/struct
    member_state: list[int] = []  # per open member: 0 nothing yet, 1 name seen, 2 value seen
    text: list[str] = []
    method: list[str] = []
    root: list[str] = []  # the root element's name, then "fault" if there was one
    join = "".join

    def start(tag: str, _attrs: object) -> None:
        parent = tags[-1]
        action = _START.get((parent, tag))
        if action is None:
            raise MalformedError(f"unexpected <{tag}> in <{parent}>")
        tags.append(tag)
        text.clear()
        if action == _VALUE:
            if len(tags) > MAX_DEPTH:
                raise MalformedError("XML-RPC value nested too deeply")
            if parent == "member":
                if member_state[-1] != 1:
                    raise MalformedError("struct member value without a name")
                member_state[-1] = 2
            marks.append(len(stack))
        elif action == _SCALAR:
            if len(stack) != marks[-1]:
                raise MalformedError("more than one item in a value")
        elif action == _CONTAINER:
            if len(stack) != marks[-1]:
                raise MalformedError("more than one item in a value")
            marks.append(len(stack))
        elif action == _MEMBER:
            member_state.append(0)
        elif action == _NAME:
            if member_state[-1] != 0:
                raise MalformedError("struct member with two names")
            member_state[-1] = 1
        elif action == _ONE_VALUE:
            marks.append(len(stack))
        elif action == _ROOT:
            root.append(tag)

    def end(tag: str) -> None:
        tags.pop()
        if tag == "value":
            n = len(stack) - marks.pop()
            if n == 0:
                # XmlRpc++ writes strings without a <string> tag
                stack.append(join(text))
            elif n != 1:
                raise MalformedError("more than one item in a value")
        elif tag == "string" or tag == "name":
            stack.append(join(text))
        elif tag == "array":
            mark = marks.pop()
            items = stack[mark:]
            del stack[mark:]
            stack.append(items)
        elif tag == "struct":
            mark = marks.pop()
            items = stack[mark:]
            del stack[mark:]
            stack.append(dict(zip(items[0::2], items[1::2], strict=True)))  # type: ignore[arg-type]
        elif tag == "member":
            if member_state.pop() != 2:
                raise MalformedError("struct member without a value")
        elif tag == "param" or tag == "fault":
            if len(stack) - marks.pop() != 1:
                raise MalformedError(f"<{tag}> must hold exactly one value")
            if tag == "fault":
                root.append(tag)
        elif tag == "methodName":
            method.append(join(text))
        else:
            convert = _CONVERT.get(tag)
            if convert is not None:
                try:
                    stack.append(convert(join(text)))
                except (ValueError, binascii.Error) as e:
                    raise MalformedError(f"bad <{tag}>: {e}") from e
        text.clear()

    parser = expat.ParserCreate()
    parser.buffer_text = True
    # Entities can only be declared inside a DOCTYPE, so refusing it at its start refuses them all.
    parser.StartDoctypeDeclHandler = _refuse_dtd
    parser.StartElementHandler = start
    parser.EndElementHandler = end
    parser.CharacterDataHandler = text.append
    try:
        parser.Parse(data, True)
    except expat.ExpatError as e:
        raise MalformedError(f"not well-formed XML: {e}") from e
    return _Message(root[0], method[0] if method else None, stack, len(root) > 1)


# The fast path for flat requests. Whitespace between elements is ignored by the full parser too;
# text is printable ASCII, tab and newline, without `&` and `<` (no references or markup), `]`
# (so never `]]>`) or CR (which expat would normalise). Numbers are limited to forms int() and
# float() read exactly as they read the full parser's text.
_WS = rb"[ \t\r\n]*"
_TEXT = rb"[\t\n\x20-\x25\x27-\x3b\x3d-\x5c\x5e-\x7e]*"
_FAST_HEAD = re.compile(
    rb"(?:<\?xml version=(?:'1\.0'|\"1\.0\")\?>)?" + _WS + rb"<methodCall>" + _WS
    + rb"<methodName>(" + _TEXT + rb")</methodName>" + _WS + rb"(<params>" + _WS + rb")?")
_FAST_PARAM = re.compile(
    rb"<param>" + _WS + rb"<value>(?:"
    rb"<string>(" + _TEXT + rb")</string>"  # 1
    rb"|<int>(-?[0-9]{1,18})</int>"  # 2
    rb"|<i4>(-?[0-9]{1,18})</i4>"  # 3
    rb"|<boolean>([01])</boolean>"  # 4
    rb"|<double>(-?[0-9]{1,300}(?:\.[0-9]{1,300})?(?:e[-+]?[0-9]{1,3})?)</double>"  # 5
    rb"|(" + _TEXT + rb"))"  # 6: XmlRpc++'s untagged string
    rb"</value>" + _WS + rb"</param>" + _WS)
_FAST_END_PARAMS = re.compile(rb"</params>" + _WS + rb"</methodCall>" + _WS)
_FAST_END = re.compile(rb"</methodCall>" + _WS)


def _decode_flat_request(data: bytes) -> tuple[str, list[Value]] | None:
    """(method, params) if `data` is a flat request the fast path reads, else None."""
    m = _FAST_HEAD.match(data)
    if m is None:
        return None
    method = m.group(1).decode("ascii")
    pos = m.end()
    params: list[Value] = []
    if m.group(2) is not None:
        match_param = _FAST_PARAM.match
        append = params.append
        while (p := match_param(data, pos)) is not None:
            kind = p.lastindex
            text = p.group(kind)  # type: ignore[arg-type]
            if kind == 1 or kind == 6:
                append(text.decode("ascii"))
            elif kind == 4:
                append(text == b"1")
            elif kind == 5:
                append(float(text))
            else:
                append(int(text))
            pos = p.end()
        end = _FAST_END_PARAMS
    else:
        end = _FAST_END
    if end.fullmatch(data, pos) is None:
        return None
    return method, params


def decode_request(data: bytes) -> tuple[str, list[Value]]:
    """Decode a `methodCall` body into (method name, params). Raises MalformedError."""
    fast = _decode_flat_request(data)
    if fast is not None:
        return fast
    return _decode_request_full(data)


def _decode_request_full(data: bytes) -> tuple[str, list[Value]]:
    msg = _decode(data)
    if msg.kind != "methodCall" or msg.method is None:
        raise MalformedError("not an XML-RPC method call")
    return msg.method, msg.params


def decode_response(data: bytes) -> Value:
    """Decode a `methodResponse` body into its value. Raises Fault or MalformedError."""
    msg = _decode(data)
    if msg.kind != "methodResponse":
        raise MalformedError("not an XML-RPC method response")
    if msg.fault:
        f = msg.params[0] if len(msg.params) == 1 else None
        if not isinstance(f, dict):
            raise MalformedError("bad XML-RPC fault")
        code, message = f.get("faultCode"), f.get("faultString")
        if type(code) is not int or not isinstance(message, str):
            raise MalformedError("bad XML-RPC fault")
        raise Fault(code, message)
    if len(msg.params) != 1:
        raise MalformedError("an XML-RPC response carries exactly one value")
    return msg.params[0]

