// listener_with_userdata: three subscriptions to chatter, each callback bound to its own user string.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <string>
#include <vector>

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener_with_userdata");
  ros::NodeHandle node;
  std::vector<ros::Subscriber> subscriptions;
  for (const std::string user : {"User 1", "User 2", "User 3"})
  {
    boost::function<void(const std_msgs::String::ConstPtr&)> callback =
        [user](const std_msgs::String::ConstPtr& message) {
          ROS_INFO("I heard: [%s] with user string [%s]", message->data.c_str(), user.c_str());
        };
    subscriptions.push_back(node.subscribe<std_msgs::String>("chatter", 1000, callback));
  }
  ros::spin();
  return 0;
}
