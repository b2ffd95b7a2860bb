"""gazebo_ros on kame: gzserver as the ROS node /gazebo over kame.gazebo's World, its plugins
under their Gazebo file names, and spawn_model.

- `command_line`: gzserver's options (pure).
- `spawn_model`: gazebo_ros's spawn_model program.
"""
