// listener_with_tracked_object: a subscription whose callback object is tracked; once the object is gone its
// callback is never called, and only the plain function's line is printed.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <boost/make_shared.hpp>

class Tracked
{
public:
  void onChatter(const std_msgs::String::ConstPtr& message)
  {
    ROS_INFO("This should never be printed: [%s]", message->data.c_str());
  }
};

void onChatter(const std_msgs::String::ConstPtr& message)
{
  ROS_INFO("Only this version should print: [%s]", message->data.c_str());
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener");
  ros::NodeHandle node;
  boost::shared_ptr<Tracked> tracked = boost::make_shared<Tracked>();
  ros::Subscriber tracked_subscription = node.subscribe("chatter", 1, &Tracked::onChatter, tracked);
  ros::Subscriber plain = node.subscribe("chatter", 1, onChatter);
  tracked.reset();  // the tracked subscription's callback is not called from now on
  ros::spin();
  return 0;
}
