"""rospkg, ROS 1's library for finding packages and stacks and reading their manifests, for kame.

The search path is ROS_ROOT and ROS_PACKAGE_PATH, then the packages kame ships (see
rospkg.environment).
"""

from __future__ import annotations

from .common import MANIFEST_FILE, PACKAGE_FILE, STACK_FILE, ResourceNotFound
from .environment import (
    get_etc_ros_dir,
    get_log_dir,
    get_ros_home,
    get_ros_package_path,
    get_ros_paths,
    get_ros_root,
    get_test_results_dir,
    on_ros_path,
)
from .manifest import InvalidManifest, Manifest, parse_manifest_file
from .rospack import RosPack, RosStack, expand_to_packages, get_package_name, list_by_path

__all__ = ["MANIFEST_FILE", "PACKAGE_FILE", "STACK_FILE", "InvalidManifest", "Manifest", "ResourceNotFound", "RosPack",
           "RosStack", "expand_to_packages", "get_etc_ros_dir", "get_log_dir", "get_package_name", "get_ros_home",
           "get_ros_package_path", "get_ros_paths", "get_ros_root", "get_test_results_dir", "list_by_path",
           "on_ros_path", "parse_manifest_file"]
