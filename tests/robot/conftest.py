from __future__ import annotations

import os

# before Qt starts: joint_state_publisher_gui's window is tested offscreen, with no display
if not os.environ.get("QT_QPA_PLATFORM"):
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
