#!/usr/bin/env python3
# tf2_tools' echo.py, as kame runs it (rosrun tf2_tools echo.py).
import sys

from kame.cli.tf_echo import main_tf2

if __name__ == "__main__":
    sys.exit(main_tf2())
