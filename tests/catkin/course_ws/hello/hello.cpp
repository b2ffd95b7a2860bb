// The course's first C++ node: starts, greets once, ends.
#include <ros/ros.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "hello_ros");
  ros::NodeHandle nh;
  ROS_INFO_STREAM("Hello, ROS!");
  return 0;
}
