"""turtle_tf's demo programs as kame programs (ROS ships them in C++): turtle_tf_broadcaster
turns a turtle's pose into its tf frame, turtle_tf_listener spawns turtle2 and steers it
toward turtle1 through tf. The turtle_tf2 and Python turtle_tf nodes are the tutorials' rospy
scripts, shipped under kame/share."""
