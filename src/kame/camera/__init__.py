"""kame.camera: the camera lesson's packages (usb_cam, camera_info_manager,
camera_calibration_parsers, image_view, camera_calibration, image_proc).

Pure modules (L1): `pixel_formats` (a camera's raw frames to sensor_msgs/Image), `testsrc` (the
moving test pattern), `calibration_files` (camera_calibration_parsers' YAML and INI),
`info_url` (camera_info_manager's URLs), `opencv` (the one place OpenCV is imported, with the
line naming the feature that needs it). `sources` (L2) reads frames from V4L2 devices (linuxpy),
video files and the test pattern; the nodes on kame.client are L4.
"""
