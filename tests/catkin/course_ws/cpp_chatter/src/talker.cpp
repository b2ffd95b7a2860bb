// Says "hello world N" on chatter at ~rate Hz (a private parameter, 10 by default).
#include <ros/ros.h>
#include <std_msgs/String.h>
#include <sstream>

int main(int argc, char** argv) {
  ros::init(argc, argv, "talker");
  ros::NodeHandle nh;
  ros::NodeHandle private_nh("~");
  double hz = private_nh.param("rate", 10.0);
  ros::Publisher chatter = nh.advertise<std_msgs::String>("chatter", 1000);
  ros::Rate rate(hz);
  for (int count = 0; ros::ok(); ++count) {
    std_msgs::String msg;
    std::stringstream text;
    text << "hello world " << count;
    msg.data = text.str();
    ROS_INFO("%s", msg.data.c_str());
    chatter.publish(msg);
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
