"""tf2_ros's runtime on a node: a thread-safe Buffer whose waits wake when transforms arrive,
the /tf and /tf_static listener and broadcasters. The tf2_ros, tf and tf2_geometry_msgs
packages users import are facades over this and kame.tf."""
