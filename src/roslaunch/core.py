"""roslaunch.core: the launch model's values as roslaunch names them: Node (a node to launch,
kame.launch.scripting), Test, Param, Machine, Master, RLException."""

from __future__ import annotations

from typing import Any

import rosgraph
from kame.launch.runner import machine_is_local
from kame.launch.scripting import Node, RLException
from rosgraph.network import parse_http_host_and_port

__all__ = ["Machine", "Master", "Node", "Param", "RLException", "Test", "is_machine_local"]


def is_machine_local(machine: Machine) -> bool:
    """True when `machine`'s nodes run on this host: its address is this host's and it names no
    other user (another user on this host is reached over SSH)."""
    return machine_is_local(machine.address, machine.user)


class Param:
    """A parameter to set: its global key and value."""

    def __init__(self, key: str, value: Any) -> None:
        self.key = rosgraph.names.canonicalize_name(key)
        self.value = value

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Param) and (other.key, other.value) == (self.key, self.value)

    def __hash__(self) -> int:
        return hash(self.key)

    def __repr__(self) -> str:
        return f"{self.key}={self.value}"

    __str__ = __repr__


class Test(Node):
    """A <test>: a node rostest runs, with its name, time limit and retries."""

    def __init__(self, test_name: str, package: str, node_type: str, name: str | None = None, namespace: str = "/",
                 machine_name: str | None = None, args: str = "", remap_args: list[tuple[str, str]] | None = None,
                 env_args: list[tuple[str, str]] | None = None, time_limit: float | None = None,
                 cwd: str | None = None, launch_prefix: str | None = None, retry: int | None = None,
                 filename: str = "<unknown>") -> None:
        super().__init__(package, node_type, name=name or test_name, namespace=namespace, machine_name=machine_name,
                         args=args, remap_args=remap_args, env_args=env_args, output="log", cwd=cwd,
                         launch_prefix=launch_prefix, filename=filename)
        self.test_name = test_name
        self.time_limit = 60.0 if time_limit is None else time_limit
        self.retry = retry or 0


class Machine:
    """A <machine>: where nodes assigned to it run."""

    def __init__(self, name: str, address: str, env_loader: str | None = None, ssh_port: int = 22,
                 user: str | None = None, password: str | None = None, assignable: bool = True,
                 env_args: list[tuple[str, str]] | None = None, timeout: float | None = None) -> None:
        self.name = name
        self.address = address
        self.env_loader = env_loader
        self.ssh_port = ssh_port
        self.user = user
        self.password = password
        self.assignable = assignable
        self.env_args = list(env_args or [])
        self.timeout = timeout

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Machine) and self.config_key() == other.config_key() and self.name == other.name

    def __hash__(self) -> int:
        return hash(self.config_key())

    def config_key(self) -> str:
        """What makes two machines the same place to run (not their names), as roslaunch writes it."""
        return (f"Machine(address[{self.address}] env_loader[{self.env_loader}] ssh_port[{self.ssh_port}] "
                f"user[{self.user or ''}] password[{self.password or ''}] timeout[{self.timeout}])")

    def __repr__(self) -> str:
        return f"[{self.name}] <user>{self.user}</user><address>{self.address}</address>"


class Master:
    """The master a launch uses: its kind and URI (ROS_MASTER_URI unless given)."""

    ROSMASTER = "rosmaster"
    ZENMASTER = "zenmaster"

    def __init__(self, type_: str | None = None, uri: str | None = None, auto: int | None = None) -> None:
        self.auto = None  # no longer used, as in roslaunch
        self.type = type_ or Master.ROSMASTER
        self.uri = uri or rosgraph.get_master_uri()

    def get_host(self) -> str:
        return parse_http_host_and_port(self.uri)[0]

    def get_port(self) -> int:
        return parse_http_host_and_port(self.uri)[1]

    def get(self) -> rosgraph.Master:
        """A handle on the master (rosgraph.Master, calling as /roslaunch)."""
        return rosgraph.Master("/roslaunch", master_uri=self.uri)

    def is_running(self) -> bool:
        return rosgraph.is_master_online(self.uri)

    def __eq__(self, other: object) -> bool:
        return isinstance(other, Master) and (other.type, other.uri) == (self.type, self.uri)

    def __hash__(self) -> int:
        return hash((self.type, self.uri))
