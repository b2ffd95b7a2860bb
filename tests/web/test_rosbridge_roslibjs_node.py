"""roslibjs (npm roslib, pinned in tests/web/package.json) in Node against rosbridge_websocket.launch:
plain JSON, cbor, cbor-raw and png compressions, throttle_rate with queue_length, fragments
reassembled by roslibjs, rosapi's getTopics, a service call and parameters (rosbridge_roslibjs.mjs)."""

from __future__ import annotations

import json
import struct
import subprocess
from pathlib import Path

import pytest

from tests.web.rosbridge_graph import WEB, bridge_graph, have_node_roslib

pytestmark = [pytest.mark.timeout(240),
              pytest.mark.skipif(not have_node_roslib(), reason="node or tests/web/node_modules missing "
                                 "(scripts/install-web-peers.sh)")]


def test_roslibjs_in_node(tmp_path: Path) -> None:
    with bridge_graph(tmp_path) as graph:
        done = subprocess.run(["node", str(WEB / "rosbridge_roslibjs.mjs"), graph.url], cwd=WEB, capture_output=True,
                              text=True, timeout=180)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    start = {"x": pytest.approx(5.544445, abs=1e-4), "y": pytest.approx(5.544445, abs=1e-4), "theta": 0,
             "linear_velocity": 0, "angular_velocity": 0}
    for compression in ("json", "cbor", "png"):
        assert seen[compression] == start, compression
    raw = bytes(seen["cborRaw"]["bytes"])  # the message as TCPROS carries it: five float32
    assert struct.unpack("<5f", raw)[:2] == (pytest.approx(5.544445, abs=1e-4),) * 2
    assert seen["cborRaw"]["secs"] > 0
    assert seen["cborArrays"] == {"name": ["a", "b"], "position": [1.5, -2.25], "kind": "Float64Array"}
    assert 1 <= seen["throttledCount"] <= 6  # 2 s at one every 500 ms, of ~120 published
    assert seen["fragmented"]["msg"] == "a message long enough to be cut into pieces"
    assert "/turtle1/pose" in seen["topics"]
    assert seen["spawn"] == {"name": "node_turtle"}
    assert seen["param"] == [1, 2, 3]
    assert seen["missingService"] == "Service /no_such_service does not exist"
