"""tf.TransformListener and friends: the first tf API (lists for translations and quaternions,
camelCase names, frames with or without a leading '/') over a tf2_ros Buffer. A node's first
TransformListener serves ~tf_frames (tf/FrameGraph: allFramesAsDot), which
`view_frames --node` asks."""

import numpy
import yaml

import geometry_msgs.msg
import rospy
import sensor_msgs.msg
import tf2_ros

from . import transformations

_frames_service = []  # the process's one ~tf_frames service, if any


def xyz_to_mat44(pos):
    return transformations.translation_matrix((pos.x, pos.y, pos.z))


def xyzw_to_mat44(ori):
    return transformations.quaternion_matrix((ori.x, ori.y, ori.z, ori.w))


def strip_leading_slash(s):
    return s[1:] if s.startswith("/") else s


def _lists(msg):
    t, r = msg.transform.translation, msg.transform.rotation
    return [t.x, t.y, t.z], [r.x, r.y, r.z, r.w]


class Transformer:
    def __init__(self, interpolate=True, cache_time=None):
        self._buffer = tf2_ros.Buffer(cache_time, debug=False)
        self._using_dedicated_thread = False

    def allFramesAsDot(self, current_time=None):
        return self._buffer._allFramesAsDot(current_time) if current_time else self._buffer._allFramesAsDot()

    def allFramesAsString(self):
        return self._buffer.all_frames_as_string()

    def setTransform(self, transform, authority="default_authority"):
        self._buffer.set_transform(transform, authority)

    def canTransform(self, target_frame, source_frame, time):
        return self._buffer.can_transform(strip_leading_slash(target_frame), strip_leading_slash(source_frame), time)

    def canTransformFull(self, target_frame, target_time, source_frame, source_time, fixed_frame):
        return self._buffer.can_transform_full(strip_leading_slash(target_frame), target_time,
                                               strip_leading_slash(source_frame), source_time,
                                               strip_leading_slash(fixed_frame))

    def _need_thread(self):
        if not self._using_dedicated_thread:
            raise tf2_ros.TransformException(
                "cannot wait for transform without a dedicated thread that listens to incoming TF messages")

    def waitForTransform(self, target_frame, source_frame, time, timeout, polling_sleep_duration=None):
        """Block until the transform is possible (woken as transforms arrive) or `timeout` passes."""
        self._need_thread()
        ok, error = self._buffer.can_transform(strip_leading_slash(target_frame), strip_leading_slash(source_frame),
                                               time, timeout, return_debug_tuple=True)
        if not ok:
            raise tf2_ros.TransformException(error or f'no such transformation: "{source_frame}" -> "{target_frame}"')

    def waitForTransformFull(self, target_frame, target_time, source_frame, source_time, fixed_frame, timeout,
                             polling_sleep_duration=None):
        self._need_thread()
        ok, error = self._buffer.can_transform_full(strip_leading_slash(target_frame), target_time,
                                                    strip_leading_slash(source_frame), source_time,
                                                    strip_leading_slash(fixed_frame), timeout, return_debug_tuple=True)
        if not ok:
            raise tf2_ros.TransformException(error or f'no such transformation: "{source_frame}" -> "{target_frame}"')

    def chain(self, target_frame, target_time, source_frame, source_time, fixed_frame):
        return self._buffer._chain(target_frame, target_time, source_frame, source_time, fixed_frame)

    def clear(self):
        self._buffer.clear()

    def frameExists(self, frame_id):
        return frame_id in self.getFrameStrings()

    def getFrameStrings(self):
        data = yaml.safe_load(self._buffer.all_frames_as_yaml()) or {}
        return list(data)

    def getLatestCommonTime(self, source_frame, dest_frame):
        return self._buffer.get_latest_common_time(strip_leading_slash(source_frame), strip_leading_slash(dest_frame))

    def lookupTransform(self, target_frame, source_frame, time):
        """([x, y, z], [x, y, z, w]): the pose of source_frame in target_frame at `time`."""
        return _lists(self._buffer.lookup_transform(strip_leading_slash(target_frame),
                                                    strip_leading_slash(source_frame), time))

    def lookupTransformFull(self, target_frame, target_time, source_frame, source_time, fixed_frame):
        return _lists(self._buffer.lookup_transform_full(strip_leading_slash(target_frame), target_time,
                                                         strip_leading_slash(source_frame), source_time,
                                                         strip_leading_slash(fixed_frame)))

    def lookupTwist(self, tracking_frame, observation_frame, time, averaging_interval):
        return self.lookupTwistFull(tracking_frame, observation_frame, observation_frame, (0, 0, 0), tracking_frame,
                                    time, averaging_interval)

    def lookupTwistFull(self, tracking_frame, observation_frame, reference_frame, ref_point, reference_point_frame,
                        time, averaging_interval):
        """Linear and angular velocity of tracking_frame seen from observation_frame, averaged
        over `averaging_interval` (tf's algorithm)."""
        latest_time = self.getLatestCommonTime(observation_frame, tracking_frame)
        target_time = time or latest_time
        end_time = min(target_time + rospy.Duration(0.5 * averaging_interval.to_sec()), latest_time)
        start_time = max(rospy.Time(0.0001) + averaging_interval, end_time) - averaging_interval
        delta_t = (end_time - start_time).to_sec()
        start_tr, start_rt = self.lookupTransform(observation_frame, tracking_frame, start_time)
        end_tr, end_rt = self.lookupTransform(observation_frame, tracking_frame, end_time)
        d_rot = numpy.dot(numpy.linalg.inv(transformations.quaternion_matrix(start_rt)),
                          transformations.quaternion_matrix(end_rt))
        ang, o, _ = transformations.rotation_from_matrix(d_rot)
        vel0 = tuple((end_tr[i] - start_tr[i]) / delta_t for i in range(3))
        rot0 = tuple(o[i] * ang / delta_t for i in range(3))
        inverse_tr, inverse_rt = self.lookupTransform(reference_frame, tracking_frame, target_time)
        inverse_rot = transformations.quaternion_matrix(inverse_rt)[:3, :3]
        rot = numpy.dot(inverse_rot, rot0)
        vel = numpy.dot(inverse_rot, vel0) + numpy.cross(inverse_tr, rot)
        rp_orig = numpy.array((inverse_tr[0], inverse_tr[1], inverse_tr[2], 1))
        rp_tr, rp_rt = self.lookupTransform(reference_frame, reference_point_frame, target_time)
        to_reference = numpy.dot(transformations.translation_matrix(rp_tr), transformations.quaternion_matrix(rp_rt))
        rp_desired = numpy.dot(to_reference, (rp_orig[0], rp_orig[1], rp_orig[2], 1))
        delta = rp_desired - rp_orig
        vel += numpy.dot(rot, delta[:3])
        return (vel[0], vel[1], vel[2]), (rot[0], rot[1], rot[2])

    def setUsingDedicatedThread(self, value):
        self._using_dedicated_thread = value

    def getTFPrefix(self):
        return ""


class TransformerROS(Transformer):
    """Transformer plus transforms of geometry_msgs stamped types, as 4x4 numpy matrices."""

    def asMatrix(self, target_frame, hdr):
        translation, rotation = self.lookupTransform(target_frame, hdr.frame_id, hdr.stamp)
        return self.fromTranslationRotation(translation, rotation)

    def fromTranslationRotation(self, translation, rotation):
        return numpy.dot(transformations.translation_matrix(translation), transformations.quaternion_matrix(rotation))

    def transformPoint(self, target_frame, ps):
        mat44 = self.asMatrix(target_frame, ps.header)
        xyz = tuple(numpy.dot(mat44, numpy.array([ps.point.x, ps.point.y, ps.point.z, 1.0])))[:3]
        r = geometry_msgs.msg.PointStamped()
        r.header.stamp = ps.header.stamp
        r.header.frame_id = target_frame
        r.point = geometry_msgs.msg.Point(*xyz)
        return r

    def transformVector3(self, target_frame, v3s):
        mat44 = self.asMatrix(target_frame, v3s.header)
        mat44[0:3, 3] = 0.0
        xyz = tuple(numpy.dot(mat44, numpy.array([v3s.vector.x, v3s.vector.y, v3s.vector.z, 1.0])))[:3]
        r = geometry_msgs.msg.Vector3Stamped()
        r.header.stamp = v3s.header.stamp
        r.header.frame_id = target_frame
        r.vector = geometry_msgs.msg.Vector3(*xyz)
        return r

    def transformQuaternion(self, target_frame, ps):
        mat44 = self.asMatrix(target_frame, ps.header)
        quat = tuple(transformations.quaternion_from_matrix(numpy.dot(mat44, xyzw_to_mat44(ps.quaternion))))
        r = geometry_msgs.msg.QuaternionStamped()
        r.header.stamp = ps.header.stamp
        r.header.frame_id = target_frame
        r.quaternion = geometry_msgs.msg.Quaternion(*quat)
        return r

    def transformPose(self, target_frame, ps):
        mat44 = self.asMatrix(target_frame, ps.header)
        pose44 = numpy.dot(xyz_to_mat44(ps.pose.position), xyzw_to_mat44(ps.pose.orientation))
        txpose = numpy.dot(mat44, pose44)
        xyz = tuple(transformations.translation_from_matrix(txpose))[:3]
        quat = tuple(transformations.quaternion_from_matrix(txpose))
        r = geometry_msgs.msg.PoseStamped()
        r.header.stamp = ps.header.stamp
        r.header.frame_id = target_frame
        r.pose = geometry_msgs.msg.Pose(geometry_msgs.msg.Point(*xyz), geometry_msgs.msg.Quaternion(*quat))
        return r

    def transformPointCloud(self, target_frame, point_cloud):
        r = sensor_msgs.msg.PointCloud()
        r.header.stamp = point_cloud.header.stamp
        r.header.frame_id = target_frame
        r.channels = point_cloud.channels
        mat44 = self.asMatrix(target_frame, point_cloud.header)

        def xf(p):
            return geometry_msgs.msg.Point(*tuple(numpy.dot(mat44, numpy.array([p.x, p.y, p.z, 1.0])))[:3])
        r.points = [xf(p) for p in point_cloud.points]
        return r


class TransformListener(TransformerROS):
    """A TransformerROS fed by /tf and /tf_static."""

    def __init__(self, *args, **kwargs):
        TransformerROS.__init__(self, *args, **kwargs)
        self._listener = tf2_ros.TransformListener(self._buffer)
        self.setUsingDedicatedThread(True)
        if not _frames_service and rospy.core.is_initialized():
            from tf.srv import FrameGraph
            _frames_service.append(rospy.Service("~tf_frames", FrameGraph, self._frame_graph))

    def _frame_graph(self, request):
        from tf.srv import FrameGraphResponse
        return FrameGraphResponse(self.allFramesAsDot(rospy.Time.now()))
