"""map_server and map_saver as a course uses them: serve a map, save it, get the same image back;
a bad map is an error line and status 255, never a traceback."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest
from PIL import Image

from kame.stage.mapfile import load, parse_description
from kame.stage.world import LaserModel, Walls, World
from tests.stage.test_mapfile import huge_png
from tests.turtlesim.sim import master

SHIPPED = Path(__file__).resolve().parents[2] / "src" / "kame" / "share" / "turtlebot_gazebo" / "worlds"


def _write_map(folder: Path) -> np.ndarray:
    pixels = np.full((40, 60), 254, dtype=np.uint8)
    pixels[0, :] = pixels[-1, :] = pixels[:, 0] = pixels[:, -1] = 0
    pixels[10:15, 20:45] = 0
    pixels[30:38, 2:10] = 205
    Image.fromarray(pixels, "L").save(folder / "room.pgm")
    (folder / "room.yaml").write_text("image: room.pgm\nresolution: 0.050000\norigin: [-1.5, -1.0, 0.0]\n"
                                      "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n")
    return pixels


def test_map_saver_reproduces_the_served_map(tmp_path: Path) -> None:
    pixels = _write_map(tmp_path)
    with master(tmp_path / "home") as sim:
        server = sim.start("map_server", "map_server", str(tmp_path / "room.yaml"), wait="Read a 60 X 40 map")
        assert f'Loading map from image "{tmp_path}/room.pgm"' in "".join(server.out)
        assert "@ 0.050 m/cell" in "".join(server.out)
        info = sim.echo("/map_metadata")
        assert (info["width"], info["height"], info["resolution"]) == (60, 40, pytest.approx(0.05))
        assert info["origin"]["position"]["x"] == -1.5
        saved = sim.run("rosrun", "map_server", "map_saver", "-f", str(tmp_path / "copy"))
        out = saved.stdout
        for line in ("Waiting for the map", "Received a 60 X 40 map @ 0.050 m/pix",
                     f"Writing map occupancy data to {tmp_path}/copy.pgm",
                     f"Writing map occupancy data to {tmp_path}/copy.yaml", "Done"):
            assert line in out, out
        again = np.asarray(Image.open(tmp_path / "copy.pgm"))
        assert again.tolist() == pixels.tolist()
        assert (tmp_path / "copy.yaml").read_text() == (
            f"image: {tmp_path}/copy.pgm\nresolution: 0.050000\norigin: [-1.500000, -1.000000, 0.000000]\n"
            "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n\n")
        call = sim.run("rosservice", "call", "/static_map").stdout
        assert "width: 60" in call and "height: 40" in call


# a raw-mode map serves each pixel as its cell's value (255 wraps to -1, unknown): every value
# either side of map_saver's thresholds, the defaults' (65, 25) and the ones given (70, 30)
RAW_CELLS = [0, 10, 25, 26, 30, 31, 50, 64, 65, 69, 70, 100, -1]


def test_map_saver_classifies_cells_by_its_occ_and_free_options(tmp_path: Path) -> None:
    Image.fromarray(np.array([RAW_CELLS], dtype=np.int16).astype(np.uint8), "L").save(tmp_path / "raw.pgm")
    (tmp_path / "raw.yaml").write_text("image: raw.pgm\nresolution: 0.1\norigin: [2.0, -3.0, 0.0]\nnegate: 0\n"
                                       "occupied_thresh: 0.65\nfree_thresh: 0.196\nmode: raw\n")
    with master(tmp_path / "home") as sim:
        sim.start("map_server", "map_server", str(tmp_path / "raw.yaml"), wait="Read a 13 X 1 map")
        assert sim.echo("/map")["data"] == RAW_CELLS
        sim.run("rosrun", "map_server", "map_saver", "--occ", "70", "--free", "30", "-f", str(tmp_path / "given"))
        sim.run("rosrun", "map_server", "map_saver", "-f", str(tmp_path / "default"))
    free, occupied, unknown = 254, 0, 205
    given = np.asarray(Image.open(tmp_path / "given.pgm"))[0].tolist()
    assert dict(zip(RAW_CELLS, given, strict=True)) == {
        0: free, 10: free, 25: free, 26: free, 30: free,  # up to --free, inclusive
        31: unknown, 50: unknown, 64: unknown, 65: unknown, 69: unknown,  # between the two
        70: occupied, 100: occupied,  # from --occ, inclusive
        -1: unknown}
    default = np.asarray(Image.open(tmp_path / "default.pgm"))[0].tolist()
    assert dict(zip(RAW_CELLS, default, strict=True)) == {
        0: free, 10: free, 25: free, 26: unknown, 30: unknown, 31: unknown, 50: unknown, 64: unknown,
        65: occupied, 69: occupied, 70: occupied, 100: occupied, -1: unknown}
    assert (tmp_path / "given.pgm").read_bytes().startswith(b"P5\n# CREATOR: map_saver.cpp 0.100 m/pix\n13 1\n255\n")
    # the YAML names the thresholds map_server should read the image with, whatever --occ and
    # --free were: map_saver writes 0.65 and 0.196 always
    assert (tmp_path / "given.yaml").read_text() == (
        f"image: {tmp_path}/given.pgm\nresolution: 0.100000\norigin: [2.000000, -3.000000, 0.000000]\n"
        "negate: 0\noccupied_thresh: 0.65\nfree_thresh: 0.196\n\n")


def test_bad_maps_are_errors_not_crashes(tmp_path: Path) -> None:
    _write_map(tmp_path)
    (tmp_path / "missing.yaml").write_text((tmp_path / "room.yaml").read_text().replace("room.pgm", "gone.pgm"))
    (tmp_path / "thresholds.yaml").write_text(
        (tmp_path / "room.yaml").read_text().replace("free_thresh: 0.196", "free_thresh: 0.8"))
    (tmp_path / "huge.png").write_bytes(huge_png(100_000, 100_000))
    (tmp_path / "huge.yaml").write_text((tmp_path / "room.yaml").read_text().replace("room.pgm", "huge.png"))
    with master(tmp_path / "home") as sim:
        for name, text in (("missing.yaml", 'Failed to open image file "'),
                           ("huge.yaml", "could be decompression bomb DOS attack"),
                           ("thresholds.yaml", "must be below its occupied_thresh"),
                           ("nothing.yaml", "Map_server could not open")):
            result = sim.run("rosrun", "map_server", "map_server", str(tmp_path / name), check=False)
            assert result.returncode == 255, (name, result.stdout, result.stderr)
            assert text in result.stderr and "Traceback" not in result.stderr, result.stderr
        usage = sim.run("rosrun", "map_server", "map_server", check=False)
        assert usage.returncode == 255 and "USAGE: map_server <map.yaml>" in usage.stderr
        saver = sim.run("rosrun", "map_server", "map_saver", "--occ", "10", "--free", "50", check=False)
        assert saver.returncode == 1 and "must be below --occ" in saver.stderr


def test_the_shipped_worlds_load_and_start_the_robot_in_the_open() -> None:
    names = sorted(p.stem for p in SHIPPED.glob("*.yaml"))
    assert names == ["maze", "office", "playground"]
    for name in names:
        description = parse_description((SHIPPED / f"{name}.yaml").read_text())
        image = description.image_path(str(SHIPPED / f"{name}.yaml"))
        grid = load(description, Path(image).read_bytes(), image)
        world = World(Walls(grid), laser=LaserModel(beams=36, angle_min=-3.1, angle_max=3.1))
        world.spawn("bot", 0.0, 0.0, 0.0)
        assert np.isfinite(world.scans()["bot"]).all(), name  # walled in: every beam meets a wall


def test_without_the_sim_extra_the_programs_say_what_to_install(tmp_path: Path) -> None:
    fake = tmp_path / "no_numpy" / "numpy"
    fake.mkdir(parents=True)
    (fake / "__init__.py").write_text("raise ModuleNotFoundError(\"No module named 'numpy'\", name='numpy')\n")
    with master(tmp_path / "home") as sim:
        env = {**sim.env, "PYTHONPATH": str(fake.parent)}
        for package, program in (("map_server", "map_server"), ("map_server", "map_saver"), ("stage_ros", "stageros")):
            result = sim.run("rosrun", package, program, "x.yaml", check=False, env=env)
            assert result.returncode == 1, result.stderr
            assert f"{program} needs numpy and Pillow, kame's 'sim' extra (pip install 'kame[sim]')" in result.stderr
            assert "Traceback" not in result.stderr


def test_a_16_bit_map(tmp_path: Path) -> None:
    grey = np.array([[0, 65535, 30000]], dtype=np.uint16)
    Image.fromarray(grey).save(tmp_path / "deep.png")
    description = parse_description("image: deep.png\nresolution: 0.1\norigin: [0, 0, 0]\nnegate: 0\n"
                                    "occupied_thresh: 0.65\nfree_thresh: 0.196\n")
    grid = load(description, (tmp_path / "deep.png").read_bytes(), "deep.png")
    assert grid.cells.tolist() == [[100, 0, -1]]
