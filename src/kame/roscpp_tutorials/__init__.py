"""roscpp_tutorials, as the courses run it: `rosrun roscpp_tutorials talker`, `listener`,
`add_two_ints_server`, ..., and `roslaunch roscpp_tutorials talker_listener.launch`.

kame/share/roscpp_tutorials holds what an installed ROS keeps in share/ (cmake, launch,
package.xml, srv); kame/lib/roscpp_tutorials the programs' launchers, found by rosrun and
roslaunch as lib/roscpp_tutorials. A launcher runs (run.py) the C++ program built from kame's
sources (cpp/, written in the tutorials' style) with the system's roscpp, building it once
where the machine has a C++ toolchain and roscpp (build.py); elsewhere, or with
KAME_CPP_TUTORIALS=port, kame's Python port of it (ports.py), with the same node names, topics,
service and console lines.
"""
