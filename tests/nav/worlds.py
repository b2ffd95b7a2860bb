"""The shipped worlds' maps, loaded as stageros and map_server load them, for the navigation tests."""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any

import yaml

from kame.stage import mapfile

WORLDS = Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"


def load_world_map(name: str) -> mapfile.Grid:
    yaml_path = WORLDS / f"{name}.yaml"
    description = mapfile.parse_description(yaml_path.read_text())
    image = Path(description.image_path(str(yaml_path)))
    return mapfile.load(description, image.read_bytes(), image.name)


NAVIGATION = WORLDS.parents[1] / "turtlebot_navigation"


def _flatten(prefix: str, value: Any, into: dict[str, Any]) -> None:
    if isinstance(value, dict):
        for key, inner in value.items():
            _flatten(f"{prefix}/{key}" if prefix else str(key), inner, into)
    else:
        into[prefix] = value


def turtlebot_move_base_params() -> Callable[[str, Any], Any]:
    """move_base's private parameters as turtlebot_navigation's move_base.launch.xml loads them
    (its rosparam files, in its order and namespaces), as a get(name, default)."""
    loads = [("costmap_common_params.yaml", "global_costmap"), ("costmap_common_params.yaml", "local_costmap"),
             ("local_costmap_params.yaml", ""), ("global_costmap_params.yaml", ""),
             ("dwa_local_planner_params.yaml", ""), ("move_base_params.yaml", ""),
             ("global_planner_params.yaml", ""), ("navfn_global_planner_params.yaml", "")]
    params: dict[str, Any] = {}
    for name, namespace in loads:
        _flatten(namespace, yaml.safe_load((NAVIGATION / "param" / name).read_text()), params)
    return lambda name, default: params.get(name, default)
