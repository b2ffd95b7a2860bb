"""Gazebo's material scripts (media/materials/scripts/gazebo.material) by name, as the diffuse
colour each one draws with. Textured ones (wood, grass, the checker) are their main colour:
kame draws colours, not textures. An unknown name is drawn grey, as Gazebo draws a missing script.
"""

from __future__ import annotations

from kame.gazebo.description import GRAY, Color

SCRIPT_COLORS: dict[str, Color] = {
    "Gazebo/Grey": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/Gray": (0.7, 0.7, 0.7, 1.0),
    "Gazebo/DarkGrey": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/DarkGray": (0.175, 0.175, 0.175, 1.0),
    "Gazebo/White": (1.0, 1.0, 1.0, 1.0),
    "Gazebo/FlatBlack": (0.1, 0.1, 0.1, 1.0),
    "Gazebo/Black": (0.0, 0.0, 0.0, 1.0),
    "Gazebo/Red": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/RedBright": (0.87, 0.26, 0.07, 1.0),
    "Gazebo/Green": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/Blue": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/SkyBlue": (0.53, 0.81, 0.92, 1.0),
    "Gazebo/Yellow": (1.0, 1.0, 0.0, 1.0),
    "Gazebo/ZincYellow": (0.9725, 0.9529, 0.2078, 1.0),
    "Gazebo/DarkYellow": (0.7, 0.7, 0.0, 1.0),
    "Gazebo/Purple": (1.0, 0.0, 1.0, 1.0),
    "Gazebo/Turquoise": (0.0, 1.0, 1.0, 1.0),
    "Gazebo/Orange": (1.0, 0.5088, 0.0468, 1.0),
    "Gazebo/Indigo": (0.33, 0.0, 0.5, 1.0),
    "Gazebo/Gold": (0.8, 0.64, 0.2, 1.0),
    "Gazebo/Wood": (0.56, 0.42, 0.28, 1.0),
    "Gazebo/WoodFloor": (0.56, 0.42, 0.28, 1.0),
    "Gazebo/Grass": (0.34, 0.55, 0.21, 1.0),
    "Gazebo/Bricks": (0.62, 0.32, 0.24, 1.0),
    "Gazebo/CeilingTiled": (0.9, 0.9, 0.9, 1.0),
    "Gazebo/PaintedWall": (0.9, 0.9, 0.85, 1.0),
    "Gazebo/Road": (0.3, 0.3, 0.3, 1.0),
    "Gazebo/Residential": (0.6, 0.6, 0.6, 1.0),
    "Gazebo/Asphalt": (0.25, 0.25, 0.25, 1.0),
    "Gazebo/GreyTransparent": (0.5, 0.5, 0.5, 0.5),
    "Gazebo/RedTransparent": (1.0, 0.0, 0.0, 0.5),
    "Gazebo/GreenTransparent": (0.0, 1.0, 0.0, 0.5),
    "Gazebo/BlueTransparent": (0.0, 0.0, 1.0, 0.5),
    "Gazebo/BlueGlow": (0.0, 0.0, 1.0, 1.0),
    "Gazebo/GreenGlow": (0.0, 1.0, 0.0, 1.0),
    "Gazebo/RedGlow": (1.0, 0.0, 0.0, 1.0),
    "Gazebo/Chrome": (0.8, 0.8, 0.8, 1.0),
    "Gazebo/Trunk": (0.4, 0.3, 0.2, 1.0),
    "Gazebo/Leaf": (0.2, 0.6, 0.2, 1.0),
    "Gazebo/CloudySky": (0.6, 0.7, 0.8, 1.0),
}


def script_color(name: str) -> Color:
    return SCRIPT_COLORS.get(name.strip(), GRAY)
