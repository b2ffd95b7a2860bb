// talker: says "hello world N" on chatter ten times a second, logging each line it sends.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <sstream>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "talker");
  ros::NodeHandle node;
  ros::Publisher chatter = node.advertise<std_msgs::String>("chatter", 1000);
  ros::Rate ten_hz(10);
  for (int count = 0; ros::ok(); ++count)
  {
    std::ostringstream text;
    text << "hello world " << count;
    std_msgs::String message;
    message.data = text.str();
    ROS_INFO("%s", message.data.c_str());
    chatter.publish(message);
    ros::spinOnce();
    ten_hz.sleep();
  }
  return 0;
}
