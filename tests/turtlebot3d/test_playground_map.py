"""amcl_demo's map of the 3-D playground is the world's own: worlds/playground.world's walls, boxes
and cylinders, rasterised cell by cell from the SDF as kame.gazebo reads it, are
worlds/playground.yaml's occupied cells (the map both worlds share, so the lessons' maps look alike)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np

from kame.gazebo.resources import Resources, read_xml
from kame.gazebo.sdf import SdfReader
from kame.stage import mapfile
from tests.support import REPO

WORLDS = REPO / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"


def test_the_shipped_map_is_the_worlds_geometry_seen_from_above() -> None:
    description = WORLDS / "playground.yaml"
    known = mapfile.parse_description(description.read_text())
    image = Path(known.image_path(str(description)))
    grid = mapfile.load(known, image.read_bytes(), image.name)
    rows, columns = grid.cells.shape
    ys, xs = np.mgrid[0:rows, 0:columns].astype(float)
    xs = grid.origin[0] + (xs + 0.5) * grid.resolution  # each cell's centre, row 0 at the map's bottom
    ys = grid.origin[1] + (ys + 0.5) * grid.resolution

    world = SdfReader(Resources()).world(read_xml(str(WORLDS / "playground.world")))
    solid = np.zeros_like(grid.cells, dtype=bool)
    shapes = 0
    for model in world.models:
        for link in model.links:
            for collision in link.collisions:
                x, y, z = model.pose.position
                geometry = collision.geometry
                if geometry.kind == "box":
                    size_x, size_y, height = geometry.size
                    solid |= (abs(xs - x) < size_x / 2) & (abs(ys - y) < size_y / 2)
                elif geometry.kind == "cylinder":
                    radius, height = geometry.size
                    solid |= np.hypot(xs - x, ys - y) < radius
                else:
                    continue
                assert model.static and z - height / 2 < 0.01 and z + height / 2 > 0.5, model.name  # seen by the scan
                shapes += 1
    assert shapes == 12  # four walls, three boxes, five cylinders
    occupied = grid.cells == 100
    differing = solid != occupied
    # only the cylinders' rims may round either way
    assert differing.sum() < 0.005 * solid.size, differing.sum()
    assert math.isclose((solid & occupied).sum() / occupied.sum(), 1.0, abs_tol=0.02)
