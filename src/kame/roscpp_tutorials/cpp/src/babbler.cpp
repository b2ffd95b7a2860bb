// babbler: the talker's lines, on babble instead of chatter.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <sstream>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "babbler");
  ros::NodeHandle node;
  ros::Publisher babble = node.advertise<std_msgs::String>("babble", 1000);
  ros::Rate ten_hz(10);
  for (int count = 0; node.ok(); ++count)
  {
    std::ostringstream text;
    text << "hello world " << count;
    ROS_INFO("%s", text.str().c_str());
    std_msgs::String message;
    message.data = text.str();
    babble.publish(message);
    ros::spinOnce();
    ten_hz.sleep();
  }
  return 0;
}
