#!/usr/bin/env python3
# camera_calibration's cameracalibrator.py, as kame runs it
# (rosrun camera_calibration cameracalibrator.py --size 8x6 --square 0.108 image:=/usb_cam/image_raw camera:=/usb_cam).
import sys

from kame.camera.cameracalibrator import main

if __name__ == "__main__":
    sys.exit(main())
