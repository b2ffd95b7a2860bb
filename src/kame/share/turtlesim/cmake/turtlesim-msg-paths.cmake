# turtlesim's message search paths, as catkin installs them: msg/Color.msg and msg/Pose.msg,
# generated with geometry_msgs, std_msgs and std_srvs
_prepend_path("${turtlesim_DIR}/.." "msg" turtlesim_MSG_INCLUDE_DIRS UNIQUE)
set(turtlesim_MSG_DEPENDENCIES geometry_msgs;std_msgs;std_srvs)
