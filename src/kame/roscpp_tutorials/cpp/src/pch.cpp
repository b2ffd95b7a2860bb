// The translation unit that compiles the programs' shared precompiled header (see CMakeLists.txt).
#include <ros/ros.h>
