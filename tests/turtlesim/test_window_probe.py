"""What turtlesim says when its window cannot open: the probe's output, read into a reason and a
fix (pure), and the apt list the install script uses kept equal to the one turtlesim prints."""

from __future__ import annotations

import re

import pytest

from kame.turtlesim.window_probe import (
    PROBE_LEAK,
    PROBE_OK,
    QT_X11_PACKAGES,
    debian_package,
    window_verdict,
)
from tests.support import REPO

# What Qt 6.11's plugin loader printed here (QT_DEBUG_PLUGINS=1, abridged), libxcb-icccm4 missing
MISSING_ICCCM = """\
qt.core.plugin.factoryloader: Got keys from plugin meta data QList("xcb")
qt.core.library: "/v/PySide6/Qt/plugins/platforms/libqxcb.so" cannot load: Cannot load library \
/v/PySide6/Qt/plugins/platforms/libqxcb.so: libxcb-icccm.so.4: cannot open shared object file: No such file or directory
qt.qpa.plugin: From 6.5.0, xcb-cursor0 or libxcb-cursor0 is needed to load the Qt xcb platform plugin.
qt.qpa.plugin: Could not load the Qt platform plugin "xcb" in "" even though it was found.
"""
NO_X_SERVER = """\
qt.core.plugin.factoryloader: looking at "libqvkkhrdisplay.so"
qt.qpa.xcb: could not connect to display :4093
qt.qpa.plugin: Could not load the Qt platform plugin "xcb" in "" even though it was found.
"""
NO_EGL = """\
Traceback (most recent call last):
  File "<frozen runpy>", line 198, in _run_module_as_main
ImportError: libEGL.so.1: cannot open shared object file: No such file or directory
"""


@pytest.mark.parametrize(("soname", "package"), [
    ("libxcb-icccm.so.4", "libxcb-icccm4"),
    ("libxcb-keysyms.so.1", "libxcb-keysyms1"),
    ("libxcb-cursor.so.0", "libxcb-cursor0"),
    ("libxcb-render-util.so.0", "libxcb-render-util0"),
    ("libxkbcommon-x11.so.0", "libxkbcommon-x11-0"),
    ("libdbus-1.so.3", "libdbus-1-3"),
    ("libEGL.so.1", "libegl1"),
    ("libX11-xcb.so.1", "libx11-xcb1"),
    ("libglib-2.0.so.0", "libglib2.0-0"),
])
def test_debian_package_of_a_library(soname: str, package: str) -> None:
    assert debian_package(soname) == package


def test_a_window_when_the_probe_opened_qt() -> None:
    assert window_verdict(0, f"noise\n{PROBE_OK} xcb\n", "3.11.2") is None


def test_a_missing_library_is_named_with_its_package() -> None:
    verdict = window_verdict(-6, MISSING_ICCCM, "3.11.2")
    assert verdict is not None
    assert "libxcb-icccm.so.4 is missing" in verdict
    assert "sudo apt-get install libxcb-icccm4;" in verdict
    assert verdict.endswith("turtlesim runs headless, without a window")
    assert "libxcb-cursor0" in verdict  # in the full list, not as Qt's misleading guess


def test_a_missing_library_of_qtgui_itself() -> None:
    verdict = window_verdict(1, NO_EGL, "3.11.2")
    assert verdict is not None and "libEGL.so.1 is missing" in verdict and "install libegl1;" in verdict


def test_no_x_server() -> None:
    verdict = window_verdict(-6, NO_X_SERVER, "3.11.2")
    assert verdict == ("Qt cannot connect to the display :4093 (is the X server running, and may you use it?): "
                       "turtlesim runs headless, without a window")


def test_a_binding_that_loses_references_to_none_is_refused() -> None:
    verdict = window_verdict(2, f"{PROBE_LEAK} 6.12.0\n", "3.11.7")
    assert verdict is not None
    assert "PySide6 6.12.0" in verdict and "Python 3.11.7" in verdict and "none_dealloc" in verdict
    assert "PySide6-Essentials!=6.12.0" in verdict


def test_a_probe_that_hangs_or_fails_otherwise() -> None:
    assert "did not start" in (window_verdict(None, "", "3.11.2") or "")
    verdict = window_verdict(-11, "qt.core.plugin.loader: noise\nsomething odd\n", "3.11.2")
    assert verdict is not None and "signal 11" in verdict and "something odd" in verdict and "noise" not in verdict


def test_the_install_script_installs_what_turtlesim_asks_for() -> None:
    script = (REPO / "scripts" / "install-gui-libs.sh").read_text()
    listed = re.search(r"^packages=\(\n(.*?)\n\)", script, re.MULTILINE | re.DOTALL)
    assert listed is not None
    assert tuple(listed.group(1).split()) == QT_X11_PACKAGES
