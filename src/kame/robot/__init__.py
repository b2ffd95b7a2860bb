"""robot_state_publisher and joint_state_publisher: a URDF robot's joints turned into tf frames."""
