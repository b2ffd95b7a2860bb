from __future__ import annotations

import os

# before Qt starts: the camera windows are tested offscreen here, and under Xvfb in their own processes
if not os.environ.get("QT_QPA_PLATFORM"):
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
