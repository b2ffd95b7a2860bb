"""view_frames: listen to /tf and /tf_static for five seconds, then write the frame tree as
frames.gv (graphviz's dot text) and frames.pdf (drawn by kame, no graphviz needed) in the
current folder. `rosrun tf view_frames` writes tf's dot text (allFramesAsDot);
`rosrun tf2_tools view_frames.py` writes tf2_tools' own."""

from __future__ import annotations

import sys
import time
from collections.abc import Sequence
from pathlib import Path
from typing import Any

import yaml

from kame.cli._tf import console, listening_buffer, start_node
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


def _edges(data: dict[str, Any]) -> list[Edge]:
    return [Edge(str(info["parent"]), str(child), (
        f"Broadcaster: {info['broadcaster']}", f"Average rate: {info['rate']}",
        f"Buffer length: {info['buffer_length']}", f"Most recent transform: {info['most_recent_transform']}",
        f"Oldest transform: {info['oldest_transform']}")) for child, info in data.items()]


def _write(dot: str, data: dict[str, Any]) -> None:
    Path("frames.gv").write_text(dot)
    legend = ["view_frames Result", f"Recorded at time: {time.time():.3f}"] if data else ["No tf data received"]
    Path("frames.pdf").write_bytes(render(_edges(data), legend))


def main_tf(argv: Sequence[str] | None = None) -> int:
    """tf's view_frames."""
    heard = _listen(argv, "view_frames")
    if heard is None:
        return 0
    data, dot = heard
    print("Done Listening", flush=True)
    _write(dot, data)
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
    _write(tf2_dot(data, time.time()), data)
    return 0


if __name__ == "__main__":
    sys.exit(main_tf())
