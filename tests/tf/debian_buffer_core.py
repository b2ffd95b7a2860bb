"""Run under Debian's /usr/bin/python3: replays a JSON script on tf2's real BufferCore (tf2_py).

stdin: {"cache_time": s, "ops": [[op, ...], ...]}; stdout: one result per op:
["ok", value] or [exception class name, message].
"""

import json
import sys

import tf2_py

import rospy
from geometry_msgs.msg import TransformStamped


def stamp(ns):
    return rospy.Time(ns // 10**9, ns % 10**9)


def transform(parent, child, ns, translation, rotation):
    msg = TransformStamped()
    msg.header.frame_id, msg.child_frame_id, msg.header.stamp = parent, child, stamp(ns)
    (msg.transform.translation.x, msg.transform.translation.y, msg.transform.translation.z) = translation
    (msg.transform.rotation.x, msg.transform.rotation.y, msg.transform.rotation.z,
     msg.transform.rotation.w) = rotation
    return msg


def plain(msg):
    t, r = msg.transform.translation, msg.transform.rotation
    return [msg.header.frame_id, msg.child_frame_id, msg.header.stamp.to_nsec(), [t.x, t.y, t.z], [r.x, r.y, r.z, r.w]]


script = json.load(sys.stdin)
core = tf2_py.BufferCore(rospy.Duration(script["cache_time"]))
results = []
for op, *args in script["ops"]:
    try:
        if op == "set":
            parent, child, ns, translation, rotation, authority, static = args
            setter = core.set_transform_static if static else core.set_transform
            value = setter(transform(parent, child, ns, translation, rotation), authority)
        elif op == "lookup":
            value = plain(core.lookup_transform_core(args[0], args[1], stamp(args[2])))
        elif op == "lookup_full":
            value = plain(core.lookup_transform_full_core(args[0], stamp(args[1]), args[2], stamp(args[3]), args[4]))
        elif op == "can":
            value = list(core.can_transform_core(args[0], args[1], stamp(args[2])))
        elif op == "common":
            value = core.get_latest_common_time(args[0], args[1]).to_nsec()
        elif op == "string":
            value = core.all_frames_as_string()
        elif op == "yaml":
            value = core.all_frames_as_yaml()
        elif op == "dot":
            value = core._allFramesAsDot(*[rospy.Time.from_sec(a) for a in args])
        elif op == "clear":
            value = core.clear()
        results.append(["ok", value])
    except Exception as exc:
        results.append([type(exc).__name__, str(exc)])
json.dump(results, sys.stdout)
