// listener_async_spin: listener_multiple's four callbacks served by four threads of an AsyncSpinner while
// the main thread reports itself five times a second.
#include <ros/ros.h>
#include <std_msgs/String.h>

#include <thread>

static const ros::Duration g_work(0.01);

void report(int which, const std_msgs::String::ConstPtr& message)
{
  ROS_INFO_STREAM("chatter" << which << ": [" << message->data << "] [thread=" << std::this_thread::get_id() << "]");
  g_work.sleep();
}

class Listener
{
public:
  void first(const std_msgs::String::ConstPtr& message) { report(1, message); }
  void second(const std_msgs::String::ConstPtr& message) { report(2, message); }
  void third(const std_msgs::String::ConstPtr& message) { report(3, message); }
};

void fourth(const std_msgs::String::ConstPtr& message)
{
  report(4, message);
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener");
  ros::NodeHandle node;
  Listener listener;
  ros::Subscriber one = node.subscribe("chatter", 10, &Listener::first, &listener);
  ros::Subscriber two = node.subscribe("chatter", 10, &Listener::second, &listener);
  ros::Subscriber three = node.subscribe("chatter", 10, &Listener::third, &listener);
  ros::Subscriber four = node.subscribe("chatter", 10, fourth);
  ros::AsyncSpinner spinner(4);
  spinner.start();
  ros::Rate five_hz(5);
  while (ros::ok())
  {
    ROS_INFO_STREAM("Main thread [" << std::this_thread::get_id() << "].");
    five_hz.sleep();
  }
  return 0;
}
