"""tf2_ros.Buffer: kame's waiting buffer (kame.tf_ros.buffer) with rospy's time types and
logging, the tf2_py method names, transform() and the node's ~tf2_frames service."""

import rospy
from geometry_msgs.msg import TransformStamped
from kame.tf.errors import LookupException
from kame.tf_ros import buffer as _buffer
from tf2_msgs.srv import FrameGraph, FrameGraphResponse

from .buffer_interface import NO_WAIT, BufferInterface

_frames_service = []  # the process's one ~tf2_frames service, if any


class Buffer(_buffer.Buffer, BufferInterface):
    def __init__(self, cache_time=None, debug=True):
        _buffer.Buffer.__init__(self, cache_time, TransformStamped, rospy.Time, warn=rospy.logwarn,
                                error=rospy.logerr)
        BufferInterface.__init__(self)
        if debug and not _frames_service and rospy.core.is_initialized():
            _frames_service.append(rospy.Service("~tf2_frames", FrameGraph, self._get_frames))

    def _get_frames(self, request):
        return FrameGraphResponse(self.all_frames_as_yaml())

    def lookup_transform(self, target_frame, source_frame, time, timeout=NO_WAIT):
        return _buffer.Buffer.lookup_transform(self, target_frame, source_frame, time, timeout)

    def lookup_transform_full(self, target_frame, target_time, source_frame, source_time, fixed_frame,
                              timeout=NO_WAIT):
        return _buffer.Buffer.lookup_transform_full(self, target_frame, target_time, source_frame, source_time,
                                                    fixed_frame, timeout)

    def can_transform(self, target_frame, source_frame, time, timeout=NO_WAIT, return_debug_tuple=False):
        return _buffer.Buffer.can_transform(self, target_frame, source_frame, time, timeout, return_debug_tuple)

    def can_transform_full(self, target_frame, target_time, source_frame, source_time, fixed_frame,
                           timeout=NO_WAIT, return_debug_tuple=False):
        return _buffer.Buffer.can_transform_full(self, target_frame, target_time, source_frame, source_time,
                                                 fixed_frame, timeout, return_debug_tuple)

    # tf2_py's BufferCore names
    def lookup_transform_core(self, target_frame, source_frame, time):
        return _buffer.Buffer.lookup_transform(self, target_frame, source_frame, time)

    def lookup_transform_full_core(self, target_frame, target_time, source_frame, source_time, fixed_frame):
        return _buffer.Buffer.lookup_transform_full(self, target_frame, target_time, source_frame, source_time,
                                                    fixed_frame)

    def can_transform_core(self, target_frame, source_frame, time):
        return _buffer.Buffer.can_transform(self, target_frame, source_frame, time, None, True)

    def can_transform_full_core(self, target_frame, target_time, source_frame, source_time, fixed_frame):
        return _buffer.Buffer.can_transform_full(self, target_frame, target_time, source_frame, source_time,
                                                 fixed_frame, None, True)

    def _frameExists(self, frame_id):
        return self.frame_exists(frame_id)

    def _getParent(self, frame_id, time):
        parent = self.parent_of(frame_id, time)
        if parent is None:
            raise LookupException(f'"{frame_id}" has no parent')
        return parent

    def _allFramesAsDot(self, time=None):
        return self.all_frames_as_dot(time.to_sec() if time else 0.0)

    def _getFrameStrings(self):
        return self.frames()

    def _chain(self, target_frame, target_time, source_frame, source_time, fixed_frame):
        return self.chain(target_frame, source_frame, target_time)


class BufferCore(Buffer):
    """tf2_py's BufferCore, which tf2_ros re-exports (tf2_ros.BufferCore(cache_time)): the same
    buffer, without the ~tf2_frames service."""

    def __init__(self, cache_time=None):
        Buffer.__init__(self, cache_time, debug=False)
