// Builds the action goals an actionlib client sends, from headers generated for kame's .action files.
#include <iostream>
#include <ros/ros.h>
#include <actionlib_tutorials/FibonacciAction.h>
#include <nav_msgs/GetMapAction.h>

int main(int argc, char** argv) {
  actionlib_tutorials::FibonacciActionGoal fibonacci;
  fibonacci.goal.order = 20;
  nav_msgs::GetMapActionGoal map;
  std::cout << ros::message_traits::datatype(fibonacci) << " " << fibonacci.goal.order << "\n"
            << ros::message_traits::md5sum<actionlib_tutorials::FibonacciAction>() << "\n"
            << ros::message_traits::datatype(map) << "\n"
            << ros::message_traits::md5sum<nav_msgs::GetMapAction>() << std::endl;
  return 0;
}
