#!/bin/sh
# kame's env-loader for roslaunch <machine> tags (ROS's /opt/ros/<distro>/env.sh): sets up the
# ROS environment of the kame installation it lies in, then runs its arguments in it.
#   <machine name="robot" address="robot" env-loader="/path/to/kame/shell/env.sh"/>
# A lab's own loader sets ROS_HOSTNAME/ROS_IP (and sources a workspace) and then runs this one.
if [ $# -eq 0 ]; then
    echo "Usage: env.sh COMMANDS" >&2
    echo "Calling env.sh without arguments is not supported anymore. Instead spawn a subshell and source a setup file manually." >&2
    exit 1
fi
_KAME_SETUP_DIR=$(cd "$(dirname "$0")" && pwd)
. "$_KAME_SETUP_DIR/setup.sh" || exit 1
exec "$@"
