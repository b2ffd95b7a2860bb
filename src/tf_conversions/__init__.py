"""tf_conversions, the parts courses use: `tf_conversions.transformations` (tf.transformations).
posemath's PyKDL frames are not provided."""

from kame.tf import transformations

__all__ = ["transformations"]
