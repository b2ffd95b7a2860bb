// listener_unreliable: the listener asking for an unreliable (UDP) transport; the publisher may offer TCP only.
#include <ros/ros.h>
#include <std_msgs/String.h>

void onChatter(const std_msgs::String::ConstPtr& message)
{
  ROS_INFO("I heard: [%s]", message->data.c_str());
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener_unreliable");
  ros::NodeHandle node;
  ros::Subscriber chatter = node.subscribe("chatter", 1000, onChatter, ros::TransportHints().unreliable());
  ros::spin();
  return 0;
}
