#!/usr/bin/env bash
# Installs real ROS 1 (Debian's ros_comm 1.15.15) as a test peer for the interop tests, and the
# shells and terminal multiplexer some end-to-end tests drive, iproute2 and
# sshd for the tests on several hosts, and Debian's rviz (the reference viewer of kame's worlds).
# It runs under the system interpreter (/usr/bin/python3) and is never a kame dependency.
# Does nothing where apt is missing or we are not root: the interop tests then skip.
set -euo pipefail
packages=(
  ros-core python3-genpy python3-genmsg python3-numpy
  python3-geometry-msgs python3-sensor-msgs python3-nav-msgs python3-std-srvs python3-tf2-msgs
  python3-actionlib
  python3-interactive-markers python3-visualization-msgs  # Debian's InteractiveMarkerServer feeding kame's rviz model (tests/interactive_markers)
  python3-dynamic-reconfigure  # dynparam, Client and Server against kame's (tests/dynamic_reconfigure)
  libdynamic-reconfigure-config-init-mutex-dev  # the generator's templates: catkin's cfg outputs compared with kame's
  python3-tf2-ros python3-tf python3-tf2-geometry-msgs tf2-tools tf-tools  # tf/tf2 interop (tests/tf)
  python3-tf-conversions python3-pykdl  # posemath and PyKDL compared with kame's (tests/tf/test_posemath.py)
  # image_transport's republish (raw only: Debian has no compressed plugin) and cv_bridge with OpenCV,
  # which decode and make the compressed images kame's republish reads and writes (tests/libs/test_image_transport.py)
  image-transport-tools python3-cv-bridge
  python3-camera-calibration-parsers  # Debian's readCalibration reads kame's YAML and INI calibration files (tests/camera)
  libroscpp-dev libstd-msgs-dev libgeometry-msgs-dev libsensor-msgs-dev libstd-srvs-dev
  ros-std-msgs ros-std-srvs ros-geometry-msgs ros-sensor-msgs ros-nav-msgs ros-rosgraph-msgs
  ros-actionlib-msgs ros-diagnostic-msgs ros-trajectory-msgs ros-visualization-msgs
  ros-shape-msgs ros-stereo-msgs ros-tf2-msgs ros-roscpp-msg ros-move-base-msgs python3-rostest
  rosbash  # rosrun and rospack (rospack-tools), compared with kame's
  g++ pkg-config
  # catkin_make and catkin build of C++ packages with the real tools (tests/catkin): CMake, make, the
  # system's catkin macros, message generation (gencpp for the headers, actionlib_msgs' genaction for
  # kame's actions) and the course's message headers
  cmake make catkin ros-message-generation ros-message-runtime python3-gencpp libgeometry-msgs-dev
  libactionlib-msgs-dev
  zsh tmux  # the shell-integration and terminal (teleop) tests drive these
  iproute2  # ip netns: the several-hosts tests (tests/hosts) run each host in a network namespace
  openssh-server  # sshd, run by tests/hosts in a namespace for roslaunch's <machine> nodes
  rviz  # Debian's rviz 1.14 on Xvfb, shown kame's TurtleBot world (tests/stage/test_debian_rviz.py)
)
if ! command -v apt-get >/dev/null 2>&1 || [ "$(id -u)" != 0 ]; then
  echo "install-ros-peers: no apt-get or not root; interop tests with real ROS 1 will be skipped" >&2
  exit 0
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
echo "install-ros-peers: installing ${#missing[@]} Debian packages" >&2
apt-get update -qq
# The tests start their own sshd (and nothing else) in a namespace: installing openssh-server
# must not start a system-wide sshd on port 22 as a side effect, so for this one install
# Debian's policy-rc.d says no service may start (exit 101), unless the machine already has one.
policy=/usr/sbin/policy-rc.d
if [ ! -e "$policy" ]; then
  printf '#!/bin/sh\nexit 101\n' >"$policy" && chmod +x "$policy"
  trap 'rm -f "$policy"' EXIT
fi
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
