"""The shipped worlds' maps, loaded as stageros and map_server load them, for the navigation tests."""

from __future__ import annotations

from pathlib import Path

from kame.stage import mapfile

WORLDS = Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"


def load_world_map(name: str) -> mapfile.Grid:
    yaml_path = WORLDS / f"{name}.yaml"
    description = mapfile.parse_description(yaml_path.read_text())
    image = Path(description.image_path(str(yaml_path)))
    return mapfile.load(description, image.read_bytes(), image.name)
