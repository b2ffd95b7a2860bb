"""tf2_ros.buffer_interface: transform() of stamped types through registered functions, and
the conversions between types (tf2_geometry_msgs registers the geometry_msgs ones)."""

from copy import deepcopy

import rospy
from std_msgs.msg import Header

NO_WAIT = rospy.Duration(0.0)


class TypeException(Exception):
    """Raised when an unexpected type is received while registering a transform."""


class NotImplementedException(Exception):
    """Raised when trying to use a method not implemented by a BufferInterface subclass."""


class TransformRegistration:
    __type_map = {}

    def print_me(self):
        print(TransformRegistration.__type_map)

    def add(self, key, callback):
        TransformRegistration.__type_map[key] = callback

    def get(self, key):
        if key not in TransformRegistration.__type_map:
            raise TypeException(f"Type {key!s} if not loaded or supported")
        return TransformRegistration.__type_map[key]


class ConvertRegistration:
    __to_msg_map = {}
    __from_msg_map = {}
    __convert_map = {}

    def add_from_msg(self, key, callback):
        ConvertRegistration.__from_msg_map[key] = callback

    def add_to_msg(self, key, callback):
        ConvertRegistration.__to_msg_map[key] = callback

    def add_convert(self, key, callback):
        ConvertRegistration.__convert_map[key] = callback

    def get_from_msg(self, key):
        if key not in ConvertRegistration.__from_msg_map:
            raise TypeException(f"Type {key!s} if not loaded or supported")
        return ConvertRegistration.__from_msg_map[key]

    def get_to_msg(self, key):
        if key not in ConvertRegistration.__to_msg_map:
            raise TypeException(f"Type {key!s} if not loaded or supported")
        return ConvertRegistration.__to_msg_map[key]

    def get_convert(self, key):
        if key not in ConvertRegistration.__convert_map:
            raise TypeException(f"Type {key!s} if not loaded or supported")
        return ConvertRegistration.__convert_map[key]


def convert(a, b_type):
    registry = ConvertRegistration()
    try:
        return registry.get_convert((type(a), b_type))(a)
    except TypeException:
        if type(a) == b_type:  # noqa: E721 -- exactly this type, as tf2_ros compares
            return deepcopy(a)
        return registry.get_from_msg(b_type)(registry.get_to_msg(type(a))(a))


def Stamped(obj, stamp, frame_id):
    obj.header = Header(frame_id=frame_id, stamp=stamp)
    return obj


class BufferInterface:
    """transform()/transform_full() over lookup_transform()/lookup_transform_full()."""

    def __init__(self):
        self.registration = TransformRegistration()

    def transform(self, object_stamped, target_frame, timeout=NO_WAIT, new_type=None):
        do_transform = self.registration.get(type(object_stamped))
        result = do_transform(object_stamped, self.lookup_transform(
            target_frame, object_stamped.header.frame_id, object_stamped.header.stamp, timeout))
        return convert(result, new_type) if new_type else result

    def transform_full(self, object_stamped, target_frame, target_time, fixed_frame, timeout=NO_WAIT,
                       new_type=None):
        do_transform = self.registration.get(type(object_stamped))
        result = do_transform(object_stamped, self.lookup_transform_full(
            target_frame, target_time, object_stamped.header.frame_id, object_stamped.header.stamp,
            fixed_frame, timeout))
        return convert(result, new_type) if new_type else result

    def lookup_transform(self, target_frame, source_frame, time, timeout=NO_WAIT):
        raise NotImplementedException()

    def lookup_transform_full(self, target_frame, target_time, source_frame, source_time, fixed_frame,
                              timeout=NO_WAIT):
        raise NotImplementedException()

    def can_transform(self, target_frame, source_frame, time, timeout=NO_WAIT):
        raise NotImplementedException()

    def can_transform_full(self, target_frame, target_time, source_frame, source_time, fixed_frame,
                           timeout=NO_WAIT):
        raise NotImplementedException()
