// listener_multiple: four callbacks on the one chatter topic (three methods of an object, one function).
#include <ros/ros.h>
#include <std_msgs/String.h>

class Listener
{
public:
  void first(const std_msgs::String::ConstPtr& message) { ROS_INFO("chatter1: [%s]", message->data.c_str()); }
  void second(const std_msgs::String::ConstPtr& message) { ROS_INFO("chatter2: [%s]", message->data.c_str()); }
  void third(const std_msgs::String::ConstPtr& message) { ROS_INFO("chatter3: [%s]", message->data.c_str()); }
};

void fourth(const std_msgs::String::ConstPtr& message)
{
  ROS_INFO("chatter4: [%s]", message->data.c_str());
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener");
  ros::NodeHandle node;
  Listener listener;
  ros::Subscriber one = node.subscribe("chatter", 10, &Listener::first, &listener);
  ros::Subscriber two = node.subscribe("chatter", 10, &Listener::second, &listener);
  ros::Subscriber three = node.subscribe("chatter", 10, &Listener::third, &listener);
  ros::Subscriber four = node.subscribe("chatter", 10, fourth);
  ros::spin();
  return 0;
}
