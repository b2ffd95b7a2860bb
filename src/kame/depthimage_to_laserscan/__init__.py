"""depthimage_to_laserscan: a depth image's middle rows as a sensor_msgs/LaserScan, as the
TurtleBot's simulation makes /scan from its Kinect. `conversion` is the pure arithmetic
(DepthImageToLaserScan::convert_msg's), `node` the ROS node around it."""
