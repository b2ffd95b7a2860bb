"""genmsg.gentools: md5sums and full definition texts of loaded specs, computed by kame's
(kame.msg.md5, the rules that make kame's own message classes' md5sums ROS's) on the specs
a MsgContext holds."""

from __future__ import annotations

from io import StringIO as StringIO  # genmsg.gentools' name, imported from it by old code

from genmsg import base, msgs, names
from genmsg.base import InvalidMsgSpec
from genmsg.msg_loader import MsgContext, load_depends
from genmsg.msgs import MsgSpec, bare_msg_type, is_builtin
from genmsg.srvs import SrvSpec
from kame.msg import md5 as _md5
from kame.msg import spec as _kame

__all__ = ["InvalidMsgSpec", "MsgSpec", "SrvSpec", "bare_msg_type", "base", "compute_full_text",
           "compute_full_type_name", "compute_md5", "compute_md5_text", "compute_md5_v2", "is_builtin",
           "load_depends", "msgs", "names"]


def _kame_spec(spec: MsgSpec) -> _kame.MsgSpec:
    fields = tuple(_kame.Field(f.name, f.type, f.base_type, f.is_array, f.array_len) for f in spec.parsed_fields())
    constants = tuple(_kame.Constant(c.type, c.name, c.val, c.val_text) for c in spec.constants)
    return _kame.MsgSpec(spec.full_name, fields, constants, spec.text)


def _md5_cache(msg_context: MsgContext) -> _md5.Md5Cache:
    return _md5.Md5Cache(lambda full_name: _kame_spec(msg_context.get_registered(full_name)))


def compute_md5_text(msg_context: MsgContext, spec: MsgSpec) -> str:
    """The text a message's md5sum is of: constants first, then fields, each message field as
    its type's md5sum (KeyError for a type `msg_context` does not hold)."""
    return _md5_cache(msg_context).md5_text(_kame_spec(spec))


def compute_md5(msg_context: MsgContext, spec: MsgSpec | SrvSpec) -> str:
    """The md5sum of a message, or of a service (its request's md5 text then its response's)."""
    cache = _md5_cache(msg_context)
    if isinstance(spec, MsgSpec):
        return cache.md5sum(_kame_spec(spec))
    if isinstance(spec, SrvSpec):
        srv = _kame.SrvSpec(spec.full_name, _kame_spec(spec.request), _kame_spec(spec.response), spec.text)
        return cache.srv_md5sum(srv)
    raise Exception(f"[{spec}] is not a message or service")


compute_md5_v2 = compute_md5


def compute_full_text(msg_context: MsgContext, spec: MsgSpec) -> str:
    """The message_definition: the spec's text, then each type it uses (depth first, once) after
    a line of 80 '=' and `MSG: pkg/Type`. The types are those load_depends recorded (KeyError
    when it was not called)."""
    msg_context.get_all_depends(spec.full_name)
    return _md5.full_text(_kame_spec(spec), lambda full_name: _kame_spec(msg_context.get_registered(full_name)))


def compute_full_type_name(package_name: str, file_name: str) -> str:
    """'std_msgs', 'String.msg' -> 'std_msgs/String'; MsgGenerationException for another extension."""
    for ext in (base.EXT_MSG, base.EXT_SRV):
        if file_name.endswith(ext):
            return f"{package_name}/{file_name[:-len(ext)]}"
    raise base.MsgGenerationException(f"Processing file: '{file_name}' - unknown file extension")
