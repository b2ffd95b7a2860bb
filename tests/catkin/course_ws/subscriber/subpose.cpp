// Prints where turtlesim's turtle is, each time turtle1/pose says so.
#include <ros/ros.h>
#include <turtlesim/Pose.h>
#include <iomanip>

void onPose(const turtlesim::Pose& pose) {
  ROS_INFO_STREAM(std::setprecision(2) << std::fixed << "position=(" << pose.x << "," << pose.y << ")"
                  << " direction=" << pose.theta);
}

int main(int argc, char** argv) {
  ros::init(argc, argv, "subscribe_to_pose");
  ros::NodeHandle nh;
  ros::Subscriber sub = nh.subscribe("turtle1/pose", 1000, &onPose);
  ros::spin();
  return 0;
}
