#!/usr/bin/env bash
# Installs the system libraries that Qt's X11 platform plugin (PySide6's libqxcb.so) loads, so
# turtlesim's window can open on a fresh Debian/Ubuntu; with --xvfb also the X server and tools
# the GUI tests use (Xvfb, xwininfo from x11-utils, xwd from x11-apps, xdotool clicking the camera
# calibrator's buttons, and Mesa's software OpenGL that rviz's 3-D view renders with on Xvfb, and
# MuJoCo's cameras with through EGL, headless).
# Runs apt-get as root, or through sudo when sudo needs no password; otherwise it says what to
# install and exits 0 (turtlesim then names the missing library and runs headless).
# The list is kame.turtlesim.window_probe.QT_X11_PACKAGES (a test keeps the two the same).
set -euo pipefail
packages=(
  libxcb-cursor0 libxcb-icccm4 libxcb-keysyms1 libxcb-image0 libxcb-render-util0
  libxcb-randr0 libxcb-shape0 libxcb-shm0 libxcb-sync1 libxcb-xfixes0 libxcb-xkb1
  libxcb-util1 libx11-xcb1 libxkbcommon0 libxkbcommon-x11-0 libegl1 libgl1
  libfontconfig1 libfreetype6 libglib2.0-0 libdbus-1-3
)
if [ "${1:-}" = --xvfb ]; then
  # libopengl0 with libegl1, libegl-mesa0 and libgl1-mesa-dri: MuJoCo's headless renderer (MUJOCO_GL=egl),
  # the 3-D simulator's cameras; xdotool clicks the camera calibrator's buttons
  packages+=(xvfb x11-utils x11-apps libgl1-mesa-dri libglx-mesa0 libegl-mesa0 libopengl0 xdotool)
fi
if ! command -v apt-get >/dev/null 2>&1 || ! command -v dpkg-query >/dev/null 2>&1; then
  echo "install-gui-libs: no apt-get here; Qt's window needs the X11 libraries your system calls" \
       "${packages[*]}" >&2
  exit 0
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q 'install ok installed' || missing+=("$p")
done
if [ ${#missing[@]} -eq 0 ]; then
  exit 0
fi
if [ "$(id -u)" = 0 ]; then
  as_root=()
elif command -v sudo >/dev/null 2>&1 && sudo -n true 2>/dev/null; then
  as_root=(sudo -n)
else
  echo "install-gui-libs: not root and no password-less sudo; to give turtlesim its window run:" >&2
  echo "  sudo apt-get install ${missing[*]}" >&2
  exit 0
fi
echo "install-gui-libs: installing ${missing[*]}" >&2
if ! { "${as_root[@]}" apt-get update -qq &&
       "${as_root[@]}" env DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
         "${missing[@]}" >/dev/null; }; then
  echo "install-gui-libs: apt-get failed; turtlesim will name what it misses, and the Xvfb tests skip" >&2
fi
