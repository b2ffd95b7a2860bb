"""What the graph tools (rosnode, rosparam, rosservice) share: errors, names, the master.

- A failure the user should see is a ToolError: one `ERROR: ...` line on stderr and its exit
  status; `run` turns it (and Ctrl-C) into that, never a traceback.
- Command-line names resolve as rosgraph's script_resolve_name does: global names as typed,
  `~x` under the tool's own name, relative names under ROS_NAMESPACE.
- Every master call goes through Master, which says `Unable to communicate with master!`
  when the master cannot be reached.
"""

from __future__ import annotations

import os
import sys
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import Any

from kame import environ, names
from kame.node.master_proxy import MasterError, MasterProxy
from kame.protocol.xmlrpc import Fault, XmlRpcError

DEFAULT_MASTER_URI = environ.DEFAULT_MASTER_URI
NO_MASTER = "Unable to communicate with master!"


class ToolError(Exception):
    """Reported as `ERROR: <message>` on stderr, exit `status`."""

    def __init__(self, message: str, status: int = 1, prefix: str = "ERROR: ") -> None:
        super().__init__(message)
        self.message = message
        self.status = status
        self.prefix = prefix


def run(main: Callable[[list[str]], int | None], argv: Sequence[str] | None = None) -> int:
    args = list(sys.argv[1:] if argv is None else argv)
    try:
        return main(args) or 0
    except ToolError as exc:
        sys.stdout.flush()
        print(exc.prefix + exc.message, file=sys.stderr)
        return exc.status
    except KeyboardInterrupt:
        return 0
    except BrokenPipeError:
        return 0


def ros_namespace(env: Mapping[str, str] | None = None) -> str:
    return environ.namespace(os.environ if env is None else env)


def script_resolve_name(script: str, name: str, env: Mapping[str, str] | None = None) -> str:
    ns = ros_namespace(env)
    if not name:
        return ns
    if names.is_global(name):
        return name
    if names.is_private(name):
        return names.ns_join(names.make_global_ns(names.ns_join(ns, script)), name[1:])
    return ns + name


def strip_remappings(argv: Sequence[str]) -> list[str]:
    """argv without ROS arguments (`a:=b`), as rospy.myargv gives it."""
    return [arg for arg in argv if ":=" not in arg]


def master_uri(env: Mapping[str, str] | None = None) -> str:
    return environ.master_uri(os.environ if env is None else env)


class Master:
    """The master's API for a tool: MasterError passes through, no master is a ToolError."""

    def __init__(self, caller_id: str, uri: str | None = None, no_master_status: int = 1) -> None:
        self.caller_id = caller_id
        self.uri = uri or master_uri()
        self.no_master_status = no_master_status
        try:
            self._proxy = MasterProxy(self.uri, caller_id, timeout=10.0)
        except ValueError:
            raise ToolError(NO_MASTER, no_master_status) from None

    @property
    def proxy(self) -> MasterProxy:
        return self._proxy

    def call(self, method: str, *args: object) -> Any:
        try:
            return self._proxy.call(method, *args)
        except Fault as exc:  # the master answered: say what it said, not that it cannot be reached
            raise ToolError(f"the master refused {method}: {exc.message}") from None
        except (OSError, XmlRpcError):
            raise ToolError(NO_MASTER, self.no_master_status) from None

    def call_as(self, caller_id: str, method: str, *args: object) -> Any:
        """A call made in another node's name (rosnode cleanup unregisters for the dead)."""
        other = MasterProxy(self.uri, caller_id, timeout=10.0)
        try:
            return other.call(method, *args)
        except OSError:
            raise ToolError(NO_MASTER, self.no_master_status) from None
        finally:
            other.close()

    def lookup_node(self, name: str) -> str | None:
        try:
            return str(self.call("lookupNode", name))
        except MasterError:
            return None

    def system_state(self) -> tuple[list[tuple[str, list[str]]], ...]:
        state = self.call("getSystemState")
        return tuple([(str(entry[0]), [str(n) for n in entry[1]]) for entry in part] for part in state)

    def close(self) -> None:
        self._proxy.close()


@contextmanager
def master(caller_id: str, no_master_status: int = 1) -> Iterator[Master]:
    m = Master(caller_id, no_master_status=no_master_status)
    try:
        yield m
    finally:
        m.close()


def node_names(state: tuple[list[tuple[str, list[str]]], ...], namespace: str | None = None) -> list[str]:
    """Every node named in getSystemState, sorted; within `namespace` if one is given."""
    found: set[str] = set()
    for part in state:
        for _, nodes in part:
            found.update(nodes)
    if namespace:
        prefix = names.make_global_ns(namespace)
        found = {n for n in found if n.startswith(prefix) or n == namespace}
    return sorted(found)
