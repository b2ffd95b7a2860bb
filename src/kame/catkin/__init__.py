"""Workspaces: what catkin_make and `catkin build` do. Python-only packages are kame's, with no
CMake; packages with C/C++ targets are the real CMake's, with the system's catkin and roscpp.

workspace: the source space (packages, order, C++ targets, setup.py, catkin_install_python).
devel: the devel space written (setup files chaining to kame's, Python relays).
build: one build of a workspace, reported through a callback.
reconfigure_files: catkin's dynamic_reconfigure files written when a .cfg is run as catkin runs it.
toolchain: the system's CMake, make, compiler, catkin and roscpp, found; what to install if not.
cmake: catkin_make's cmake and make commands run over the C/C++ packages.
cpp_messages: C++ headers (by the system's gencpp) for kame's message packages the system lacks.
"""
