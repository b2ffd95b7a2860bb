"""nodelet's program for the nodelets kame has (image_proc's, and the TurtleBot's
depthimage_to_laserscan and yocs_cmd_vel_mux): `nodelet standalone
image_proc/rectify`, and `nodelet load image_proc/rectify MANAGER` and `nodelet manager` as
launch files run them. kame's nodelets are Python and run each in its own process: `load` runs
the nodelet where roscpp's would join the manager's process (same topics, names and
parameters; messages go over kame's shared memory, not a pointer), and `manager` is a node that
waits, so the launch files that start one work unchanged."""

from __future__ import annotations

import sys
from collections.abc import Sequence

from kame.camera.image_proc import NODELETS, run_nodelet
from kame.client.process import init_node, myargv, spin
from kame.cmd_vel_mux import node as cmd_vel_mux
from kame.depthimage_to_laserscan import node as depthimage_to_laserscan

# the TurtleBot's nodelets: their nodes' programs, which take the nodelet's name and parameters
NODES = {"depthimage_to_laserscan/DepthImageToLaserScanNodelet": depthimage_to_laserscan.main,
         "yocs_cmd_vel_mux/CmdVelMuxNodelet": cmd_vel_mux.main}

USAGE = """nodelet usage:
nodelet load pkg/Type manager [--no-bond]  - Launch a nodelet of type pkg/Type on manager manager
nodelet standalone pkg/Type   - Launch a nodelet of type pkg/Type in a standalone node
nodelet unload name manager   - Unload a nodelet by name from manager
nodelet manager               - Launch a nodelet manager node
"""


def main(argv: Sequence[str] | None = None) -> int:
    argv = list(sys.argv if argv is None else argv)
    args = myargv(argv)
    command = args[1] if len(args) > 1 else ""
    if command == "manager":
        init_node("nodelet_manager", argv)
        spin()
        return 0
    if command in ("load", "standalone") and len(args) >= 3:
        kind = args[2]
        if kind in NODES:
            return NODES[kind](argv)
        if kind not in NODELETS:
            sys.stderr.write(f"Failed to load nodelet [{kind}]: kame has the nodelets "
                             f"{', '.join((*NODELETS, *NODES))}\n")
            return 255
        return run_nodelet(kind, "nodelet", argv)
    if command == "unload":
        return 0  # each of kame's nodelets is its own process, which ends with its launch
    sys.stderr.write(USAGE)
    return 255
