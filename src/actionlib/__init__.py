"""actionlib as ROS users import it, on kame: SimpleActionServer/SimpleActionClient and the
lower-level ActionServer/ActionClient with their goal handles, wire-compatible with ROS 1.

The rules (status transitions, cancel matching, CommState) are plain data in kame.action.
"""

from actionlib_msgs.msg import GoalID, GoalStatus, GoalStatusArray
from kame.client.action.action_client import (
    ActionClient,
    ClientGoalHandle,
    CommState,
    CommStateMachine,
    GoalManager,
    TerminalState,
    get_name_of_constant,
)
from kame.client.action.action_server import ActionServer, nop_cb
from kame.client.action.exceptions import ActionException
from kame.client.action.goal_id_generator import GoalIDGenerator
from kame.client.action.server_goal_handle import ServerGoalHandle
from kame.client.action.simple_action_client import SimpleActionClient, SimpleGoalState
from kame.client.action.simple_action_server import SimpleActionServer
from kame.client.action.status_tracker import StatusTracker

__all__ = [
    "ActionClient", "ActionException", "ActionServer", "ClientGoalHandle", "CommState", "CommStateMachine",
    "GoalID", "GoalIDGenerator", "GoalManager", "GoalStatus", "GoalStatusArray", "ServerGoalHandle",
    "SimpleActionClient", "SimpleActionServer", "SimpleGoalState", "StatusTracker", "TerminalState",
    "get_name_of_constant", "nop_cb",
]
