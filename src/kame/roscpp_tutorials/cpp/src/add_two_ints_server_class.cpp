// add_two_ints_server_class: add_two_ints_server with the service served by an object's method.
#include <ros/ros.h>
#include <roscpp_tutorials/TwoInts.h>

class Adder
{
public:
  explicit Adder(const ros::NodeHandle& node) : node_(node) {}

  void advertise()
  {
    service_ = node_.advertiseService("add_two_ints", &Adder::add, this);
  }

private:
  bool add(roscpp_tutorials::TwoInts::Request& request, roscpp_tutorials::TwoInts::Response& response)
  {
    response.sum = request.a + request.b;
    ROS_INFO("request: x=%ld, y=%ld", static_cast<long>(request.a), static_cast<long>(request.b));
    ROS_INFO("  sending back response: [%ld]", static_cast<long>(response.sum));
    return true;
  }

  ros::NodeHandle node_;
  ros::ServiceServer service_;
};

int main(int argc, char** argv)
{
  ros::init(argc, argv, "add_two_ints_server");
  ros::NodeHandle node;
  Adder adder(node);
  adder.advertise();
  ros::spin();
  return 0;
}
