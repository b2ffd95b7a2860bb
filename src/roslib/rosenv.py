"""roslib.rosenv: the ROS environment variables and folders, as the deprecated roslib module
reads them (rospkg.environment and rosgraph.rosenv are the maintained ones)."""

from __future__ import annotations

import os
import sys
import warnings
from collections.abc import Mapping, Sequence

from rosgraph.roslogging import makedirs_with_parent_perms

__all__ = ["ROS_BINDEPS_PATH", "ROS_BOOST_ROOT", "ROS_HOME", "ROS_HOSTNAME", "ROS_IP", "ROS_LOG_DIR", "ROS_MASTER_URI",
           "ROS_NAMESPACE", "ROS_PACKAGE_PATH", "ROS_ROOT", "ROSEnvException", "get_log_dir", "get_master_uri",
           "get_ros_home", "get_ros_package_path", "get_ros_root", "get_test_results_dir", "makedirs_with_parent_perms"]

ROS_ROOT = "ROS_ROOT"
ROS_MASTER_URI = "ROS_MASTER_URI"
ROS_PACKAGE_PATH = "ROS_PACKAGE_PATH"
ROS_HOME = "ROS_HOME"
ROS_BINDEPS_PATH = "ROS_BINDEPS_PATH"
ROS_BOOST_ROOT = "ROS_BOOST_ROOT"
ROS_IP = "ROS_IP"
ROS_HOSTNAME = "ROS_HOSTNAME"
ROS_NAMESPACE = "ROS_NAMESPACE"
ROS_LOG_DIR = "ROS_LOG_DIR"

warnings.warn("roslib.rosenv is deprecated, please use rospkg or rosgraph.rosenv", stacklevel=2)


class ROSEnvException(Exception):
    """A required variable is not set, or set wrong."""


def get_ros_root(required: bool = True, env: Mapping[str, str] | None = None) -> str | None:
    env = os.environ if env is None else env
    if ROS_ROOT in env:
        return env[ROS_ROOT]
    if required:
        raise ROSEnvException(f"\nThe {ROS_ROOT} environment variable has not been set.\nPlease set to the "
                              "location of your ROS installation\nbefore continuing.\n")
    return None


def get_ros_package_path(required: bool = False, env: Mapping[str, str] | None = None) -> str | None:
    env = os.environ if env is None else env
    if ROS_PACKAGE_PATH in env:
        return env[ROS_PACKAGE_PATH]
    if required:
        raise ROSEnvException(f"{ROS_PACKAGE_PATH} has not been configured")
    return None


def get_master_uri(required: bool = True, env: Mapping[str, str] | None = None,
                   argv: Sequence[str] | None = None) -> str | None:
    """`__master:=` from `argv` (sys.argv), else ROS_MASTER_URI."""
    env = os.environ if env is None else env
    for arg in sys.argv if argv is None else argv:
        if arg.startswith("__master:="):
            parts = arg.split(":=")
            if len(parts) != 2 or not parts[1]:
                raise ROSEnvException(f"__master remapping argument '{arg}' improperly specified")
            return parts[1]
    if ROS_MASTER_URI in env:
        return env[ROS_MASTER_URI]
    if required:
        raise ROSEnvException(f"{ROS_MASTER_URI} has not been configured")
    return None


def get_ros_home(env: Mapping[str, str] | None = None) -> str:
    env = os.environ if env is None else env
    return env[ROS_HOME] if ROS_HOME in env else os.path.join(os.path.expanduser("~"), ".ros")


def get_log_dir(env: Mapping[str, str] | None = None) -> str:
    env = os.environ if env is None else env
    return env[ROS_LOG_DIR] if ROS_LOG_DIR in env else os.path.join(get_ros_home(env), "log")


def get_test_results_dir(env: Mapping[str, str] | None = None) -> str:
    return os.path.join(get_ros_home(env), "test_results")
