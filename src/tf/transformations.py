"""tf.transformations: kame.tf.transformations under ROS's module name."""

from kame.tf.transformations import *  # noqa: F403
from kame.tf.transformations import _AXES2TUPLE, _EPS, _NEXT_AXIS, _TUPLE2AXES  # noqa: F401
