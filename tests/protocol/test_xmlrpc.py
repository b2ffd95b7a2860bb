import xmlrpc.client

import pytest

from kame.protocol import xmlrpc as x

# Values whose encoding must equal xmlrpc.client.dumps byte for byte (rospy's own writer).
SAMPLES = [
    1,
    -(2**31),
    2**31 - 1,
    "plain",
    "",
    "a&b<c>d\"e'",
    "ünïcødé ✓",
    True,
    False,
    1.5,
    -0.0,
    1e300,
    b"\x00\x01binary\xff",
    b"",
    [],
    {},
    [1, "two", 3.0, [True, {"k": "v"}]],
    {"a": {"b": {"c": [1, 2, {"d": b"x"}]}}, "e&": "f<"},
    [1, "", 0],
    [[["/t", ["/n1", "/n2"]]], [], [["/s", ["/n"]]]],
    # ROS's [code, message, value] triples (encoded by a shortcut) and near misses
    [1, "node api", "http://h:1/"],
    [-1, "unknown node [/a&b]", ""],
    [1, "Registered [/n] as publisher of [/t]", ["http://h:1/", "http://h:2/"]],
    [1, "current system state", [[["/t", ["/n"]]], [], []]],
    [1, "Parameter [/p]", {"a": [1.5, True, b"x"]}],
    [-(2**31), "", 0],
    [True, "x", 1],
    [1.0, "x", 1],
    [1, 2, 3],
    [1, "x"],
]


@pytest.mark.parametrize("value", SAMPLES)
def test_response_bytes_equal_stdlib(value: object) -> None:
    want = xmlrpc.client.dumps((_stdlib(value),), methodresponse=True, allow_none=False).encode()
    assert x.encode_response(value) == want


@pytest.mark.parametrize("value", SAMPLES)
def test_request_bytes_equal_stdlib(value: object) -> None:
    want = xmlrpc.client.dumps(("/caller", _stdlib(value)), "setParam").encode()
    assert x.encode_request("setParam", ["/caller", value]) == want


def test_empty_request_and_fault_bytes() -> None:
    assert x.encode_request("getPid", []) == xmlrpc.client.dumps((), "getPid").encode()
    want = xmlrpc.client.dumps(xmlrpc.client.Fault(1, "boom & <bang>"), methodresponse=True).encode()
    assert x.encode_fault(1, "boom & <bang>") == want


def _stdlib(v: object) -> object:
    if isinstance(v, bytes):
        return xmlrpc.client.Binary(v)
    if isinstance(v, list):
        return [_stdlib(i) for i in v]
    if isinstance(v, dict):
        return {k: _stdlib(i) for k, i in v.items()}
    return v


@pytest.mark.parametrize("value", SAMPLES)
def test_round_trip(value: object) -> None:
    assert x.decode_response(x.encode_response(value)) == value
    assert x.decode_request(x.encode_request("m", [value, value])) == ("m", [value, value])


def test_tuple_and_subclasses_encode_as_base_types() -> None:
    class S(str):
        pass

    class I(int):  # noqa: E742 - a one-letter subclass name is clear here
        pass

    assert x.encode_response((1, S("s"), I(3))) == x.encode_response([1, "s", 3])


@pytest.mark.parametrize(
    ("value", "error"),
    [(None, TypeError), ([1, None], TypeError), (2**31, OverflowError), (-(2**31) - 1, OverflowError),
     ([2**31, "", 0], OverflowError), ([1, "", 2**31], OverflowError), ([1, "", None], TypeError),
     ({1: "a"}, TypeError), (object(), TypeError)],
)
def test_encode_refuses(value: object, error: type[Exception]) -> None:
    with pytest.raises(error):
        x.encode_response(value)


def test_encode_refuses_recursive_and_too_deep_values_with_a_type_error() -> None:
    # These escaped as RecursionError (xmlrpc.client says TypeError: cannot marshal recursive ...).
    cyclic: list[object] = []
    cyclic.append(cyclic)
    looped: dict[str, object] = {}
    looped["a"] = looped
    deep: list[object] = []
    for _ in range(5000):
        deep = [deep]
    for value in (cyclic, looped, deep):
        with pytest.raises(TypeError, match="recursive or too deeply nested"):
            x.encode_response(value)
        with pytest.raises(TypeError, match="recursive or too deeply nested"):
            x.encode_response([1, "", value])
        with pytest.raises(TypeError, match="recursive or too deeply nested"):
            x.encode_request("setParam", ["/n", "/p", value])


# What roscpp (XmlRpc++ 0.7) sends: untagged strings, <i4>, CRLF and tabs between elements.
XMLRPCPP_REQUEST = (
    b'<?xml version="1.0"?>\r\n<methodCall><methodName>registerPublisher</methodName>\r\n<params>'
    b"<param><value>/cppnode</value></param><param><value>/chatter</value></param>"
    b"<param><value>std_msgs/String</value></param><param><value>http://host:40123/</value></param>"
    b"</params></methodCall>\r\n"
)
XMLRPCPP_RESPONSE = (
    b'<?xml version="1.0"?>\r\n<methodResponse><params><param>\r\n\t<value><array><data>'
    b"<value><i4>1</i4></value><value></value><value><array><data><value>TCPROS</value>"
    b"<value>host</value><value><i4>40124</i4></value></data></array></value></data></array></value>\r\n"
    b"</param></params></methodResponse>\r\n"
)
XMLRPCPP_FAULT = (
    b'<?xml version="1.0"?>\r\n<methodResponse><fault>\r\n\t<value><struct><member><name>faultCode</name>'
    b"<value><i4>-1</i4></value></member><member><name>faultString</name><value>getUri: unknown method "
    b"name</value></member></struct></value>\r\n</fault></methodResponse>\r\n"
)


def test_decode_xmlrpcpp_request() -> None:
    assert x.decode_request(XMLRPCPP_REQUEST) == (
        "registerPublisher", ["/cppnode", "/chatter", "std_msgs/String", "http://host:40123/"])


def test_decode_xmlrpcpp_response_and_fault() -> None:
    assert x.decode_response(XMLRPCPP_RESPONSE) == [1, "", ["TCPROS", "host", 40124]]
    with pytest.raises(x.Fault) as e:
        x.decode_response(XMLRPCPP_FAULT)
    assert (e.value.code, e.value.message) == (-1, "getUri: unknown method name")


def test_decode_scalars() -> None:
    body = (
        b"<methodResponse><params><param><value><array><data>"
        b"<value><i8>4294967296</i8></value><value><int> 7 </int></value><value><boolean>1</boolean></value>"
        b"<value><double>2.5</double></value><value><base64>aGk=\n</base64></value>"
        b"<value><dateTime.iso8601>20260101T00:00:00</dateTime.iso8601></value>"
        b"<value><string>a&amp;b&#x263A;</string></value><value>\n  spaced  \n</value>"
        b"<value><struct></struct></value><value><array><data></data></array></value>"
        b"</data></array></value></param></params></methodResponse>"
    )
    assert x.decode_response(body) == [
        2**32, 7, True, 2.5, b"hi", x.DateTime("20260101T00:00:00"), "a&b\u263a", "\n  spaced  \n", {}, []]


def test_datetime_round_trips() -> None:
    v = x.DateTime("20260101T00:00:00")
    assert x.decode_response(x.encode_response(v)) == v


def test_decode_request_with_no_params_element() -> None:
    assert x.decode_request(b"<methodCall><methodName>getPid</methodName></methodCall>") == ("getPid", [])


MALFORMED = [
    b"",
    b"not xml",
    b"<methodCall><methodName>m</methodName>",  # truncated
    b"<methodCall><methodName>m</methodName><params><param><value><nil/></value></param></params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><int>x</int></value></param></params>"
    b"</methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><boolean>2</boolean></value></param>"
    b"</params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><base64>a</base64></value></param>"
    b"</params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><int>1</int><int>2</int></value></param>"
    b"</params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param></param></params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value>a</value><value>b</value></param>"
    b"</params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><struct><member><value>1</value>"
    b"</member></struct></value></param></params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><struct><member><name>a</name>"
    b"</member></struct></value></param></params></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value><struct><member><name>a</name><name>b"
    b"</name><value>1</value></member></struct></value></param></params></methodCall>",
    b"<methodCall><params/></methodCall>",  # no method name
    b"<other/>",
    b"<methodCall><methodName>m</methodName><bogus/></methodCall>",
    b"<methodResponse><params/></methodResponse>",  # a response, not a call
]


@pytest.mark.parametrize("body", MALFORMED)
def test_decode_request_refuses(body: bytes) -> None:
    with pytest.raises(x.MalformedError):
        x.decode_request(body)


@pytest.mark.parametrize(
    "body",
    [b"<methodResponse><params></params></methodResponse>",
     b"<methodResponse><fault><value><int>1</int></value></fault></methodResponse>",
     b"<methodResponse><fault><value><struct></struct></value></fault></methodResponse>",
     b"<methodCall><methodName>m</methodName></methodCall>"],
)
def test_decode_response_refuses(body: bytes) -> None:
    with pytest.raises(x.MalformedError):
        x.decode_response(body)


def test_doctype_and_entities_refused() -> None:
    laughs = (
        b'<?xml version="1.0"?><!DOCTYPE lolz [<!ENTITY lol "lol">'
        + b"".join(b'<!ENTITY lol%d "%s">' % (i, (b"&lol%d;" % (i - 1) if i > 1 else b"&lol;") * 10)
                   for i in range(1, 10))
        + b"]><methodCall><methodName>&lol9;</methodName></methodCall>"
    )
    with pytest.raises(x.MalformedError, match="DOCTYPE"):
        x.decode_request(laughs)
    external = (b'<?xml version="1.0"?><!DOCTYPE r [<!ENTITY e SYSTEM "file:///etc/passwd">]>'
                b"<methodCall><methodName>&e;</methodName></methodCall>")
    with pytest.raises(x.MalformedError):
        x.decode_request(external)
    # an undeclared entity is just bad XML
    with pytest.raises(x.MalformedError):
        x.decode_request(b"<methodCall><methodName>&e;</methodName></methodCall>")


def test_nesting_is_bounded() -> None:
    ok = 40
    body = x.encode_request("m", [_nest(ok)])
    assert x.decode_request(body)[1] == [_nest(ok)]
    deep = (b"<methodCall><methodName>m</methodName><params><param>"
            + b"<value><array><data>" * 10000 + b"</data></array></value>" * 10000
            + b"</param></params></methodCall>")
    with pytest.raises(x.MalformedError, match="deep"):
        x.decode_request(deep)


def _nest(n: int) -> object:
    v: object = 1
    for _ in range(n):
        v = [v]
    return v


def test_agrees_with_stdlib_loads_on_python_output() -> None:
    for value in SAMPLES:
        body = xmlrpc.client.dumps((_stdlib(value), "x"), "m", allow_none=False)
        params, method = xmlrpc.client.loads(body, use_builtin_types=True)
        assert x.decode_request(body.encode()) == (method, list(params))


def test_fault_str() -> None:
    assert str(x.Fault(1, "m")) == "<Fault 1: 'm'>"


# ---------------------------------------------------------------------------------------- fast path
# Flat requests skip expat. The fast path must give exactly the full parser's values, and must
# decline (return None, so the full parser decides) everything outside its strict subset.

def _full(body: bytes) -> tuple[str, list[object]] | type[x.MalformedError]:
    try:
        return x._decode_request_full(body)  # type: ignore[return-value]
    except x.MalformedError:
        return x.MalformedError


FAST = [
    xmlrpc.client.dumps(("/caller", "/node"), "lookupNode").encode(),
    xmlrpc.client.dumps(("/c", "/t", "std_msgs/String", "http://h:1/"), "registerPublisher").encode(),
    xmlrpc.client.dumps(("/c",), "getSystemState").encode(),
    xmlrpc.client.dumps((), "getPid").encode(),
    xmlrpc.client.dumps(("/c", "/k", 7, -(2**31), True, False, 1.5, -0.0, 1e300, 1.5e-07, ""), "m").encode(),
    xmlrpc.client.dumps(("tab\tand\nnewline", "~!@#$%^*()_+{}|:\"'?/.,;=`"), "m").encode(),
    XMLRPCPP_REQUEST,
    b'<?xml version="1.0"?>\r\n<methodCall><methodName>getParam</methodName>\r\n<params><param><value>/n'
    b"</value></param><param><value></value></param><param><value><i4>-5</i4></value></param>"
    b"</params></methodCall>\r\n",
    b"<methodCall><methodName>getPid</methodName></methodCall>",
    b" \n<methodCall><methodName></methodName><params></params></methodCall>\n\n",
    b"<methodCall><methodName>m</methodName><params><param><value><int>0007</int></value></param>"
    b"<param><value><double>12</double></value></param></params></methodCall>",
]


@pytest.mark.parametrize("body", FAST)
def test_fast_path_takes_flat_requests_with_identical_values(body: bytes) -> None:
    fast = x._decode_flat_request(body)
    assert fast is not None
    assert fast == _full(body) == x.decode_request(body)
    assert [type(v) for v in fast[1]] == [type(v) for v in _full(body)[1]]  # type: ignore[index]


def _call(*params: bytes, method: bytes = b"m") -> bytes:
    return (b"<?xml version='1.0'?>\n<methodCall>\n<methodName>" + method + b"</methodName>\n<params>\n"
            + b"".join(b"<param>\n<value>" + p + b"</value>\n</param>\n" for p in params)
            + b"</params>\n</methodCall>\n")


# Valid requests the fast path leaves to expat (the full parser reads them).
FALLBACK_VALID = [
    _call(b"<string>a&amp;b</string>"),  # entity
    _call(b"<string>&#x263A;</string>"),  # character reference
    _call(b"<string><![CDATA[<x>]]></string>"),  # CDATA
    _call(b"<string>\xc3\xbcn\xc3\xafc\xc3\xb8de</string>"),  # non-ASCII
    _call(b"<string>[::1]</string>"),  # `]`
    _call(b"<string>a\r\nb</string>"),  # CR, normalised by expat
    _call(b"<array><data><value>a</value></data></array>"),  # nesting
    _call(b"<struct><member><name>a</name><value>1</value></member></struct>"),
    _call(b"<base64>aGk=\n</base64>"),
    _call(b"<dateTime.iso8601>20260101T00:00:00</dateTime.iso8601>"),
    _call(b"<int> 7 </int>"),
    _call(b"<int>+7</int>"),
    _call(b"<double>1E5</double>"),
    _call(b"<double>inf</double>"),
    _call(b"<i8>4294967296</i8>"),
    _call(b"<int>" + b"9" * 19 + b"</int>"),
    _call(b"\n<string>x</string>\n"),  # text around a typed value inside <value>
    _call(b"<!-- hi --><string>x</string>"),  # comment
    _call(b"x", method=b"a&amp;b"),
    b"<?xml version='1.0' encoding='utf-8'?>\n<methodCall><methodName>m</methodName></methodCall>",
    b"<?xml version='1.1'?><methodCall><methodName>m</methodName></methodCall>",
    _call(b"<string>a&gt;b</string>"),
    b"<?xml version='1.0'?><?pi x?><methodCall><methodName>m</methodName></methodCall>",
    b"<methodCall><methodName>m</methodName><params/></methodCall>",
    b"<methodCall><methodName>m</methodName><params><param><value/></param></params></methodCall>",
    b'<methodCall ><methodName a="1">m</methodName></methodCall>',
    b"\xef\xbb\xbf<methodCall><methodName>m</methodName></methodCall>",  # UTF-8 BOM
    b"<methodCall><methodName>m</methodName><params><param>junk<value>a</value></param></params></methodCall>",
]


@pytest.mark.parametrize("body", FALLBACK_VALID)
def test_fast_path_declines_what_only_the_full_parser_reads(body: bytes) -> None:
    assert x._decode_flat_request(body) is None
    assert x.decode_request(body) == _full(body) != x.MalformedError


FALLBACK_INVALID = [
    *MALFORMED,
    _call(b"<string>a]]>b</string>"),
    _call(b"<string>a\x01b</string>"),
    _call(b"<string>a\xffb</string>"),
    _call(b"<string>\xef\xbf\xbe</string>"),  # U+FFFE: valid UTF-8, not an XML character
    _call(b"<string>x</str>"),
    _call(b"<int>1</i4>"),
    _call(b"<value>x</value>"),
    _call(b"<boolean>2</boolean>"),
    _call(b"<string>a</string>") + b"<trailing/>",
    _call(b"<string>a</string>") + b"junk",
    b"\n<?xml version='1.0'?><methodCall><methodName>m</methodName></methodCall>",  # decl not first
    b"<methodCall><methodName>m</methodName><params></methodCall>",
    b"<methodCall><methodName>m</methodName></params></methodCall>",
    b"<methodCall><methodName>m</methodName>",
    b"<methodcall><methodName>m</methodName></methodcall>",
]


@pytest.mark.parametrize("body", FALLBACK_INVALID)
def test_fast_path_never_accepts_what_the_full_parser_refuses(body: bytes) -> None:
    assert x._decode_flat_request(body) is None
    with pytest.raises(x.MalformedError):
        x.decode_request(body)


def test_fast_path_agrees_with_full_parser_on_mutations() -> None:
    # Differential fuzz: mutate accepted requests byte by byte; whatever the fast path accepts,
    # the full parser must accept with identical values (and types).
    import random

    rng = random.Random(3)
    alphabet = [*b"<>/&;]!?=x01-.e \t\r\n'\"", 0, 0x80, 0xC3, 0xFF, 0x0B]
    seeds = [*FAST, _call(b"<string>ab</string>", b"<int>-12</int>", b"<double>1.5e+10</double>", b"zz")]
    accepted = 0
    for _ in range(20000):
        body = bytearray(rng.choice(seeds))
        for _ in range(rng.randint(1, 3)):
            i = rng.randrange(len(body) + 1)
            op = rng.randrange(3)
            if op == 0:
                body.insert(i, rng.choice(alphabet))
            elif op == 1 and i < len(body):
                del body[i]
            elif i < len(body):
                body[i] = rng.choice(alphabet)
        data = bytes(body)
        fast = x._decode_flat_request(data)
        if fast is not None:
            accepted += 1
            full = _full(data)
            assert full == fast, data
            assert [type(v) for v in fast[1]] == [type(v) for v in full[1]], data  # type: ignore[index]
    assert accepted > 300  # the fuzz did exercise the fast path


def test_decoders_raise_only_their_own_errors_on_mutated_bodies() -> None:
    # Seeded fuzz: structural tokens and bytes spliced into valid calls, responses and faults.
    # Whatever comes in, the decoders raise MalformedError or Fault, never anything else.
    import random

    rng = random.Random(11)
    seeds = [
        x.encode_request("registerPublisher", ["/n", "/t", "std_msgs/String", "http://h:1/"]),
        x.encode_request("m", [[1, 2.5, True, "x", b"abc", {"a": [1, {"b": "c"}]}]]),
        x.encode_response([1, "ok", [["/a", ["/b"]]]]),
        x.encode_fault(1, "bad"),
        XMLRPCPP_REQUEST,
    ]
    tokens = [b"<value>", b"</value>", b"<struct>", b"</struct>", b"<member>", b"</member>", b"<name>",
              b"</name>", b"<array>", b"</array>", b"<data>", b"</data>", b"<param>", b"</param>",
              b"<params>", b"</params>", b"<int>", b"</int>", b"<fault>", b"</fault>", b"<methodName>",
              b"</methodName>", b"<string>", b"</string>", b"<base64>", b"</base64>", b"<double>",
              b"<boolean>", b"<dateTime.iso8601>", b"<nil/>", b"<i8>", b"9" * 5000, b"&amp;", b"&#0;", b"\xff"]
    for _ in range(6000):
        body = bytearray(rng.choice(seeds))
        for _ in range(rng.randint(1, 4)):
            i = rng.randrange(len(body) + 1)
            op = rng.randrange(4)
            if op == 0:
                del body[i:i + rng.randint(1, 10)]
            elif op == 1:
                body[i:i] = rng.choice(tokens)
            elif op == 2 and i < len(body):
                body[i] = rng.randrange(256)
            else:
                j = rng.randrange(len(body) + 1)
                body[i:i] = body[j:j + rng.randint(1, 40)]
        data = bytes(body)
        for decode in (x.decode_request, x.decode_response):
            try:
                decode(data)
            except (x.MalformedError, x.Fault):
                pass
