// A roscpp talker for kame's interop tests: "hello N" on /chatter (std_msgs/String) at 10 Hz,
// each one also logged with ROS_INFO (so it reaches /rosout), until the node is shut down.
#include <cstdio>
#include <sstream>

#include "ros/ros.h"
#include "std_msgs/String.h"

int main(int argc, char** argv) {
  ros::init(argc, argv, "cpp_talker");
  ros::NodeHandle n;
  ros::Publisher pub = n.advertise<std_msgs::String>("chatter", 10);
  ros::Rate rate(10);
  std::printf("ready\n");
  std::fflush(stdout);
  for (int count = 0; ros::ok(); ++count) {
    std_msgs::String msg;
    std::stringstream ss;
    ss << "hello " << count;
    msg.data = ss.str();
    ROS_INFO("%s", msg.data.c_str());
    pub.publish(msg);
    ros::spinOnce();
    rate.sleep();
  }
  return 0;
}
