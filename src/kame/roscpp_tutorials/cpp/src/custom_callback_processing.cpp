// custom_callback_processing: one chatter subscription served by a callback queue on a thread of
// its own, the other by the main thread, which serves its queue once a second.
#include <ros/ros.h>
#include <ros/callback_queue.h>
#include <std_msgs/String.h>

#include <thread>

static ros::CallbackQueue g_custom_queue;

void onMainQueue(const std_msgs::String::ConstPtr& message)
{
  ROS_INFO_STREAM("I heard: [ " << message->data << "] in thread [" << std::this_thread::get_id()
                  << "] (Main thread)");
}

void onCustomQueue(const std_msgs::String::ConstPtr& message)
{
  ROS_INFO_STREAM("I heard: [ " << message->data << "] in thread [" << std::this_thread::get_id() << "]");
}

void serveCustomQueue()
{
  ROS_INFO_STREAM("Callback thread id=" << std::this_thread::get_id());
  ros::NodeHandle node;
  while (node.ok())
    g_custom_queue.callAvailable(ros::WallDuration(0.01));
}

int main(int argc, char** argv)
{
  ros::init(argc, argv, "listener_with_custom_callback_processing");
  ros::NodeHandle node;
  ros::SubscribeOptions options = ros::SubscribeOptions::create<std_msgs::String>(
      "chatter", 1000, onCustomQueue, ros::VoidPtr(), &g_custom_queue);
  ros::Subscriber custom = node.subscribe(options);
  ros::Subscriber main_queue = node.subscribe("chatter", 1000, onMainQueue);
  std::thread worker(serveCustomQueue);
  ROS_INFO_STREAM("Main thread id=" << std::this_thread::get_id());
  ros::Rate once_a_second(1);
  while (node.ok())
  {
    ros::spinOnce();
    once_a_second.sleep();
  }
  worker.join();
  return 0;
}
