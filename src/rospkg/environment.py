"""rospkg.environment: the ROS search path and the folders ROS writes to.

As on Debian, whose rospkg appends /usr/share (where its packages live) to ROS_PACKAGE_PATH,
kame's rospkg appends the folder of the packages kame ships, so RosPack finds them without a
setup file.
"""

from __future__ import annotations

import os
from collections.abc import Mapping

from kame.msg.catalog import SHARE_DIR

ROS_ROOT = "ROS_ROOT"
ROS_PACKAGE_PATH = "ROS_PACKAGE_PATH"
ROS_HOME = "ROS_HOME"
ROS_LOG_DIR = "ROS_LOG_DIR"
ROS_TEST_RESULTS_DIR = "ROS_TEST_RESULTS_DIR"
ROS_ETC_DIR = "ROS_ETC_DIR"

__all__ = ["ROS_ETC_DIR", "ROS_HOME", "ROS_LOG_DIR", "ROS_PACKAGE_PATH", "ROS_ROOT", "ROS_TEST_RESULTS_DIR",
           "get_etc_ros_dir", "get_log_dir", "get_ros_home", "get_ros_package_path", "get_ros_paths",
           "get_ros_root", "get_test_results_dir", "on_ros_path"]


def _env(env: Mapping[str, str] | None) -> Mapping[str, str]:
    return os.environ if env is None else env


def get_ros_root(env: Mapping[str, str] | None = None) -> str | None:
    ros_root = _env(env).get(ROS_ROOT)
    return os.path.normpath(ros_root) if ros_root else None


def get_ros_package_path(env: Mapping[str, str] | None = None) -> str:
    """ROS_PACKAGE_PATH, then the packages kame ships."""
    return _env(env).get(ROS_PACKAGE_PATH, "") + os.pathsep + str(SHARE_DIR)


def get_ros_paths(env: Mapping[str, str] | None = None) -> list[str]:
    """ROS_ROOT (when set), then each entry of get_ros_package_path(): first one wins."""
    paths = [root] if (root := get_ros_root(env)) else []
    return paths + [p for p in get_ros_package_path(env).split(os.pathsep) if p.strip()]


def get_ros_home(env: Mapping[str, str] | None = None) -> str:
    env = _env(env)
    return env[ROS_HOME] if ROS_HOME in env else os.path.join(os.path.expanduser("~"), ".ros")


def get_log_dir(env: Mapping[str, str] | None = None) -> str:
    env = _env(env)
    return env[ROS_LOG_DIR] if ROS_LOG_DIR in env else os.path.join(get_ros_home(env), "log")


def get_test_results_dir(env: Mapping[str, str] | None = None) -> str:
    env = _env(env)
    return env[ROS_TEST_RESULTS_DIR] if ROS_TEST_RESULTS_DIR in env else os.path.join(get_ros_home(env),
                                                                                    "test_results")


def get_etc_ros_dir(env: Mapping[str, str] | None = None) -> str:
    env = _env(env)
    return env[ROS_ETC_DIR] if ROS_ETC_DIR in env else "/etc/ros"


def _resolve(path: str) -> str:
    return os.path.realpath(os.path.abspath(os.path.expanduser(path)))


def on_ros_path(p: str, env: Mapping[str, str] | None = None) -> bool:
    """True when path `p` is one of the ROS paths or inside one."""
    target = _resolve(p)
    roots = [_resolve(x) for x in get_ros_paths(env)]
    return any(target == root or target.startswith(root + os.sep) for root in roots)
