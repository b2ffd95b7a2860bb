"""Runs under kame's interpreter and under Debian's /usr/bin/python3 alike (no node needed): tf's
TransformerROS on a small tree; prints one JSON list of results for the test to compare."""

import json
import math

import rospy
import tf
from geometry_msgs.msg import PointStamped, PoseStamped, QuaternionStamped, TransformStamped, Vector3Stamped


def transform(parent, child, secs, xyz, rpy):
    t = TransformStamped()
    t.header.frame_id, t.child_frame_id, t.header.stamp = parent, child, rospy.Time.from_sec(secs)
    t.transform.translation.x, t.transform.translation.y, t.transform.translation.z = xyz
    q = tf.transformations.quaternion_from_euler(*rpy)
    t.transform.rotation.x, t.transform.rotation.y, t.transform.rotation.z, t.transform.rotation.w = q
    return t


tr = tf.TransformerROS()
for secs, yaw in ((1.0, 0.0), (2.0, 0.5), (3.0, 1.0)):
    tr.setTransform(transform("world", "base", secs, (secs, 0.5 * secs, 0.0), (0.0, 0.0, yaw)), "/mover")
tr.setTransform(transform("base", "arm", 1.0, (0.2, 0.0, 0.3), (0.1, 0.2, 0.3)), "/arm")
tr.setTransform(transform("base", "arm", 3.0, (0.2, 0.0, 0.3), (0.1, 0.2, 0.3)), "/arm")
out = []
stamp = rospy.Time.from_sec(2.5)
out.append(tr.lookupTransform("world", "/arm", stamp))
out.append(tr.lookupTransform("arm", "world", rospy.Time(0)))
out.append([tr.canTransform("world", "arm", stamp), tr.canTransform("world", "arm", rospy.Time(9)),
            tr.frameExists("arm"), tr.frameExists("ghost"), sorted(tr.getFrameStrings())])
out.append(tr.getLatestCommonTime("world", "arm").to_sec())
out.append(sorted(tr.allFramesAsString().splitlines()))  # tf2 lists frames in no fixed order
p = PointStamped()
p.header.frame_id, p.header.stamp = "arm", stamp
p.point.x, p.point.y, p.point.z = 1.0, 2.0, 3.0
r = tr.transformPoint("world", p)
out.append([r.header.frame_id, r.point.x, r.point.y, r.point.z])
v = Vector3Stamped()
v.header.frame_id, v.header.stamp = "arm", stamp
v.vector.x = 1.0
r = tr.transformVector3("world", v)
out.append([r.vector.x, r.vector.y, r.vector.z])
q = QuaternionStamped()
q.header.frame_id, q.header.stamp = "arm", stamp
q.quaternion.w = 1.0
r = tr.transformQuaternion("world", q)
out.append(sorted([abs(r.quaternion.x), abs(r.quaternion.y), abs(r.quaternion.z), abs(r.quaternion.w)]))
pose = PoseStamped()
pose.header.frame_id, pose.header.stamp = "arm", stamp
pose.pose.position.x = 1.0
pose.pose.orientation.z, pose.pose.orientation.w = math.sin(0.2), math.cos(0.2)
r = tr.transformPose("world", pose)
out.append([r.pose.position.x, r.pose.position.y, r.pose.position.z])
out.append(tr.lookupTransformFull("arm", rospy.Time.from_sec(3.0), "arm", rospy.Time.from_sec(1.0), "world"))
out.append(tr.lookupTwist("base", "world", rospy.Time.from_sec(2.0), rospy.Duration(1.0)))
try:
    tr.lookupTransform("world", "ghost", rospy.Time(0))
except tf.LookupException as e:
    out.append(["LookupException", str(e)])
try:
    tr.waitForTransform("world", "arm", rospy.Time(0), rospy.Duration(0.1))
except tf.Exception as e:
    out.append(["Exception", str(e)])
print(json.dumps(out))
