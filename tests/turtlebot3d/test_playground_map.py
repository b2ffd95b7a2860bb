"""amcl_demo's map of the 3-D playground is the world's own: worlds/playground.world's walls, boxes
and cylinders, rasterised cell by cell from the SDF, are worlds/playground.yaml's occupied cells
(the map both worlds share, so the lessons' maps look alike). The SDF is read with ElementTree, not
kame.gazebo, whose MuJoCo import would set PYOPENGL_PLATFORM for every later test's children."""

from __future__ import annotations

import math
import xml.etree.ElementTree as ElementTree
from pathlib import Path

import numpy as np

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

    world = ElementTree.parse(WORLDS / "playground.world").getroot().find("world")
    assert world is not None
    solid = np.zeros_like(grid.cells, dtype=bool)
    shapes = 0
    for model in world.iter("model"):
        x, y, z = (float(v) for v in model.findtext("pose", "").split()[:3])
        box, cylinder = model.find("link/collision/geometry/box"), model.find("link/collision/geometry/cylinder")
        if box is not None:
            size_x, size_y, height = (float(v) for v in box.findtext("size", "").split())
            solid |= (abs(xs - x) < size_x / 2) & (abs(ys - y) < size_y / 2)
        elif cylinder is not None:
            radius, height = float(cylinder.findtext("radius", "")), float(cylinder.findtext("length", ""))
            solid |= np.hypot(xs - x, ys - y) < radius
        else:
            continue
        assert model.findtext("static") == "true", model.get("name")
        assert z - height / 2 < 0.01 and z + height / 2 > 0.5, model.get("name")  # standing, and seen by the scan
        shapes += 1
    assert shapes == 12  # four walls, three boxes, five cylinders
    occupied = grid.cells == 100
    differing = solid != occupied
    # only the cylinders' rims may round either way
    assert differing.sum() < 0.005 * solid.size, differing.sum()
    assert math.isclose((solid & occupied).sum() / occupied.sum(), 1.0, abs_tol=0.02)
