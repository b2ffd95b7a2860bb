"""`rosrun image_transport republish` in a live graph: a camera's raw images to compressed and back,
the compressed publisher's parameters and dynamic_reconfigure server, encoding only while someone
listens; and with Debian's ROS: its cv_bridge decodes kame's compressed images, kame decodes
its cv_bridge's, and its image_transport republish (raw only: Debian ships no compressed plugin)
relays between kame's nodes."""

from __future__ import annotations

import base64
import json
import sys
from collections.abc import Iterator
from contextlib import contextmanager
from pathlib import Path
from typing import Any

import numpy as np
import pytest

from kame.image_transport.compressed import default_codec, to_array
from sensor_msgs.msg import Image
from tests.support import SYSTEM_PYTHON, Proc
from tests.turtlesim.sim import Sim, master, wait_until

from . import debian
from .image_node import HEIGHT, WIDTH, pattern

NODE = Path(__file__).with_name("image_node.py")
DEBIAN_REPUBLISH = Path("/usr/lib/image_transport/republish")
RGB = np.frombuffer(pattern("rgb8"), np.uint8).reshape(HEIGHT, WIDTH, 3)


def node(sim: Sim, *args: str, python: str = sys.executable) -> Proc:
    proc = Proc([python, str(NODE), *args], sim.env, cwd=sim.home)
    sim.procs.append(proc)
    return proc


def received(sim: Sim, topic: str, type_name: str, python: str = sys.executable, count: int = 1) -> dict[str, Any]:
    """The last of `count` messages on `topic`, as image_node.py's subscriber prints it."""
    sub = node(sim, "sub", topic, type_name, str(count), python=python)
    try:
        sub.popen.wait(60)
    finally:
        out, err = sub.stop()
    assert sub.popen.returncode == 0, out + err
    fields: dict[str, Any] = json.loads(out.splitlines()[-1])
    fields["data"] = base64.b64decode(fields["data"])
    return fields


def pixels(fields: dict[str, Any]) -> np.ndarray:
    return to_array(Image(height=fields["height"], width=fields["width"], encoding=fields["encoding"],
                          step=fields["step"], data=fields["data"]))


def republish(sim: Sim, *args: str) -> Proc:
    return sim.start("image_transport", "republish", *args)


@contextmanager
def camera(tmp_path: Path, encoding: str = "rgb8") -> Iterator[Sim]:
    with master(tmp_path) as sim:
        node(sim, "pub", encoding)
        yield sim


def test_raw_to_compressed_and_back(tmp_path: Path) -> None:
    with camera(tmp_path) as sim:
        republish(sim, "raw", "in:=/camera/image_raw", "compressed", "out:=/camera/image_repub")
        republish(sim, "compressed", "in:=/camera/image_repub", "raw", "out:=/camera/image_back")
        compressed = received(sim, "/camera/image_repub/compressed", "CompressedImage")
        assert compressed["format"] == "rgb8; jpeg compressed bgr8" and compressed["frame_id"] == "camera"
        assert compressed["data"][:2] == b"\xff\xd8"
        back = received(sim, "/camera/image_back", "Image")
        assert (back["encoding"], back["width"], back["height"], back["frame_id"]) == ("rgb8", WIDTH, HEIGHT, "camera")
        assert np.abs(pixels(back).astype(int) - RGB).max() <= 12  # jpeg at quality 80
        topics = sim.run("rostopic", "list").stdout.split()
        assert "/camera/image_repub" not in topics  # only the transport asked for is advertised
        assert "/camera/image_repub/compressed/parameter_descriptions" in topics


def test_the_compressed_publishers_parameters(tmp_path: Path) -> None:
    with camera(tmp_path) as sim:
        sim.run("rosparam", "set", "/camera/image_repub/compressed/format", "png")
        republish(sim, "raw", "in:=/camera/image_raw", "compressed", "out:=/camera/image_repub")
        republish(sim, "compressed", "in:=/camera/image_repub", "raw", "out:=/camera/image_back")
        compressed = received(sim, "/camera/image_repub/compressed", "CompressedImage")
        assert compressed["format"] == "rgb8; png compressed bgr8"
        assert pixels(received(sim, "/camera/image_back", "Image")).tolist() == RGB.tolist()  # png: lossless
        # the reconfigure server wrote the other defaults back, as compressed_image_transport's does
        assert sim.run("rosparam", "get", "/camera/image_repub/compressed/jpeg_quality").stdout.strip() == "80"
        assert sim.run("rosparam", "get", "/camera/image_repub/compressed/png_level").stdout.strip() == "9"
        sim.run("rosrun", "dynamic_reconfigure", "dynparam", "set", "/camera/image_repub/compressed", "format", "jpeg")
        wait_until(lambda: received(sim, "/camera/image_repub/compressed", "CompressedImage")["format"]
                   == "rgb8; jpeg compressed bgr8", timeout=30, what="dynparam's format to take effect")


def test_images_are_encoded_only_for_listeners(tmp_path: Path) -> None:
    """Without an out transport every one is published; an image the compressed transport refuses
    is only an error once someone listens to it, and the raw one flows all along."""
    with camera(tmp_path, "32FC1") as sim:
        relay = republish(sim, "raw", "in:=/camera/image_raw", "out:=/camera/image_repub")
        raw = received(sim, "/camera/image_repub", "Image", count=3)
        assert raw["encoding"] == "32FC1" and raw["data"] == pattern("32FC1")
        assert "compression requires" not in "".join(relay.err)
        listener = node(sim, "sub", "/camera/image_repub/compressed", "CompressedImage")
        wait_until(lambda: "JPEG compression requires 8/16-bit color format (input format is: 32FC1)"
                   in "".join(relay.err), timeout=30, what="republish's error for a 32FC1 image")
        assert listener.popen.poll() is None and "Traceback" not in "".join(relay.err)


def missing(folder: Path, *modules: str) -> str:
    """A folder that, first on PYTHONPATH, makes importing `modules` fail as if they were not installed."""
    for module in modules:
        (folder / module).mkdir(parents=True)
        (folder / module / "__init__.py").write_text(
            f"raise ModuleNotFoundError(\"No module named '{module}'\", name='{module}')\n")
    return str(folder)


def test_bad_arguments(tmp_path: Path) -> None:
    with master(tmp_path) as sim:
        usage = sim.run("rosrun", "image_transport", "republish")
        assert usage.stdout.startswith("Usage: ") and \
            usage.stdout.endswith(" in_transport in:=<in_base_topic> [out_transport] out:=<out_base_topic>\n")
        theora = sim.run("rosrun", "image_transport", "republish", "theora", "in:=a", "out:=b", check=False)
        assert theora.returncode == 1 and "Unable to load plugin for transport 'theora'" in theora.stderr
        no_codec = sim.run("rosrun", "image_transport", "republish", "raw", "in:=a", "compressed", "out:=b",
                           check=False, env={**sim.env, "PYTHONPATH": missing(tmp_path / "no_codec", "cv2", "PIL")})
        assert no_codec.returncode == 1 and "Traceback" not in no_codec.stderr
        assert "the compressed transport needs Pillow or OpenCV: pip install 'kame[image]'" in no_codec.stderr
        no_numpy = sim.run("rosrun", "image_transport", "republish", "raw", "in:=a", "out:=b", check=False,
                           env={**sim.env, "PYTHONPATH": missing(tmp_path / "no_numpy", "numpy")})
        assert no_numpy.returncode == 1 and "Traceback" not in no_numpy.stderr
        assert "republish needs numpy and Pillow (or OpenCV), kame's 'image' extra" in no_numpy.stderr


@pytest.mark.skipif(not debian.has("rospy", "cv_bridge", "cv2"),
                    reason="Debian's cv_bridge and OpenCV (python3-cv-bridge, python3-opencv) are not installed")
def test_debians_cv_bridge_and_kames_compressed_images(tmp_path: Path) -> None:
    with camera(tmp_path) as sim:
        republish(sim, "raw", "in:=/camera/image_raw", "compressed", "out:=/camera/image_repub")
        cvsub = node(sim, "cvsub", "/camera/image_repub/compressed", python=SYSTEM_PYTHON)
        cvsub.popen.wait(60)
        out, err = cvsub.stop()
        assert cvsub.popen.returncode == 0, out + err
        decoded = json.loads(out.splitlines()[-1])
        assert decoded["format"] == "rgb8; jpeg compressed bgr8"
        assert (decoded["shape"], decoded["dtype"]) == ([HEIGHT, WIDTH, 3], "uint8")
        bgr = np.frombuffer(base64.b64decode(decoded["data"]), np.uint8).reshape(HEIGHT, WIDTH, 3)
        assert np.abs(bgr.astype(int) - RGB[..., ::-1]).max() <= 12
    with master(tmp_path / "png") as sim:  # Debian's cv_bridge compresses, kame's republish decodes
        node(sim, "pub-png", python=SYSTEM_PYTHON)
        republish(sim, "compressed", "in:=/camera/image_raw", "raw", "out:=/camera/image_back")
        back = received(sim, "/camera/image_back", "Image")
        assert back["encoding"] == "bgr8" and pixels(back).tolist() == RGB[..., ::-1].tolist()


@pytest.mark.skipif(not DEBIAN_REPUBLISH.exists() or not debian.has("rospy", "sensor_msgs.msg"),
                    reason="Debian's image_transport republish (image-transport-tools) is not installed")
def test_debians_republish_between_kame_nodes(tmp_path: Path) -> None:
    with camera(tmp_path) as sim:
        debian_relay = Proc([str(DEBIAN_REPUBLISH), "raw", "in:=/camera/image_raw", "raw", "out:=/camera/debian"],
                            sim.env, cwd=sim.home)
        sim.procs.append(debian_relay)
        republish(sim, "raw", "in:=/camera/debian", "compressed", "out:=/camera/image_repub")
        compressed = received(sim, "/camera/image_repub/compressed", "CompressedImage", python=SYSTEM_PYTHON)
        assert compressed["format"] == "rgb8; jpeg compressed bgr8"
        image = default_codec().decode(compressed["data"])
        assert image is not None and np.abs(image.astype(int) - RGB[..., ::-1]).max() <= 12
