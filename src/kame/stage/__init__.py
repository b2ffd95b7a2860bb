"""A 2-D mobile-robot world standing in for Stage and Gazebo, and map_server's maps.

Pure modules (L1): `world` (robots, walls, laser, odometry), `mapfile` (map_server's formats),
`worldfile` (Stage's .world files).
The programs (L4): `node` (stageros), `map_server`, `map_saver`, `teleop` (turtlebot_teleop_key),
all on the ROS runtime through one glue module, `runtime`.
"""
