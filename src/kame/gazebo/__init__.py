"""Gazebo's simulator core on MuJoCo: SDF and URDF to a running 3-D world, its sensors, no ROS.

A pure layer (no ROS, no clock, no threads, no sockets; MuJoCo and numpy compute): the gazebo_ros
node steps a `World` and publishes what it reads. `World` (kame.gazebo.world) is the API;
`Resources` says where model://, package:// and file:// lead; every refusal is a `GazeboError`.
Shipped models (ground_plane, sun, box, cylinder, sphere) are in kame/gazebo/models, searched
after GAZEBO_MODEL_PATH; shipped worlds (worlds/empty.world) in kame/gazebo/worlds, after
GAZEBO_RESOURCE_PATH.
"""

from kame.gazebo.description import Physics
from kame.gazebo.errors import GazeboError
from kame.gazebo.poses import Pose
from kame.gazebo.resources import SHIPPED_MODELS, Resources
from kame.gazebo.states import JointState, SensorInfo, State, VisualShape
from kame.gazebo.world import World

__all__ = ["SHIPPED_MODELS", "GazeboError", "JointState", "Physics", "Pose", "Resources", "SensorInfo", "State",
           "VisualShape", "World"]
