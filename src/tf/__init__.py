"""tf, the first transform API, as ROS programs import it: TransformListener,
TransformBroadcaster, transformations, and tf2's exceptions under tf's names."""

from tf2_ros import ConnectivityException, ExtrapolationException, LookupException
from tf2_ros import TransformException as Exception

from .broadcaster import TransformBroadcaster
from .listener import Transformer, TransformerROS, TransformListener

__all__ = ["ConnectivityException", "Exception", "ExtrapolationException", "LookupException", "TransformBroadcaster",
           "TransformListener", "Transformer", "TransformerROS"]
