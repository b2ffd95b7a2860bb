// timers: two timer callbacks, one every tenth of a second and one every second.
#include <ros/ros.h>

void fast(const ros::TimerEvent&)
{
  ROS_INFO("Callback 1 triggered");
}

void slow(const ros::TimerEvent&)
{
  ROS_INFO("Callback 2 triggered");
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "talker");  // the tutorial's own choice of name
  ros::NodeHandle node;
  ros::Timer tenth = node.createTimer(ros::Duration(0.1), fast);
  ros::Timer second = node.createTimer(ros::Duration(1.0), slow);
  ros::spin();
  return 0;
}
