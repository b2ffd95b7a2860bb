"""Asks rospkg about the packages on given ROS paths and prints the answers as JSON.

Run by kame's interpreter and by Debian's /usr/bin/python3 (its real rospkg) on the same trees.
"""

from __future__ import annotations

import json
import sys
from typing import Any

import rospkg


def run(request: dict[str, Any]) -> dict[str, Any]:
    paths = request["paths"]
    rospack, rosstack = rospkg.RosPack(paths), rospkg.RosStack(paths)
    answer: dict[str, Any] = {"packages": sorted(rospack.list()), "stacks": sorted(rosstack.list())}
    answer["paths"] = {name: rospack.get_path(name) for name in answer["packages"]}
    answer["stack_paths"] = {name: rosstack.get_path(name) for name in answer["stacks"]}
    answer["stack_packages"] = {name: sorted(rosstack.packages_of(name)) for name in answer["stacks"]}
    answer["names_of"] = {path: rospkg.get_package_name(path) for path in request["probe"]}
    answer["expand"] = list(rospkg.expand_to_packages(request["expand"], rospack, rosstack))
    manifests = {}
    for name in answer["packages"]:
        try:
            m = rospack.get_manifest(name)
        except Exception as exc:  # which exception is part of the answer
            manifests[name] = type(exc).__name__
            continue
        manifests[name] = [m.version, m.license, m.author, m.description, m.url, m.is_catkin, m.type,
                           [[e.tag, e.attrs, e.str] for e in m.exports]]
    answer["manifests"] = manifests
    try:
        rospack.get_path("no_such_package")
    except rospkg.ResourceNotFound as exc:
        answer["not_found"] = str(exc)
    env = request["env"]
    answer["env"] = [rospkg.get_ros_home(env), rospkg.get_log_dir(env), rospkg.get_test_results_dir(env),
                     rospkg.get_etc_ros_dir(env), rospkg.get_ros_root(env)]
    return answer


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
