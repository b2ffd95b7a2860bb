"""actionlib both ways with Debian's python3-actionlib: one peer program (move_base_msgs, which
both sides have) runs as server or client under kame or under /usr/bin/python3, and each client
prints the CommStates, terminal statuses and texts it saw. Real against real (on kame's master)
is the oracle: every pairing must print the same. Every process is stopped by its PID."""

from __future__ import annotations

from collections.abc import Iterator
from pathlib import Path

import pytest

from ..action.graph import ALL_SCENARIOS, EXPECTED, ActionGraph, normalized
from ..action.test_actionlib import check_status_timing, status_timing
from ..support import have_debian_ros

pytestmark = pytest.mark.skipif(not have_debian_ros(), reason="Debian's ROS 1 (rospy, actionlib) is not installed")


@pytest.fixture
def graph(tmp_path: Path) -> Iterator[ActionGraph]:
    g = ActionGraph(tmp_path)
    try:
        yield g
    finally:
        g.stop()


@pytest.mark.parametrize(("real_server", "real_client"), [(False, True), (True, False), (True, True)],
                         ids=["real-client-drives-kame-server", "kame-client-drives-real-server",
                              "real-with-real-oracle"])
def test_status_sequences_match(graph: ActionGraph, real_server: bool, real_client: bool) -> None:
    server = graph.server(real=real_server)
    out, err = graph.client(*ALL_SCENARIOS, real=real_client)
    assert normalized(out) == EXPECTED, err
    served, errors = server.stop()
    assert "Traceback" not in errors and "[ERROR]" not in errors, errors
    assert served.split().count("GOAL") == 10


def test_real_server_status_rate_and_list_timeout_are_kames(tmp_path: Path) -> None:
    check_status_timing(status_timing(tmp_path, real_server=True))


def test_kame_client_sees_a_dying_real_server_lose_its_goal(graph: ActionGraph) -> None:
    server = graph.server(real=True)
    client = graph.start([graph.python(False), str(Path(__file__).parents[1] / "action" / "peers" /
                                                   "move_base_peer.py"), "client", "server_dies"])
    client.wait_line("server-dies-active ACTIVE")
    server.popen.kill()
    words = client.wait_line("server-dies-done", timeout=15).split()
    assert words[1:3] == ["True", "LOST"] and float(words[3]) < 5.0, words
    _, err = client.stop()
    assert err.count("went away") == 1, err
