"""kame.client: a program's one node, as ROS 1 client programs have it: what rospy is made of.

init_node, spin and parameters (process), shutdown and names (core), typed Publisher and
Subscriber (topics), Service and ServiceProxy (services), ROS time (clock), Rate and Timer
(timer), logging to the console, the node's log file and /rosout (log), and the exceptions
(errors). This is the one place in kame with process-wide state: kame's own programs
(turtlesim, the ros* tools that run a node) use it directly, and `rospy` re-exports it under
rospy's names. kame.node underneath stays explicit objects.
"""
