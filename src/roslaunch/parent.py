"""roslaunch.parent: ROSLaunchParent (kame.launch.scripting: the launch runs on kame's own runner)."""

from kame.launch.scripting import Process, ROSLaunchParent
from roslaunch.config import load_config_default
from roslaunch.core import RLException, printerrlog, printlog_bold
from roslaunch.nodeprocess import DEFAULT_TIMEOUT_SIGINT, DEFAULT_TIMEOUT_SIGTERM, NUM_WORKERS

__all__ = ["DEFAULT_TIMEOUT_SIGINT", "DEFAULT_TIMEOUT_SIGTERM", "NUM_WORKERS", "Process", "RLException",
           "ROSLaunchParent", "load_config_default", "printerrlog", "printlog_bold"]
