"""roslaunch.server's parent node served and called over XML-RPC, and ROSLaunchConfig's machine
assignment, on one JSON request; prints JSON answers. Run by kame's interpreter and by Debian's
/usr/bin/python3 (its real roslaunch)."""

from __future__ import annotations

import io
import json
import os
import sys
import xmlrpc.client
from contextlib import redirect_stderr, redirect_stdout
from typing import Any

import roslaunch.config
import roslaunch.core
import roslaunch.server
from roslaunch.pmon import ProcessListener


class Process:
    def __init__(self, name: str, spawn_count: int) -> None:
        self.name = name
        self.spawn_count = spawn_count

    def get_info(self) -> dict[str, Any]:
        return {"name": self.name, "spawn_count": self.spawn_count, "alive": True}


class Monitor:
    """The three questions the handlers ask of roslaunch's ProcessMonitor."""

    def __init__(self, processes: list[Process]) -> None:
        self.processes = processes

    def get_process_names_with_spawn_count(self) -> list[Any]:
        return [[(p.name, p.spawn_count) for p in self.processes], []]

    def get_process(self, name: str) -> Process | None:
        return next((p for p in self.processes if p.name == name), None)

    def get_active_names(self) -> list[str]:
        return [p.name for p in self.processes]


class Heard(ProcessListener):
    def __init__(self) -> None:
        self.died: list[Any] = []

    def process_died(self, process_name: str, exit_code: int | None) -> None:
        self.died.append([process_name, exit_code])


class Broken(ProcessListener):
    def process_died(self, process_name: str, exit_code: int | None) -> None:
        raise RuntimeError("a listener's bug")


def call(proxy: Any, method: str, args: list[Any]) -> Any:
    try:
        return getattr(proxy, method)(*args)
    except xmlrpc.client.Fault:
        return "Fault"


def served(calls: list[Any]) -> dict[str, Any]:
    heard = Heard()
    node = roslaunch.server.ROSLaunchParentNode(roslaunch.config.ROSLaunchConfig(),
                                                Monitor([Process("talker-1", 2), Process("rosout-1", 1)]))
    node.add_process_listener(Broken())
    node.add_process_listener(heard)
    node.add_child("child-1", roslaunch.server.ChildROSLaunchProcess("child-1", [], {}))
    out, err = io.StringIO(), io.StringIO()
    with redirect_stdout(out), redirect_stderr(err):
        node.start()
        uri = node.uri
        try:
            proxy = xmlrpc.client.ServerProxy(str(node.uri))
            code, msg, pid = proxy.get_pid()
            answers = [[code, msg == str(os.getpid()), pid == os.getpid()]]
            answers += [call(proxy, method, args) for method, args in calls]
        finally:
            node.shutdown("done")
    lines = [line for line in out.getvalue().splitlines() + err.getvalue().splitlines() if "[child-1]" in line]
    return {"answers": answers, "died": heard.died, "logged": lines,
            "announced": f"started roslaunch server {uri}" in out.getvalue(), "after": node.uri}


def assigned(case: dict[str, Any]) -> Any:
    config = roslaunch.config.ROSLaunchConfig()
    for name, address, password in case["machines"]:
        config.add_machine(roslaunch.core.Machine(name, address, password=password), verbose=False)
    nodes = [roslaunch.core.Node("pkg", "type", name=f"n{i}", machine_name=m) for i, m in enumerate(case["nodes"])]
    for node in nodes:
        config.add_node(node, verbose=False)
    test = roslaunch.core.Test("t", "pkg", "type", machine_name=case["test"])
    config.add_test(test, verbose=False)
    try:
        config.has_remote_nodes()
        early = "answered"
    except roslaunch.core.RLException:
        early = "RLException"
    config.assign_machines()
    return [early, [n.machine.name for n in [*nodes, test]], config.has_remote_nodes()]


def run(request: dict[str, Any]) -> dict[str, Any]:
    return {"served": served(request["calls"]), "assigned": [assigned(case) for case in request["configs"]],
            "local": [roslaunch.core.is_machine_local(roslaunch.core.Machine("m", address, user=user))
                      for address, user in request["addresses"]]}


if __name__ == "__main__":
    print(json.dumps(run(json.load(sys.stdin))))
