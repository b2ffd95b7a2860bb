"""rviz for kame: a 3-D view of frames, markers, scans, clouds, maps and paths.

The package's modules without a Qt or ROS name in them are the model (L1): the camera, the
scene (what to draw, in the fixed frame), the displays that turn messages into the scene, and
the .rviz config files. `source` talks to ROS (a node, the tf Buffer), `window` draws the
scene with OpenGL inside Qt, and `main` is the `rviz` program."""
