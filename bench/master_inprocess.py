#!/usr/bin/env python3
"""The master's per-request CPU in its own process, without sockets or event loop.

Feeds pre-encoded HTTP requests straight to the master's connection protocol (a transport that
drops what is written), with the rosmaster process's file logging set up as `rosmaster` sets it,
and prints the CPU microseconds per request (best of --reps): HTTP parse, XML-RPC decode, the
registry, encode, the per-change log line and the connection's bookkeeping. What this leaves out
(epoll, recv, send, the event loop) is the same for every version, so two versions compare here
with far less noise than master_bench.py gives on a busy machine:

  .venv/bin/python bench/master_inprocess.py [--calls 10000] [--reps 5]
  PYTHONPATH=OLD_TREE/src .venv/bin/python bench/master_inprocess.py   # an older tree
"""

from __future__ import annotations

import argparse
import asyncio
import logging
import tempfile
import time
from pathlib import Path

from kame.cli import rosmaster
from kame.master.server import MasterServer
from kame.net.http_server import _Connection
from kame.protocol.http import RequestReader

from master_bench import NODE_API, request


class _Sink(asyncio.Transport):
    def write(self, data: bytes | bytearray | memoryview) -> None:
        pass

    def get_extra_info(self, name: str, default: object = None) -> object:
        return ("127.0.0.1", 1) if name == "peername" else default

    def is_closing(self) -> bool:
        return False

    def close(self) -> None:
        pass

    def abort(self) -> None:
        pass


async def measure(calls: int, reps: int) -> dict[str, float]:
    with tempfile.TemporaryDirectory(prefix="master_inprocess.") as home:
        handler = rosmaster.setup_file_logging(Path(home) / "master.log")
        logging._srcfile = None  # as rosmaster's main sets it
        server = MasterServer("127.0.0.1", 0, "127.0.0.1")
        await server.start()
        assert server.api is not None
        conn = _Connection(server.http, RequestReader(heads=server.http._heads))
        conn.connection_made(_Sink())
        server.api.call("registerPublisher", ["/bench_node", "/bench_topic", "std_msgs/String", NODE_API])
        workloads = {
            "registerPublisher": [request("registerPublisher", "/bench_rpc", f"/bench_rpc/t{n}", "std_msgs/String",
                                          NODE_API) for n in range(100)],
            "lookupNode": [request("lookupNode", "/bench_rpc", "/bench_node")],
        }
        best: dict[str, float] = {}
        for method, reqs in workloads.items():
            for i in range(1000):  # warm-up: the topics exist, the head cache is filled
                conn.data_received(reqs[i % len(reqs)])
            for _ in range(reps):
                start = time.process_time()
                for i in range(calls):
                    conn.data_received(reqs[i % len(reqs)])
                handler.flush()
                used = (time.process_time() - start) / calls * 1e6
                best[method] = min(best.get(method, used), used)
        await server.close()
        handler.close()
    return best


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--calls", type=int, default=10000)
    ap.add_argument("--reps", type=int, default=5)
    args = ap.parse_args()
    for method, us in asyncio.run(measure(args.calls, args.reps)).items():
        print(f"{method:<20} {us:6.2f} us CPU per request (best of {args.reps})")


if __name__ == "__main__":
    main()
