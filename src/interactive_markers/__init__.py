"""interactive_markers, as ROS programs import it: InteractiveMarkerServer and MenuHandler
over kame's protocol model (kame.interactive_markers) and rospy."""
