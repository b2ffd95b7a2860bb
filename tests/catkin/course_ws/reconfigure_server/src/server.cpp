// A dynamic_reconfigure server: logs each new configuration.
#include <ros/ros.h>
#include <dynamic_reconfigure/server.h>
#include <reconfigure_server/SpeedConfig.h>

int main(int argc, char** argv) {
  ros::init(argc, argv, "speed_server");
  dynamic_reconfigure::Server<reconfigure_server::SpeedConfig> server;
  server.setCallback([](reconfigure_server::SpeedConfig& config, uint32_t) {
    ROS_INFO("Reconfigure request: speed=%.1f who=%s", config.speed, config.who.c_str());
  });
  ros::spin();
  return 0;
}
