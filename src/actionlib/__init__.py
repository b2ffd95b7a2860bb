"""actionlib as ROS users import it, on kame: SimpleActionServer/SimpleActionClient and the
lower-level ActionServer/ActionClient with their goal handles, wire-compatible with ROS 1.

The rules (status transitions, cancel matching, CommState) are plain data in kame.action.
"""

from actionlib.action_client import (
    ActionClient,
    ClientGoalHandle,
    CommState,
    CommStateMachine,
    GoalManager,
    TerminalState,
    get_name_of_constant,
)
from actionlib.action_server import ActionServer, nop_cb
from actionlib.exceptions import ActionException
from actionlib.goal_id_generator import GoalIDGenerator
from actionlib.server_goal_handle import ServerGoalHandle
from actionlib.simple_action_client import SimpleActionClient, SimpleGoalState
from actionlib.simple_action_server import SimpleActionServer
from actionlib.status_tracker import StatusTracker
from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray

__all__ = [
    "ActionClient", "ActionException", "ActionServer", "ClientGoalHandle", "CommState", "CommStateMachine",
    "GoalID", "GoalIDGenerator", "GoalManager", "GoalStatus", "GoalStatusArray", "ServerGoalHandle",
    "SimpleActionClient", "SimpleActionServer", "SimpleGoalState", "StatusTracker", "TerminalState",
    "get_name_of_constant", "nop_cb",
]
