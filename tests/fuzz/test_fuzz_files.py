"""Properties of the files and messages users hand kame's robot tools: map descriptions and
images (map_server), URDF (robot_state_publisher), .rviz configs and STL meshes (rviz), and the
maps, goals and scans the navigation nodes check. Each is read or refused with the reader's own
error, never anything else; what is read keeps its invariants."""

from __future__ import annotations

import io
import math
import struct
from typing import Any

import numpy as np
import pytest
import yaml
from hypothesis import given
from hypothesis import strategies as st

from kame.nav import inputs
from kame.stage.mapfile import MapError, load, parse_description

_ANY_VALUE = st.recursive(
    st.none() | st.booleans() | st.integers(-10, 300) | st.floats() | st.text(max_size=6),
    lambda inner: st.lists(inner, max_size=4) | st.dictionaries(st.text(max_size=4), inner, max_size=3),
    max_leaves=8)
_MAP_KEYS = ["image", "resolution", "origin", "occupied_thresh", "free_thresh", "negate", "mode"]
_GOOD_MAP = {"image": "m.png", "resolution": 0.05, "origin": [0.0, 0.0, 0.0], "occupied_thresh": 0.65,
             "free_thresh": 0.196, "negate": 0}


@given(changes=st.dictionaries(st.sampled_from(_MAP_KEYS), _ANY_VALUE, max_size=4),
       dropped=st.sets(st.sampled_from(_MAP_KEYS), max_size=2))
def test_a_map_description_is_read_or_refused_with_map_servers_error(changes: dict[str, Any],
                                                                    dropped: set[str]) -> None:
    document = {k: v for k, v in {**_GOOD_MAP, **changes}.items() if k not in dropped}
    try:
        description = parse_description(yaml.safe_dump(document))
    except MapError:
        return
    assert description.resolution > 0 and 0 <= description.free_thresh < description.occupied_thresh <= 1
    assert all(math.isfinite(v) for v in description.origin)


@given(text=st.text(max_size=120))
def test_any_text_is_a_map_description_or_map_servers_error(text: str) -> None:
    try:
        parse_description(text)
    except MapError:
        pass


def _image(mode: str, width: int, height: int, seed: int, kind: str) -> bytes:
    from PIL import Image

    pixels = np.random.default_rng(seed).integers(0, 256, (height, width, len(mode)), dtype=np.uint8)
    image = Image.fromarray(pixels[:, :, 0] if mode == "L" else pixels, mode)
    out = io.BytesIO()
    image.save(out, kind)
    return out.getvalue()


@given(mode=st.sampled_from(["L", "RGB", "RGBA"]), width=st.integers(1, 12), height=st.integers(1, 12),
       seed=st.integers(0, 2**16), kind=st.sampled_from(["PNG", "BMP", "PPM"]),
       map_mode=st.sampled_from(["trinary", "scale", "raw"]), negate=st.booleans())
def test_an_image_becomes_a_grid_of_its_size_with_occupancy_values(mode: str, width: int, height: int, seed: int,
                                                                   kind: str, map_mode: str, negate: bool) -> None:
    if kind == "PPM" and mode == "RGBA":
        mode = "RGB"
    description = parse_description(yaml.safe_dump({**_GOOD_MAP, "mode": map_mode, "negate": int(negate)}))
    grid = load(description, _image(mode, width, height, seed, kind), "m")
    assert grid.cells.shape == (height, width) and grid.cells.dtype == np.int8
    if map_mode != "raw":
        assert set(np.unique(grid.cells)) <= {-1, *range(0, 101)}


@pytest.mark.filterwarnings("ignore::PIL.Image.DecompressionBombWarning")  # a header between 89 and 179 Mpx
@given(image=st.binary(max_size=200), cut=st.integers(0, 80), width=st.integers(0, 2**31 - 1),
       height=st.integers(0, 2**31 - 1))
def test_any_bytes_or_a_lying_header_are_an_image_or_map_servers_error(image: bytes, cut: int, width: int,
                                                                      height: int) -> None:
    description = parse_description(yaml.safe_dump(_GOOD_MAP))
    png = _image("L", 4, 3, 0, "PNG")
    pgm = f"P5\n{width} {height}\n255\n".encode() + image
    for data in (image, png[:cut] + image, pgm):
        try:
            load(description, data, "m")
        except MapError:
            pass


_LINKS = st.lists(st.sampled_from("abcdef"), min_size=1, max_size=6, unique=True)


@given(links=_LINKS, joints=st.lists(st.tuples(st.sampled_from("abcdefg"), st.sampled_from("abcdefg"),
                                              st.sampled_from(["fixed", "revolute", "continuous", "prismatic",
                                                               "floating", "bogus"])), max_size=7))
def test_a_urdf_is_one_tree_or_refused(links: list[str], joints: list[tuple[str, str, str]]) -> None:
    pytest.importorskip("urdf_parser_py")
    from kame.robot.model import RobotTree

    text = "<robot name='r'>" + "".join(f"<link name='{link}'/>" for link in links)
    for n, (parent, child, kind) in enumerate(joints):
        limit = "<limit lower='-1' upper='1' effort='1' velocity='1'/>" if kind in ("revolute", "prismatic") else ""
        text += f"<joint name='j{n}' type='{kind}'><parent link='{parent}'/><child link='{child}'/>{limit}</joint>"
    try:
        tree = RobotTree(text + "</robot>")
    except ValueError:
        return
    parents = {joint.child: joint.parent for joint in tree.joints}
    roots = [link for link in tree.links if link not in parents]
    assert len(roots) == 1  # one root, from which every link hangs: no tf loop is published
    for link in tree.links:
        seen = {link}
        while link in parents:
            link = parents[link]
            assert link not in seen
            seen.add(link)
        assert link == roots[0]


@given(text=st.text(max_size=100) | st.binary(max_size=100).map(lambda b: b.decode("latin-1")))
def test_any_text_is_a_urdf_or_a_value_error(text: str) -> None:
    pytest.importorskip("urdf_parser_py")
    from kame.robot.model import RobotTree

    try:
        RobotTree(text)
    except ValueError:
        pass


_RVIZ_KEYS = st.sampled_from(["Visualization Manager", "Global Options", "Displays", "Views", "Current",
                              "Fixed Frame", "Background Color", "Frame Rate", "Class", "Focal Point",
                              "Distance", "Position", "Window Geometry", "Width", "Height"])
_RVIZ_DOC = st.recursive(
    _ANY_VALUE, lambda inner: st.dictionaries(_RVIZ_KEYS, inner, max_size=4) | st.lists(inner, max_size=3),
    max_leaves=12)


@given(document=st.dictionaries(_RVIZ_KEYS, _RVIZ_DOC, max_size=4))
def test_an_rviz_config_is_read_or_refused_with_a_value_error(document: dict[str, Any]) -> None:
    from kame.rviz import config

    try:
        parsed = config.parse(yaml.safe_dump(document))
    except ValueError:
        return
    config.window_size(parsed)
    assert config.parse(config.dump(parsed)).fixed_frame == parsed.fixed_frame  # what it writes, it reads


@given(text=st.text(max_size=120))
def test_any_text_is_an_rviz_config_or_a_value_error(text: str) -> None:
    from kame.rviz import config

    try:
        config.parse(text)
    except ValueError:
        pass


@given(data=st.binary(max_size=300), count=st.integers(0, 2**32 - 1), solid=st.booleans())
def test_any_stl_bytes_are_a_mesh_or_a_value_error(data: bytes, count: int, solid: bool) -> None:
    pytest.importorskip("trimesh")
    from kame.rviz.meshes import read_mesh

    header = (b"solid x" if solid else b"").ljust(80, b"\0")
    for stl in (data, header + struct.pack("<I", count) + data, b"solid x\n" + data + b"\nendsolid x\n"):
        try:
            mesh = read_mesh(stl, "stl")
        except ValueError:
            continue
        assert mesh.triangles.shape[1:] == (3,) and len(mesh.triangles) % 3 == 0


_NUMBER = st.floats() | st.integers(-5, 5).map(float)


@given(width=st.integers(0, 5), height=st.integers(0, 5), cells=st.integers(0, 30), resolution=_NUMBER,
       x=_NUMBER, y=_NUMBER)
def test_the_navigation_checks_of_a_map_answer_without_raising(width: int, height: int, cells: int,
                                                               resolution: float, x: float, y: float) -> None:
    from nav_msgs.msg import MapMetaData

    meta = MapMetaData(width=width, height=height, resolution=resolution)
    meta.origin.position.x, meta.origin.position.y = x, y
    problem = inputs.map_problem(meta, cells)
    usable = width * height == cells > 0 and resolution > 0 and all(math.isfinite(v) for v in (resolution, x, y))
    assert (problem is None) == usable


@given(values=st.lists(_NUMBER, min_size=7, max_size=7))
def test_the_navigation_checks_of_a_pose_answer_without_raising(values: list[float]) -> None:
    from geometry_msgs.msg import Pose

    pose = Pose()
    p, q = pose.position, pose.orientation
    p.x, p.y, p.z, q.x, q.y, q.z, q.w = values
    if inputs.pose_problem(pose) is None:  # a goal the planner may take: finite, turning about z only
        assert all(math.isfinite(v) for v in values)
        length = math.hypot(q.x, q.y, q.z, q.w)
        assert math.hypot(q.x / length, q.y / length) ** 2 < 1e-3
