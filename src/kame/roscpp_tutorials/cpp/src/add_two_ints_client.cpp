// add_two_ints_client X Y: asks add_two_ints for X + Y and logs the sum.
#include <ros/ros.h>
#include <roscpp_tutorials/TwoInts.h>

#include <cstdlib>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "add_two_ints_client");
  if (argc != 3)
  {
    ROS_INFO("usage: add_two_ints_client X Y");
    return 1;
  }
  ros::NodeHandle node;
  ros::ServiceClient client = node.serviceClient<roscpp_tutorials::TwoInts>("add_two_ints");
  roscpp_tutorials::TwoInts call;
  call.request.a = std::atoi(argv[1]);
  call.request.b = std::atoi(argv[2]);
  if (!client.call(call))
  {
    ROS_ERROR("Failed to call service add_two_ints");
    return 1;
  }
  ROS_INFO("Sum: %ld", static_cast<long>(call.response.sum));
  return 0;
}
