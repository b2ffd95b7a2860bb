// anonymous_listener: the listener under a unique name (listener_<host>_<pid>_<n>), so several can run.
#include <ros/ros.h>
#include <std_msgs/String.h>

void onChatter(const std_msgs::String::ConstPtr& message)
{
  ROS_INFO("I heard: [%s]", message->data.c_str());
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener", ros::init_options::AnonymousName);
  ros::NodeHandle node;
  ros::Subscriber chatter = node.subscribe("chatter", 1000, onChatter);
  ros::spin();
  return 0;
}
