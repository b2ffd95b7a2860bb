"""A kame master for the module's tests, and Nodes made on it that the test's end shuts down."""

from __future__ import annotations

from collections.abc import Callable, Iterator
from pathlib import Path

import pytest

from kame.node.node import Node, NodeConfig

from ..support import Proc, free_port, kame_command, ros_env, wait_for_master


@pytest.fixture(scope="module")
def master_uri(tmp_path_factory: pytest.TempPathFactory) -> Iterator[str]:
    home = tmp_path_factory.mktemp("master")
    port = free_port()
    uri = f"http://127.0.0.1:{port}/"
    proc = Proc(kame_command("kame.cli.rosmaster", "--core", "-p", str(port)), ros_env(Path(home), uri))
    try:
        wait_for_master(uri, proc=proc)
        yield uri
    finally:
        proc.stop()


@pytest.fixture
def make_node(master_uri: str) -> Iterator[Callable[[str], Node]]:
    nodes: list[Node] = []

    def make(name: str) -> Node:
        node = Node(NodeConfig(name, master_uri, "127.0.0.1"))
        nodes.append(node)
        return node

    yield make
    for node in nodes:
        node.shutdown("test over")
