"""roslaunch's module API (config.ROSLaunchConfig, xmlloader.XmlLoader, load_config_default,
core) on one launch file; prints the answers as JSON. Run by kame's interpreter and Debian's."""

from __future__ import annotations

import json
import sys
from typing import Any

import roslaunch.config
import roslaunch.core
import roslaunch.xmlloader


def node_row(node: Any) -> list[Any]:
    return [node.package, node.type, node.name, node.namespace, node.args, [list(r) for r in node.remap_args],
            node.respawn, node.output, node.required, node.machine_name]


def described(config: Any) -> dict[str, Any]:
    return {"params": {key: p.value for key, p in sorted(config.params.items())},
            "nodes": [node_row(n) for n in config.nodes],
            "tests": [[t.test_name, t.time_limit, t.retry, t.name, t.package, t.type] for t in config.tests],
            "machines": sorted(config.machines), "files": config.roslaunch_files}


def errors(launch: str) -> list[Any]:
    out = []
    for args, text in ((["robot:=r2"], "<launch><node pkg='x'</launch>"),
                       ([], None)):  # malformed XML; a required arg not given
        config = roslaunch.config.ROSLaunchConfig()
        try:
            if text is None:
                loader = roslaunch.xmlloader.XmlLoader()
                loader.ignore_unset_args = False  # Debian's XmlLoader reads it but only load_config_default sets it
                loader.load(launch, config, argv=args, verbose=False)
            else:
                roslaunch.xmlloader.XmlLoader().load_string(text, config, verbose=False)
        except roslaunch.core.RLException as exc:
            out.append([type(exc).__name__, isinstance(exc, roslaunch.xmlloader.XmlParseException)])
    return out


def main(launch: str) -> dict[str, Any]:
    config = roslaunch.config.ROSLaunchConfig()
    roslaunch.xmlloader.XmlLoader().load(launch, config, argv=["robot:=r2", "rate:=7"], verbose=False)
    answer = {"loaded": described(config), "errors": errors(launch)}
    default = roslaunch.config.load_config_default([(launch, ["robot:=r9"])], 11411)
    answer["default"] = {"params": sorted(k for k in default.params if k not in ("/rosversion", "/rosdistro")),
                         "core": [node_row(n) for n in default.nodes_core],
                         "robot": default.params["/robot_name"].value,
                         "port": default.master.get_port(), "tests": len(default.tests)}
    master = roslaunch.core.Master(uri="http://example.invalid:1234/")
    answer["master"] = [master.type, master.get_host(), master.get_port(), master == roslaunch.core.Master(
        uri="http://example.invalid:1234/"), roslaunch.core.Param("a//b", 1).key]
    return answer


if __name__ == "__main__":
    print(json.dumps(main(sys.argv[1])))
