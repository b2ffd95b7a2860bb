"""rqt_graph's data from a live ROS graph: the master's getSystemState and every node's getBusInfo.

The nodes are asked in parallel, each call with a short timeout, and the whole refresh waits
at most `deadline` seconds: a dead node (connection refused) or a hung one (accepts and never
answers) is reported unreachable instead of holding up the picture. The tool does not
register as a node: it only asks.
"""

from __future__ import annotations

from concurrent.futures import Future, ThreadPoolExecutor, wait
from typing import Any

from kame.node.master_proxy import MasterError, MasterProxy
from kame.protocol.xmlrpc import XmlRpcError
from kame.rqt.graph_model import GraphSnapshot, snapshot_from

CALLER_ID = "/rqt_graph"
NODE_TIMEOUT = 1.0


class GraphSource:
    """Owns the worker threads that ask the nodes; `close()` ends them (a call in progress ends by
    its own timeout, so closing takes at most `node_timeout`)."""

    def __init__(self, master_uri: str, node_timeout: float = NODE_TIMEOUT, workers: int = 16,
                 caller_id: str = CALLER_ID) -> None:
        self.master_uri = master_uri
        self.caller_id = caller_id
        self.node_timeout = node_timeout
        self.deadline = 2 * node_timeout + 0.5  # a lookupNode and a getBusInfo, and some slack
        self._pool = ThreadPoolExecutor(max_workers=workers, thread_name_prefix="rqt-graph")

    def fetch(self) -> GraphSnapshot:
        """Raises OSError when the master cannot be reached, MasterError when it refuses."""
        master = MasterProxy(self.master_uri, self.caller_id, timeout=max(self.node_timeout, 3.0))
        try:
            state = master.call("getSystemState")
        except XmlRpcError as exc:
            raise OSError(str(exc)) from exc
        finally:
            master.close()
        nodes = sorted({str(n) for part in state for _, members in part for n in members})
        jobs: dict[str, Future[tuple[str | None, list[Any] | None]]] = {
            node: self._pool.submit(self._ask, node) for node in nodes}
        wait(jobs.values(), timeout=self.deadline)
        uris: dict[str, str] = {}
        bus_info: dict[str, list[Any] | None] = {}
        for node, job in jobs.items():
            uri, info = job.result() if job.done() else (None, None)
            if uri is not None:
                uris[node] = uri
            bus_info[node] = info
        return snapshot_from(state, bus_info, uris)

    def _ask(self, node: str) -> tuple[str | None, list[Any] | None]:
        """The node's URI and its getBusInfo rows; None for what could not be had in time."""
        try:
            master = MasterProxy(self.master_uri, self.caller_id, timeout=self.node_timeout)
            try:
                uri = str(master.call("lookupNode", node))
            finally:
                master.close()
        except (OSError, MasterError, XmlRpcError, ValueError):
            return None, None
        try:
            proxy = MasterProxy(uri, self.caller_id, timeout=self.node_timeout)
        except ValueError:
            return uri, None
        try:
            info = proxy.call("getBusInfo")
            return uri, list(info) if isinstance(info, list) else None
        except (OSError, MasterError, XmlRpcError):
            return uri, None
        finally:
            proxy.close()

    def close(self) -> None:
        self._pool.shutdown(wait=True, cancel_futures=True)
