"""roslaunch's launch files: parsed to a model (loader), planned (plan), run (supervisor).

Pure parts: errors, values, substitution, xmltree, model, loader, executables, plan.
I/O: supervisor (processes), runner (master, parameters, the whole launch).
"""

from kame.launch.errors import LaunchError, PackageNotFound
from kame.launch.loader import LaunchLoader, LoaderHost
from kame.launch.model import LaunchConfig, Machine, Node, Param

__all__ = ["LaunchConfig", "LaunchError", "LaunchLoader", "LoaderHost", "Machine", "Node", "PackageNotFound", "Param"]
