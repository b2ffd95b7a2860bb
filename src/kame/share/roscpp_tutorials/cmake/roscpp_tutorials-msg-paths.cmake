# roscpp_tutorials' message search paths, as catkin installs them: the package has services
# only (srv/TwoInts.srv), which depend on std_msgs.
set(roscpp_tutorials_MSG_INCLUDE_DIRS "")
set(roscpp_tutorials_MSG_DEPENDENCIES std_msgs)
