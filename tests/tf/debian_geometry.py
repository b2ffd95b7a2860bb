"""Run under Debian's /usr/bin/python3: tf2_geometry_msgs's do_transform_* on a JSON batch.

stdin: [[kind, transform [t, q], value], ...]; stdout: the results as nested lists."""

import json
import sys

import tf2_geometry_msgs
from geometry_msgs.msg import PointStamped, PoseStamped, TransformStamped, Vector3Stamped, WrenchStamped


def make_transform(t, q):
    msg = TransformStamped()
    msg.header.frame_id = "parent"
    (msg.transform.translation.x, msg.transform.translation.y, msg.transform.translation.z) = t
    (msg.transform.rotation.x, msg.transform.rotation.y, msg.transform.rotation.z, msg.transform.rotation.w) = q
    return msg


def xyz(v):
    return [v.x, v.y, v.z]


out = []
for kind, (t, q), value in json.load(sys.stdin):
    tf = make_transform(t, q)
    if kind == "point":
        p = PointStamped()
        p.point.x, p.point.y, p.point.z = value
        out.append(xyz(tf2_geometry_msgs.do_transform_point(p, tf).point))
    elif kind == "vector":
        v = Vector3Stamped()
        v.vector.x, v.vector.y, v.vector.z = value
        out.append(xyz(tf2_geometry_msgs.do_transform_vector3(v, tf).vector))
    elif kind == "pose":
        p = PoseStamped()
        p.pose.position.x, p.pose.position.y, p.pose.position.z = value[0]
        o = p.pose.orientation
        o.x, o.y, o.z, o.w = value[1]
        r = tf2_geometry_msgs.do_transform_pose(p, tf).pose
        out.append([xyz(r.position), [r.orientation.x, r.orientation.y, r.orientation.z, r.orientation.w]])
    elif kind == "wrench":
        w = WrenchStamped()
        w.wrench.force.x, w.wrench.force.y, w.wrench.force.z = value[0]
        w.wrench.torque.x, w.wrench.torque.y, w.wrench.torque.z = value[1]
        r = tf2_geometry_msgs.do_transform_wrench(w, tf).wrench
        out.append([xyz(r.force), xyz(r.torque)])
json.dump(out, sys.stdout)
