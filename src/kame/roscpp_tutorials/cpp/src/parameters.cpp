// parameters: the NodeHandle's parameter calls in turn (get, param with defaults, set, delete, has, search).
#include <ros/ros.h>

#include <string>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "parameters");
  ros::NodeHandle node;

  std::string text;
  if (node.getParam("my_param", text))
    ROS_INFO("Got param: %s", text.c_str());
  else
    ROS_ERROR("Failed to get param 'my_param'");

  int number;
  node.param("my_num", number, 42);
  std::string with_default;
  node.param<std::string>("my_param", with_default, "default_value");

  node.setParam("my_param", "hello there");
  node.deleteParam("my_param");
  if (!node.hasParam("my_param"))
    ROS_INFO("No param named 'my_param'");

  std::string found;
  if (node.searchParam("b", found))
  {
    int value = 0;
    node.getParam(found, value);
  }
  else
  {
    ROS_INFO("No param 'b' found in an upward search");
  }
  return 0;
}
