"""rospy.numpy_msg: message classes whose numeric arrays are numpy arrays.

`Floats = numpy_msg(rospy_tutorials.msg.Floats)` gives a class that serializes from and
deserializes into numpy arrays (the generated serialize_numpy/deserialize_numpy), for use as
a Publisher's or Subscriber's data class.
"""

from __future__ import annotations

from typing import Any

_cache: dict[type[Any], type[Any]] = {}


def numpy_msg(msg_type: type[Any]) -> type[Any]:
    cached = _cache.get(msg_type)
    if cached is not None:
        return cached
    import numpy

    def serialize(self: Any, buff: Any) -> None:
        msg_type.serialize_numpy(self, buff, numpy)

    def deserialize(self: Any, data: Any) -> Any:
        return msg_type.deserialize_numpy(self, data, numpy)

    numpy_type = type(f"Numpy_{msg_type._type.replace('/', '__')}", (msg_type,), {
        "__slots__": (),
        "serialize": serialize,
        "deserialize": deserialize,
        # the arrays are views of what they are read from: a copy that is theirs, not the
        # subscriber's reused read buffer or the publisher's shared-memory ring
        "_from_buffer": classmethod(lambda cls, data: deserialize(object.__new__(cls), bytes(data))),
        "__module__": msg_type.__module__,
    })
    _cache[msg_type] = numpy_type
    return numpy_type
