// Publishes the package's own message, cpp_msgs_demo/Reading, on readings at 5 Hz.
#include <ros/ros.h>
#include <cpp_msgs_demo/Reading.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "reading_pub");
  ros::NodeHandle nh;
  ros::Publisher pub = nh.advertise<cpp_msgs_demo::Reading>("readings", 10);
  ros::Rate rate(5);
  for (int n = 1; ros::ok(); ++n) {
    cpp_msgs_demo::Reading reading;
    reading.header.stamp = ros::Time::now();
    reading.sensor = "thermo";
    reading.value = 20.5 + n;
    reading.samples = {n, 2 * n, 3 * n};
    pub.publish(reading);
    rate.sleep();
  }
  return 0;
}
