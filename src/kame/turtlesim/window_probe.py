"""Whether a kame window (turtlesim's, the simulator's) can open, judged from what a probe child
printed, in words a user can act on.

Rules: pure (text in, text out). The probe is `python -m kame.turtlesim.gui` (run by the node
with Qt's QT_DEBUG_PLUGINS=1); on success it prints `PROBE_OK <platform>`. When Qt's platform
plugin cannot load, Qt aborts the child after its plugin loader has named the first shared
library the dynamic linker could not find; Debian and Ubuntu name that library's package after
its soname (libxcb-icccm.so.4 -> libxcb-icccm4), with the few exceptions in SONAME_PACKAGES.
"""

from __future__ import annotations

import re

PROBE_OK = "kame-window-probe: ok"
PROBE_LEAK = "kame-window-probe: leaks None"  # followed by the binding's version

# What Qt's xcb platform plugin (and QtGui) load, as Debian/Ubuntu packages: `ldd` on PySide6's
# libqxcb.so and libQt6XcbQpa.so. scripts/install-gui-libs.sh installs the same list.
QT_X11_PACKAGES = (
    "libxcb-cursor0", "libxcb-icccm4", "libxcb-keysyms1", "libxcb-image0", "libxcb-render-util0",
    "libxcb-randr0", "libxcb-shape0", "libxcb-shm0", "libxcb-sync1", "libxcb-xfixes0", "libxcb-xkb1",
    "libxcb-util1", "libx11-xcb1", "libxkbcommon0", "libxkbcommon-x11-0", "libegl1", "libgl1",
    "libfontconfig1", "libfreetype6", "libglib2.0-0", "libdbus-1-3",
)
SONAME_PACKAGES = {"libglib-2.0.so.0": "libglib2.0-0", "libgthread-2.0.so.0": "libglib2.0-0",
                   "libGLX.so.0": "libglx0", "libGLdispatch.so.0": "libglvnd0"}

_MISSING_LIBRARY = re.compile(r"([\w.+-]+\.so(?:\.\d+)*): cannot open shared object file")
_NO_DISPLAY = re.compile(r"could not connect to display ?(\S*)")


def debian_package(soname: str) -> str:
    """The Debian/Ubuntu package that ships a shared library, by Debian's naming rule:
    libfoo-bar.so.4 -> libfoo-bar4, and a hyphen before a version that follows a digit
    (libxkbcommon-x11.so.0 -> libxkbcommon-x11-0, libdbus-1.so.3 -> libdbus-1-3)."""
    if soname in SONAME_PACKAGES:
        return SONAME_PACKAGES[soname]
    name, _, version = soname.partition(".so")
    version = version.lstrip(".").split(".")[0]
    if not version:
        return name.lower()
    separator = "-" if name[-1:].isdigit() else ""
    return f"{name}{separator}{version}".lower()


def headless_words(program: str) -> str:
    return f"{program} runs headless, without a window"


def window_verdict(returncode: int | None, output: str, python_version: str, program: str = "turtlesim") -> str | None:
    """None when the probe opened Qt's platform; else why there is no window, and the fix."""
    headless = headless_words(program)
    if returncode == 0 and PROBE_OK in output:
        return None
    if returncode is None:
        return f"Qt did not start within the probe's deadline: {headless}"
    leak = re.search(re.escape(PROBE_LEAK) + r" (\S+)", output)
    if leak:
        return (f"PySide6 {leak.group(1)} loses a reference to None on every call, which aborts Python "
                f"{python_version} within seconds of drawing (Fatal Python error: none_dealloc); install "
                f"another release (pip install 'PySide6-Essentials!={leak.group(1)}'): {headless}")
    missing = _MISSING_LIBRARY.search(output)
    if missing:
        soname = missing.group(1)
        return (f"Qt cannot open a window: the system library {soname} is missing (Debian/Ubuntu: "
                f"sudo apt-get install {debian_package(soname)}; all that Qt's X11 plugin needs: "
                f"sudo apt-get install {' '.join(QT_X11_PACKAGES)}): {headless}")
    display = _NO_DISPLAY.search(output)
    if display:
        where = f" {display.group(1)}" if display.group(1) else ""
        return f"Qt cannot connect to the display{where} (is the X server running, and may you use it?): {headless}"
    lines = [line.strip() for line in output.splitlines()
             if line.strip() and not line.startswith(("qt.core.", "    ", "\t", "{", "}"))]
    said = "; ".join(lines[-3:]) or "no output"
    status = f"signal {-returncode}" if returncode < 0 else f"status {returncode}"
    return f"Qt cannot open a window (its probe ended with {status}: {said}): {headless}"
