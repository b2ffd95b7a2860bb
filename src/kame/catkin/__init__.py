"""Workspaces: what catkin_make and `catkin build` do for Python packages, with no CMake.

workspace: the source space (packages, order, C++ targets, setup.py, catkin_install_python).
devel: the devel space written (setup files chaining to kame's, Python relays).
build: one build of a workspace, reported through a callback.
reconfigure_files: catkin's dynamic_reconfigure files written when a .cfg is run as catkin runs it.
"""
