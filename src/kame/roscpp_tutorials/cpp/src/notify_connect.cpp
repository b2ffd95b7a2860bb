// notify_connect: greets each new chatter subscriber (it alone gets the greeting) and notes each that leaves.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <sstream>

static unsigned int g_connections = 0;

void onConnect(const ros::SingleSubscriberPublisher& subscriber)
{
  std::ostringstream text;
  text << "chatter connect #" << g_connections++;
  ROS_INFO("%s", text.str().c_str());
  std_msgs::String greeting;
  greeting.data = text.str();
  subscriber.publish(greeting);
}

void onDisconnect(const ros::SingleSubscriberPublisher&)
{
  ROS_INFO("chatter disconnect");
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "notify_connect");
  ros::NodeHandle node;
  ros::Publisher chatter = node.advertise<std_msgs::String>("chatter", 1000, onConnect, onDisconnect);
  ros::spin();
  return 0;
}
