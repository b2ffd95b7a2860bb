"""roslib.rospack: rosbuild-era wrappers that run the rospack and rosstack programs found on PATH
(deprecated, as in ROS: rospkg.RosPack answers the same questions in the process)."""

from __future__ import annotations

import subprocess
import warnings

from roslib.exceptions import ROSLibException

__all__ = ["python3", "rospack_depends", "rospack_depends_1", "rospack_depends_on", "rospack_depends_on_1",
           "rospack_plugins", "rospackexec", "rosstack_depends", "rosstack_depends_1", "rosstack_depends_on",
           "rosstack_depends_on_1", "rosstackexec"]

python3 = True

warnings.warn("roslib.rospack is deprecated, please use rospkg", stacklevel=2)


def _run(program: str, args: list[str]) -> str:
    out = subprocess.run([program, *args], capture_output=True, check=False).stdout.decode().strip()
    if out.startswith(f"{program}:"):  # the program's error message
        raise ROSLibException(out)
    return out


def rospackexec(args: list[str]) -> str:
    """What `rospack <args>` prints; ROSLibException for its error messages."""
    return _run("rospack", args)


def rospack_depends_on_1(pkg: str) -> list[str]:
    return rospackexec(["depends-on1", pkg]).split()


def rospack_depends_on(pkg: str) -> list[str]:
    return rospackexec(["depends-on", pkg]).split()


def rospack_depends_1(pkg: str) -> list[str]:
    return rospackexec(["deps1", pkg]).split()


def rospack_depends(pkg: str) -> list[str]:
    return rospackexec(["deps", pkg]).split()


def rospack_plugins(pkg: str) -> list[tuple[str, ...]]:
    """(package, plugin) of each package exporting a `plugin` attribute for `pkg`."""
    out = rospackexec(["plugins", "--attrib=plugin", pkg])
    return [tuple(line.split(" ")) for line in out.split("\n")] if out else []


def rosstackexec(args: list[str]) -> str:
    """What `rosstack <args>` prints; ROSLibException for its error messages."""
    return _run("rosstack", args)


def rosstack_depends_on(s: str) -> list[str]:
    return rosstackexec(["depends-on", s]).split()


def rosstack_depends_on_1(s: str) -> list[str]:
    return rosstackexec(["depends-on1", s]).split()


def rosstack_depends(s: str) -> list[str]:
    return rosstackexec(["depends", s]).split()


def rosstack_depends_1(s: str) -> list[str]:
    return rosstackexec(["depends1", s]).split()
