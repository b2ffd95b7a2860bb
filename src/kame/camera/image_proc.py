"""image_proc's programs: `image_proc` (debayer, then rectify for image_mono and image_color, in
the namespace it runs in: `ROS_NAMESPACE=usb_cam rosrun image_proc image_proc`), and each
nodelet on its own, as `rosrun nodelet nodelet standalone image_proc/rectify` runs it."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from kame.camera.image_proc_nodes import CropDecimateNode, Debayer, Rectify, ResizeNode
from kame.camera.opencv import OpenCVMissing, cv2_for
from kame.client.core import get_name
from kame.client.process import init_node, spin

NODELETS = ("image_proc/debayer", "image_proc/rectify", "image_proc/crop_decimate", "image_proc/resize")


def _opencv(feature: str) -> bool:
    try:
        cv2_for(feature)
    except OpenCVMissing as exc:
        sys.stderr.write(f"{exc}\n")
        return False
    return True


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    if not _opencv("image_proc"):
        return 1
    init_node("image_proc", argv)
    name = get_name()
    nodes = [Debayer("", f"{name}_debayer"), Rectify("image_mono", "image_rect", f"{name}_rectify_mono"),
             Rectify("image_color", "image_rect_color", f"{name}_rectify_color")]
    spin()
    del nodes  # held until spin returns: their subscriptions and servers live as long as they do
    return 0


def run_nodelet(kind: str, node_name: str, argv: list[str]) -> int:
    """One of image_proc's nodelets in this process, its parameters in its private namespace."""
    if not _opencv(kind):
        return 1
    init_node(node_name, argv)
    name = get_name()
    if kind == "image_proc/debayer":
        node: object = Debayer("", name)
    elif kind == "image_proc/rectify":
        node = Rectify("image_mono", "image_rect", name)
    elif kind == "image_proc/crop_decimate":
        node = CropDecimateNode(name)
    else:
        node = ResizeNode(name)
    spin()
    del node  # held until spin returns
    return 0
