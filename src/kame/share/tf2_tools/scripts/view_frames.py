#!/usr/bin/env python3
# tf2_tools' view_frames.py, as kame runs it (rosrun tf2_tools view_frames.py).
import sys

from kame.cli.view_frames import main_tf2

if __name__ == "__main__":
    sys.exit(main_tf2())
