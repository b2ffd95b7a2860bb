"""tf_conversions: posemath's conversions (also importable from the package, as upstream's
`from .posemath import *` makes them) and `tf_conversions.transformations` (tf.transformations)."""

from .posemath import *  # noqa: F403 -- the package re-exports its module, as upstream's does
from .posemath import __all__ as __all__
