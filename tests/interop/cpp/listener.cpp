// A roscpp listener for kame's interop tests: prints "I heard: [<data>]" for each std_msgs/String
// on /chatter, flushed at once so a test reading its stdout sees every line as it comes.
#include <cstdio>

#include "ros/ros.h"
#include "std_msgs/String.h"

void chatter(const std_msgs::String::ConstPtr& msg) {
  std::printf("I heard: [%s]\n", msg->data.c_str());
  std::fflush(stdout);
}

int main(int argc, char** argv) {
  ros::init(argc, argv, "cpp_listener");
  ros::NodeHandle n;
  ros::Subscriber sub = n.subscribe("chatter", 10, chatter);
  std::printf("ready\n");
  std::fflush(stdout);
  ros::spin();
  return 0;
}
