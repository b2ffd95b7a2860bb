"""view_frames: listen to /tf and /tf_static for five seconds, then write the frame tree as
frames.gv (graphviz's dot text) and frames.pdf (drawn by kame, no graphviz needed) in the
current folder. `rosrun tf view_frames` writes tf's dot text (allFramesAsDot), or with
`--node NAME` the one node NAME's listener serves (NAME/tf_frames, tf/FrameGraph);
`rosrun tf2_tools view_frames.py` writes tf2_tools' own."""

from __future__ import annotations

import re
import struct
import sys
import time
from collections.abc import Sequence
from optparse import OptionParser
from pathlib import Path
from typing import Any

import yaml

from kame.cli._console import console
from kame.cli._node import MASTER_POLL_PERIOD
from kame.cli._tf import listening_buffer, start_node
from kame.msg.catalog import SHARE_DIR, MsgCatalog, find_packages
from kame.node.master_proxy import MasterError
from kame.node.remote_poll import poll_remote
from kame.node.services import ServiceError
from kame.tf.frames_pdf import Edge, render

LISTEN_SECONDS = 5.0


def _listen(argv: Sequence[str] | None, name: str) -> tuple[dict[str, Any], str] | None:
    """(frames as tf2's YAML data, tf's dot text), or None when stopped first."""
    anonymous = name == "view_frames"  # tf's is anonymous; tf2_tools' node is plain 'view_frames'
    tool, _ = start_node(sys.argv[1:] if argv is None else argv, "view_frames", anonymous=anonymous)
    try:
        if not tool.wait_for_master():
            return None
        buffer, _ = listening_buffer(tool)
        if anonymous:
            print(f"Listening to /tf for {LISTEN_SECONDS} seconds", flush=True)
        else:
            console("INFO", "Listening to tf data during 5 seconds...")
        if tool.stop.wait(LISTEN_SECONDS):
            return None
        now = tool.now_ns() / 1e9
        data = yaml.safe_load(buffer.all_frames_as_yaml()) or {}
        return (data if isinstance(data, dict) else {}), buffer.all_frames_as_dot(now)
    finally:
        tool.node.shutdown("view_frames exiting")


def _poll(argv: Sequence[str], node_name: str) -> str | None:
    """tf's dot text as node `node_name` serves it (NAME/tf_frames), waiting for the service to
    appear; None when stopped first or the call fails. The request is empty and the response
    one string, read here: importing tf.srv would load the tf facade into a kame tool."""
    tool, _ = start_node(argv, "view_frames")
    try:
        if not tool.wait_for_master():
            return None
        service = tool.node.resolve(f"{node_name}/tf_frames")
        print(f"Waiting for service {service}", flush=True)

        def registered() -> bool | None:
            try:
                tool.node.master.call("lookupService", service, timeout=2.0)
            except (OSError, MasterError):
                return None
            return True

        if poll_remote(registered, tool.stop.wait, MASTER_POLL_PERIOD) is None:
            return None
        print("Polling service", flush=True)
        md5sum = MsgCatalog(find_packages([SHARE_DIR])).srv_md5sum("tf/FrameGraph")
        try:
            response = tool.node.service_client(service, "tf/FrameGraph", md5sum).call(b"", timeout=10.0)
            (length,) = struct.unpack_from("<I", response)
        except (OSError, ServiceError, struct.error) as exc:
            print(f"Service call failed: {exc}", flush=True)
            return None
        return bytes(response[4:4 + length]).decode("utf-8", "replace")
    finally:
        tool.node.shutdown("view_frames exiting")


_DOT_EDGE = re.compile(r'"(?P<parent>[^"]*)" -> "(?P<child>[^"]*)"\[label="(?P<label>[^"]*)"\];')


def edges_from_dot(dot: str) -> list[Edge]:
    """The edges of tf's allFramesAsDot text, each with its label's lines."""
    return [Edge(match["parent"], match["child"], tuple(line for line in match["label"].split("\\n") if line))
            for match in _DOT_EDGE.finditer(dot)]


def _edges(data: dict[str, Any]) -> list[Edge]:
    return [Edge(str(info["parent"]), str(child), (
        f"Broadcaster: {info['broadcaster']}", f"Average rate: {info['rate']}",
        f"Buffer length: {info['buffer_length']}", f"Most recent transform: {info['most_recent_transform']}",
        f"Oldest transform: {info['oldest_transform']}")) for child, info in data.items()]


def _write(dot: str, edges: list[Edge]) -> None:
    Path("frames.gv").write_text(dot)
    legend = ["view_frames Result", f"Recorded at time: {time.time():.3f}"] if edges else ["No tf data received"]
    Path("frames.pdf").write_bytes(render(edges, legend))


def main_tf(argv: Sequence[str] | None = None) -> int:
    """tf's view_frames [--node NAME]."""
    args = list(sys.argv[1:] if argv is None else argv)
    parser = OptionParser(usage="usage: %prog [options]", prog="viewFrames.py")
    parser.add_option("--node", metavar="node name", type="string", help="Node to get frames from", dest="node")
    options, _ = parser.parse_args([arg for arg in args if ":=" not in arg])
    if options.node:
        print("Generating graph for node: ", options.node, flush=True)
        polled = _poll([arg for arg in args if ":=" in arg], options.node)
        if polled is None:
            return 1
        _write(polled, edges_from_dot(polled))
        print("frames.pdf generated", flush=True)
        return 0
    heard = _listen(argv, "view_frames")
    if heard is None:
        return 0
    data, dot = heard
    print("Done Listening", flush=True)
    _write(dot, _edges(data))
    print("frames.pdf generated", flush=True)
    return 0


def tf2_dot(data: dict[str, Any], now: float) -> str:
    """tf2_tools' generate_dot, text for text."""
    if not data:
        return 'digraph G { "No tf data received" }'
    dot = "digraph G {\n"
    root = ""
    for child, info in data.items():
        dot += f'"{info["parent"]}" -> "{child}"'
        dot += '[label=" '
        dot += f"Broadcaster: {info['broadcaster']}\\n"
        dot += f"Average rate: {info['rate']}\\n"
        dot += f"Buffer length: {info['buffer_length']}\\n"
        dot += f"Most recent transform: {info['most_recent_transform']}\\n"
        dot += f"Oldest transform: {info['oldest_transform']}\\n"
        dot += '"];\n'
        if info["parent"] not in data:
            root = info["parent"]
    dot += "edge [style=invis];\n"
    dot += ' subgraph cluster_legend { style=bold; color=black; label ="view_frames Result";\n'
    dot += f'"Recorded at time: {now}"[ shape=plaintext ] ;\n'
    dot += f'}}->"{root}";\n}}'
    return dot


def main_tf2(argv: Sequence[str] | None = None) -> int:
    """tf2_tools' view_frames.py."""
    heard = _listen(argv, "view_frames_tf2")
    if heard is None:
        return 0
    data, _ = heard
    console("INFO", "Generating graph in frames.pdf file...")
    _write(tf2_dot(data, time.time()), _edges(data))
    return 0


if __name__ == "__main__":
    sys.exit(main_tf())
