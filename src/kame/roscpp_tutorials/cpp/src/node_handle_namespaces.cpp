// node_handle_namespaces: how a NodeHandle's namespace resolves a name (a child of one, and the private one).
#include <ros/ros.h>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "node_handle_namespaces");
  ros::NodeHandle level1("level1");
  ROS_INFO_STREAM(level1.resolveName("a"));
  ros::NodeHandle level2(level1, "level2");
  ROS_INFO_STREAM(level2.resolveName("a"));
  ros::NodeHandle private_handle("~");
  ROS_INFO_STREAM(private_handle.resolveName("a"));
  return 0;
}
