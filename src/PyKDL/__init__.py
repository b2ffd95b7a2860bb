"""PyKDL, the part tf_conversions.posemath and course code use: Vector, Rotation, Frame, dot and
Equal (kame.tf.kdl, KDL's formulas in pure Python). Twist, Wrench, the chains and solvers are
not here.

Why a top-level PyKDL: courses write `import PyKDL` beside `tf_conversions.posemath`, and the
frames posemath returns must be the ones that program builds. kame is pip-installed into its
own environment, where no real PyKDL exists: Debian's and ROS's live in the system
interpreter's dist-packages, which kame's environment does not see. Where ROS's setup puts its
Python path in PYTHONPATH, that path comes before site-packages, so a real PyKDL there is the
one imported, this one stays hidden, and posemath (which imports `PyKDL` by name) returns the
real one's frames. This one would win over a system PyKDL only where kame is installed into
the system interpreter itself (--user, or a venv with --system-site-packages): there, the real
PyKDL is hidden, which is why kame is installed in an environment of its own.
"""

from kame.tf.kdl import Equal, Frame, Rotation, Vector, dot

__all__ = ["Equal", "Frame", "Rotation", "Vector", "dot"]
