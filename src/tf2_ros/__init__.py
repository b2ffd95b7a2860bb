"""tf2_ros, as ROS programs import it: Buffer, TransformListener, the broadcasters, the
exceptions and the conversion registries, on kame's tf2 (kame.tf, kame.tf_ros)."""

from kame.tf.errors import (
    ConnectivityException,
    ExtrapolationException,
    InvalidArgumentException,
    LookupException,
    TimeoutException,
    TransformException,
)

from .buffer import Buffer, BufferCore
from .buffer_client import BufferClient
from .buffer_interface import (
    BufferInterface,
    ConvertRegistration,
    NotImplementedException,
    Stamped,
    TransformRegistration,
    TypeException,
    convert,
)
from .static_transform_broadcaster import StaticTransformBroadcaster
from .transform_broadcaster import TransformBroadcaster
from .transform_listener import TransformListener

__all__ = [
    "Buffer", "BufferClient", "BufferCore", "BufferInterface", "ConnectivityException", "ConvertRegistration",
    "ExtrapolationException", "InvalidArgumentException", "LookupException", "NotImplementedException", "Stamped",
    "StaticTransformBroadcaster", "TimeoutException", "TransformBroadcaster", "TransformException",
    "TransformListener", "TransformRegistration", "TypeException", "convert",
]
