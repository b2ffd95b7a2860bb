"""gzclient: Gazebo's window as a separate process from gzserver. It learns what to draw over ROS
(the latched /gazebo/kame/scene and /gazebo/kame/world_stats, then /gazebo/link_states and
/gazebo/model_states) and works the world through the /gazebo services."""
