from __future__ import annotations

import os

# before Qt starts: the window is tested offscreen here; the live test runs it on a private Xvfb
if not os.environ.get("QT_QPA_PLATFORM"):
    os.environ["QT_QPA_PLATFORM"] = "offscreen"
