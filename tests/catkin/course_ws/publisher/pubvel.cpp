// Drives turtlesim's turtle: a forward speed and a turn on turtle1/cmd_vel, twice a second.
#include <ros/ros.h>
#include <geometry_msgs/Twist.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "publish_velocity");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<geometry_msgs::Twist>("turtle1/cmd_vel", 1000);
  ros::Rate rate(2);
  while (ros::ok()) {
    geometry_msgs::Twist msg;
    msg.linear.x = 1.0;
    msg.angular.z = 0.5;
    pub.publish(msg);
    ROS_INFO_STREAM("Sending velocity command:" << " linear=" << msg.linear.x << " angular=" << msg.angular.z);
    rate.sleep();
  }
  return 0;
}
