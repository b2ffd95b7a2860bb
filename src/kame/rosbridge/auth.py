"""~authenticate: a client's auth op, checked by rosauth's /authenticate service.

As Noetic's rosbridge_websocket: until a client has authenticated, its only allowed op is
"auth" {mac, client, dest, rand, t, level, end}, handed to the service `authenticate` (resolved
in the bridge's namespace; rosauth's ros_mac_authentication serves it). `t` and `end` are
{secs, nsecs}, or a number of seconds as upstream's rospy.Time(msg['t']) reads them. An auth op
that cannot be read, or a call that fails (no /authenticate), is a status error and the client
stays unauthenticated: upstream hands those frames to its protocol, which answers with an error.
"""

from __future__ import annotations

import math
from typing import Any

from kame.client.errors import ROSException
from kame.client.services import ServiceException, ServiceProxy
from kame.msg.errors import MessageError
from kame.rosbridge import conversion, protocol
from rosauth.srv import Authentication

SERVICE = "authenticate"
STRING_FIELDS = ("mac", "client", "dest", "rand", "level")
TIME_FIELDS = ("t", "end")


def _time(value: Any) -> Any:
    if isinstance(value, (int, float)) and not isinstance(value, bool) and math.isfinite(value):
        secs = int(value)
        return {"secs": secs, "nsecs": round((value - secs) * 1e9)}
    return value


def request_fields(op: dict[str, Any]) -> dict[str, Any]:
    """The rosauth/Authentication request's fields from an auth op (ProtocolError if one is missing)."""
    fields = protocol.Fields(op)
    values: dict[str, Any] = {name: fields.string(name) for name in STRING_FIELDS}
    for name in TIME_FIELDS:
        if name not in op:
            raise protocol.ProtocolError(f"auth: missing field '{name}'", "auth", fields.id)
        values[name] = _time(op[name])
    return values


def authenticated(op: dict[str, Any]) -> bool:
    """The service's verdict on an auth op; ProtocolError when the op or the call goes wrong."""
    op_id = op.get("id")
    try:
        request = conversion.from_json(Authentication._request_class, request_fields(op))
    except (conversion.ConversionError, MessageError, ValueError, TypeError) as exc:
        raise protocol.ProtocolError(f"auth: {exc}", "auth", op_id) from None
    proxy = ServiceProxy(SERVICE, Authentication)
    try:
        return bool(proxy.call(request).authenticated)
    except (ServiceException, ROSException, MessageError) as exc:
        raise protocol.ProtocolError(f"auth: {exc}", "auth", op_id) from None
    finally:
        proxy.close()
