from __future__ import annotations

import os

# before Qt starts: the window tests that need no OpenGL run offscreen, with no display
# (those that draw run the window in a child process on a private Xvfb)
if not os.environ.get("QT_QPA_PLATFORM"):
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
