// time_api_sleep: ros::Duration's sleep(), one second, half a second, then five tenths (no node).
#include <ros/time.h>

#include <cstdio>

int main(int, char**)
{
  ros::Time::init();
  std::printf("sleeping for one second\n");
  ros::Duration(1, 0).sleep();
  std::printf("sleeping for a half second\n");
  ros::Duration(0, 500000000).sleep();
  const ros::Duration tenth(0, 100000000);
  for (int i = 0; i < 5; ++i)
  {
    std::printf("sleeping for a tenth of a second\n");
    tenth.sleep();
  }
  return 0;
}
