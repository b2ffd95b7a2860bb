"""Debian's real rviz 1.14 (the reference client) follows kame's InteractiveMarkerServer: on a
private Xvfb against kame's master, with the tutorial's simple_marker (kame's interactive_markers
package) serving, rviz's InteractiveMarkers display draws the marker's teal box (read back from
the screen) - the init, updates and keep-alives are what rviz expects."""

from __future__ import annotations

import os
import time
from pathlib import Path
from typing import Any

import pytest

from tests.support import Proc, have_debian_ros
from tests.turtlesim.sim import BIN, master

np = pytest.importorskip("numpy")

DEBIAN_RVIZ = "/usr/bin/rviz"
CONFIG = """\
Panels:
  - Class: rviz/Displays
    Name: Displays
Visualization Manager:
  Class: ""
  Displays:
    - Class: rviz/InteractiveMarkers
      Enable Transparency: true
      Enabled: true
      Name: InteractiveMarkers
      Show Axes: false
      Show Descriptions: true
      Show Visual Aids: false
      Update Topic: /simple_marker/update
      Interactive Markers Namespace: /simple_marker
      Value: true
  Enabled: true
  Global Options:
    Background Color: 48; 48; 48
    Fixed Frame: base_link
    Frame Rate: 30
  Name: root
  Tools:
    - Class: rviz/Interact
      Hide Inactive Objects: true
  Value: true
  Views:
    Current:
      Class: rviz/TopDownOrtho
      Name: Current View
      Scale: 100
      X: 0
      Y: 0
"""


def teal(image: Any) -> Any:
    """The box's (0, 0.5, 0.5), as rviz's light shades it."""
    r, g, b = image[:, :, 0], image[:, :, 1], image[:, :, 2]
    return (r < 40) & (g > 50) & (np.abs(g - b) < 25)


def test_debian_rviz_draws_kames_interactive_marker(tmp_path: Path) -> None:
    if not have_debian_ros():
        pytest.skip("Debian's ROS 1 is not installed")
    if not os.path.exists(DEBIAN_RVIZ):
        pytest.skip("Debian's rviz is not installed (apt-get install rviz; scripts/install-ros-peers.sh)")
    from tests.stage.test_debian_rviz import pixels
    from tests.turtlesim.xserver import find_shown_window, screenshot, xvfb

    config = tmp_path / "simple_marker.rviz"
    config.write_text(CONFIG)
    with master(tmp_path) as sim, xvfb("1024x768") as display:
        for command in ([str(BIN / "rosrun"), "interactive_marker_tutorials", "simple_marker.py"],
                        [str(BIN / "rosrun"), "tf2_ros", "static_transform_publisher", "0", "0", "0", "0", "0", "0",
                         "world", "base_link"]):
            sim.procs.append(Proc(command, sim.env, cwd=sim.home))
        rviz = Proc([DEBIAN_RVIZ, "-d", str(config)], dict(sim.env, DISPLAY=display, LIBGL_ALWAYS_SOFTWARE="1"),
                    cwd=sim.home)
        sim.procs.append(rviz)
        deadline, window, count = time.monotonic() + 120, None, 0
        while time.monotonic() < deadline:
            assert rviz.popen.poll() is None, f"rviz exited:\n{''.join(rviz.out)}\n{''.join(rviz.err)}"
            window = window or find_shown_window(display, f"{config.name} - RViz")
            if window is not None:
                count = int(teal(pixels(screenshot(display, window.id))).sum())
                if count > 500:
                    break
            time.sleep(0.5)
        # the 0.45 m box at 100 pixels a metre: about 45 x 45 pixels
        assert count > 500, (count, "".join(rviz.err)[-2000:])
