#!/usr/bin/env python3
# camera_calibration's cameracheck.py, as kame runs it
# (rosrun camera_calibration cameracheck.py --size 8x6 --square 0.108 monocular:=/usb_cam).
import sys

from kame.camera.cameracheck import main

if __name__ == "__main__":
    sys.exit(main())
