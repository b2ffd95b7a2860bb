"""Run by Debian's /usr/bin/python3: answers questions about real ROS 1 messages as JSON.

stdin: {"md5_types": [...], "srv_types": [...], "samples": [{"type": T, "value": plain}]}
stdout: {"md5": {T: md5 by genmsg from /usr/share}, "srv_md5": {...},
         "classes": {T: {"md5": genpy _md5sum, "full_text": genpy _full_text}},
         "samples": [{"type": T, "hex": genpy bytes, "str": str(msg)} or {"type": T, "missing": true}]}
"""

import importlib
import io
import json
import os
import sys

import genmsg
import genmsg.msg_loader
import genpy
from genmsg import gentools

SHARE = "/usr/share"


def search_path():
    path = {}
    for name in os.listdir(SHARE):
        for kind in ("msg",):
            folder = os.path.join(SHARE, name, kind)
            if os.path.isdir(folder):
                path.setdefault(name, []).append(folder)
    return path


def genmsg_md5(context, path, type_name):
    spec = genmsg.msg_loader.load_msg_by_type(context, type_name, path)
    genmsg.msg_loader.load_depends(context, spec, path)
    return gentools.compute_md5(context, spec)


def genmsg_srv_md5(context, path, type_name):
    package, short = type_name.split("/")
    spec = genmsg.msg_loader.load_srv_from_file(context, os.path.join(SHARE, package, "srv", short + ".srv"),
                                                type_name)
    genmsg.msg_loader.load_depends(context, spec, path)
    return gentools.compute_md5(context, spec)


def genpy_class(type_name):
    package, short = type_name.split("/")
    kind = "srv" if short.endswith(("Request", "Response")) and os.path.exists(
        os.path.join(SHARE, package, "srv", short.replace("Request", "").replace("Response", "") + ".srv")) else "msg"
    try:
        return getattr(importlib.import_module(package + "." + kind), short)
    except (ImportError, AttributeError):
        return None


def build(cls, plain):
    msg = cls()
    for name, slot_type in zip(cls.__slots__, cls._slot_types, strict=True):
        setattr(msg, name, convert(getattr(msg, name), slot_type, plain[name]))
    return msg


def convert(default, slot_type, plain):
    base = slot_type.split("[")[0]
    if "[" in slot_type:
        if base in ("uint8", "char"):
            return bytes.fromhex(plain["__bytes__"])
        return [convert(None, base, item) for item in plain]
    if base == "time":
        return genpy.Time(plain["secs"], plain["nsecs"])
    if base == "duration":
        return genpy.Duration(plain["secs"], plain["nsecs"])
    if isinstance(plain, dict):
        package, short = (base if "/" in base else "std_msgs/Header").split("/")
        return build(getattr(importlib.import_module(package + ".msg"), short), plain)
    return plain


def main():
    request = json.load(sys.stdin)
    context = genmsg.MsgContext.create_default()
    path = search_path()
    answer = {"md5": {}, "srv_md5": {}, "classes": {}, "samples": []}
    for type_name in request["md5_types"]:
        try:
            answer["md5"][type_name] = genmsg_md5(context, path, type_name)
        except Exception as exc:  # reported, and the test decides
            answer["md5"][type_name] = f"error: {exc}"
        cls = genpy_class(type_name)
        if cls is not None:
            answer["classes"][type_name] = {"md5": cls._md5sum, "full_text": cls._full_text}
    for type_name in request["srv_types"]:
        try:
            answer["srv_md5"][type_name] = genmsg_srv_md5(context, path, type_name)
        except Exception as exc:
            answer["srv_md5"][type_name] = f"error: {exc}"
    for sample in request["samples"]:
        cls = genpy_class(sample["type"])
        if cls is None:
            answer["samples"].append({"type": sample["type"], "missing": True})
            continue
        msg = build(cls, sample["value"])
        buff = io.BytesIO()
        msg.serialize(buff)
        answer["samples"].append({"type": sample["type"], "hex": buff.getvalue().hex(), "str": str(msg)})
    json.dump(answer, sys.stdout)


main()
