// listener_class: the listener with a class method as its callback.
#include <ros/ros.h>
#include <std_msgs/String.h>

class Listener
{
public:
  void onChatter(const std_msgs::String::ConstPtr& message)
  {
    ROS_INFO("I heard: [%s]", message->data.c_str());
  }
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener_class");
  ros::NodeHandle node;
  Listener listener;
  ros::Subscriber chatter = node.subscribe("chatter", 1000, &Listener::onChatter, &listener);
  ros::spin();
  return 0;
}
