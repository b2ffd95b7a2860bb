// add_two_ints_server: answers add_two_ints (roscpp_tutorials/TwoInts) with the sum, logging each call.
#include <ros/ros.h>
#include <roscpp_tutorials/TwoInts.h>

bool add(roscpp_tutorials::TwoInts::Request& request, roscpp_tutorials::TwoInts::Response& response)
{
  response.sum = request.a + request.b;
  ROS_INFO("request: x=%ld, y=%ld", static_cast<long>(request.a), static_cast<long>(request.b));
  ROS_INFO("  sending back response: [%ld]", static_cast<long>(response.sum));
  return true;
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "add_two_ints_server");
  ros::NodeHandle node;
  ros::ServiceServer service = node.advertiseService("add_two_ints", add);
  ros::spin();
  return 0;
}
