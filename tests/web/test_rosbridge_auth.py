"""rosbridge_websocket.launch authenticate:=true with rosauth's ros_mac_authentication: roslibpy's
and roslibjs's (in Node) authenticate() with a right MAC are served; a wrong MAC, or any op
before auth, closes the connection; the rosauth node on its own answers `rosservice call /authenticate`.

The MACs here are worked out by hand as rosauth's C++ does: the lowercase hex SHA-512 of
secret + client + dest + rand + t.secs + level + end.secs."""

from __future__ import annotations

import hashlib
import json
import subprocess
import sys
import time
from collections.abc import Iterator
from typing import Any

import pytest
from websockets.exceptions import ConnectionClosed
from websockets.sync.client import ClientConnection, connect

from tests.support import Proc, kame_command
from tests.web.rosbridge_graph import WEB, Graph, bridge_graph, have_node_roslib

pytest.importorskip("roslibpy")

pytestmark = pytest.mark.timeout(180)

SECRET = "0123456789abcdef"  # rosauth wants exactly 16 characters


def hand_mac(client: str, dest: str, rand: str, t_secs: int, level: str, end_secs: int) -> str:
    return hashlib.sha512(f"{SECRET}{client}{dest}{rand}{t_secs}{level}{end_secs}".encode()).hexdigest()


@pytest.fixture(scope="module")
def graph(tmp_path_factory: pytest.TempPathFactory) -> Iterator[Graph]:
    home = tmp_path_factory.mktemp("rosauth")
    secret_file = home / "secret"
    secret_file.write_text(SECRET + "\n")
    with bridge_graph(home, "authenticate:=true") as live:
        rosauth = Proc(kame_command("kame.cli.rosrun", "rosauth", "ros_mac_authentication",
                                    f"_secret_file_location:={secret_file}"), live.env)
        try:
            rosauth.wait_line("ROS Authentication Server Started", 60)
            yield live
        finally:
            rosauth.stop()


def auth_op(mac: str | None = None, t: float | None = None, **changes: Any) -> dict[str, Any]:
    now = time.time() if t is None else t
    fields = {"client": "192.168.1.101", "dest": "192.168.1.111", "rand": "xyzzy", "level": "admin"}
    t_time, end_time = {"secs": int(now), "nsecs": 5}, {"secs": int(now) + 3600, "nsecs": 0}
    good = hand_mac(fields["client"], fields["dest"], fields["rand"], t_time["secs"], fields["level"],
                    end_time["secs"])
    return {"op": "auth", "mac": good if mac is None else mac, **fields, "t": t_time, "end": end_time, **changes}


def closed_without_answer(ws: ClientConnection) -> bool:
    try:
        frame = ws.recv(timeout=20)
    except ConnectionClosed:
        return True
    raise AssertionError(f"expected the bridge to close the connection, got {frame!r}")


# roslibpy runs in a process of its own: Twisted's reactor cannot start again once stopped, and a
# second roslibpy client in one process cannot stop it (test_rosbridge_roslibpy has the one here)
ROSLIBPY_CLIENT = """
import json, sys, threading
import roslibpy
port, args = int(sys.argv[1]), json.loads(sys.argv[2])
ros = roslibpy.Ros(host="127.0.0.1", port=port)
ros.authenticate(*args)
ros.run(timeout=20)
got = threading.Event()
poses = []
pose = roslibpy.Topic(ros, "/turtle1/pose", "turtlesim/Pose")
pose.subscribe(lambda msg: (poses.append(msg), got.set()))
print(json.dumps(poses[0] if got.wait(20) else None), flush=True)
ros.terminate()
"""


def test_roslibpy_with_the_right_mac_subscribes_and_receives(graph: Graph) -> None:
    now = time.time()  # roslibpy sends t and end as numbers of seconds, as its docs say
    end = now + 3600
    args = [hand_mac("10.0.0.1", "10.0.0.2", "r4nd", int(now), "user", int(end)), "10.0.0.1", "10.0.0.2", "r4nd",
            now, "user", end]
    done = subprocess.run([sys.executable, "-c", ROSLIBPY_CLIENT, str(graph.port), json.dumps(args)],
                          capture_output=True, text=True, timeout=120)
    assert done.returncode == 0, done.stderr
    pose = json.loads(done.stdout.strip().splitlines()[-1])
    assert pose is not None, "no pose through the authenticated connection"
    assert pose["x"] == pytest.approx(5.544445, abs=1e-4)
    graph.launch.wait_line("has authenticated", 20)


def test_a_wrong_mac_gets_the_connection_closed(graph: Graph) -> None:
    with connect(graph.url) as ws:
        ws.send(json.dumps(auth_op(mac="0" * 128)))
        assert closed_without_answer(ws)


def test_a_stale_t_gets_the_connection_closed_though_its_mac_is_right(graph: Graph) -> None:
    with connect(graph.url) as ws:
        ws.send(json.dumps(auth_op(t=time.time() - 60)))  # rosauth allows 5 s either way
        assert closed_without_answer(ws)


def test_an_op_before_auth_is_refused_and_closes_the_connection(graph: Graph) -> None:
    with connect(graph.url) as ws:
        ws.send(json.dumps({"op": "subscribe", "topic": "/turtle1/pose", "type": "turtlesim/Pose"}))
        assert closed_without_answer(ws)


def test_an_unreadable_auth_is_an_error_then_a_good_one_lets_the_client_in(graph: Graph) -> None:
    with connect(graph.url) as ws:
        broken = auth_op()
        del broken["end"]
        ws.send(json.dumps({**broken, "id": "a1"}))
        status = json.loads(ws.recv(timeout=20))
        assert status["op"] == "status" and status["level"] == "error" and status["id"] == "a1"
        assert "end" in status["msg"]
        ws.send(json.dumps(auth_op()))  # time as {secs, nsecs}, as rosbridge's JSON writes it
        ws.send(json.dumps({"op": "subscribe", "topic": "/turtle1/pose", "type": "turtlesim/Pose"}))
        msg = json.loads(ws.recv(timeout=20))
        assert msg["op"] == "publish" and msg["topic"] == "/turtle1/pose"


def _rosservice_call(graph: Graph, t_secs: int, mac: str) -> str:
    request = {"mac": mac, "client": "c", "dest": "d", "rand": "r", "t": {"secs": t_secs, "nsecs": 0},
               "level": "admin", "end": {"secs": t_secs + 60, "nsecs": 0}}
    done = subprocess.run(kame_command("kame.cli.rosservice", "call", "/authenticate", json.dumps(request)),
                          env=graph.env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 0, done.stderr
    return done.stdout.strip()


def test_the_rosauth_node_answers_rosservice_call(graph: Graph) -> None:
    now = int(time.time())
    assert _rosservice_call(graph, now, hand_mac("c", "d", "r", now, "admin", now + 60)) == "authenticated: True"
    assert _rosservice_call(graph, now, hand_mac("c", "d", "r", now, "user", now + 60)) == "authenticated: False"
    stale = now - 30
    assert _rosservice_call(graph, stale, hand_mac("c", "d", "r", stale, "admin", stale + 60)) == \
        "authenticated: False"


def test_a_secret_of_the_wrong_length_stops_the_node(graph: Graph, tmp_path: Any) -> None:
    short = tmp_path / "short"
    short.write_text("tooshort\n")
    done = subprocess.run(kame_command("kame.cli.rosrun", "rosauth", "ros_mac_authentication",
                                       "__name:=short_secret", f"_secret_file_location:={short}"),
                          env=graph.env, capture_output=True, text=True, timeout=60)
    assert done.returncode == 253  # rosauth's INVALID_SECRET, -3
    assert "Secret string not of length 16." in done.stderr + done.stdout


@pytest.mark.skipif(not have_node_roslib(), reason="node or tests/web/node_modules missing "
                    "(scripts/install-web-peers.sh)")
def test_roslibjs_authenticate_in_node(graph: Graph) -> None:
    now = int(time.time())
    t, end = {"secs": now, "nsecs": 0}, {"secs": now + 600, "nsecs": 0}
    good = [hand_mac("web", "robot", "s33d", now, "admin", now + 600), "web", "robot", "s33d", t, "admin", end]
    bad = [hand_mac("web", "robot", "s33d", now, "admin", now + 600), "web", "robot", "other", t, "admin", end]
    done = subprocess.run(["node", str(WEB / "rosbridge_roslibjs_auth.mjs"), graph.url,
                           json.dumps({"good": good, "bad": bad})], cwd=WEB, capture_output=True, text=True,
                          timeout=120)
    assert done.returncode == 0, done.stderr
    seen = json.loads(done.stdout.strip().splitlines()[-1])
    assert seen["pose"]["x"] == pytest.approx(5.544445, abs=1e-4)
    assert seen["badClosed"] is True
