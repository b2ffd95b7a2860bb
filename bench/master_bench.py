#!/usr/bin/env python3
"""Master benchmark: Debian's rosmaster against kame's, same client, same run (stdlib only).

For each measurement a fresh master is started on a free loopback port and stopped by its PID
afterwards. The client is deliberately thin so that it measures the master, not itself: "N
clients" are N keep-alive connections, each sending a pre-encoded XML-RPC request as soon as the
previous response (read by Content-Length) is complete, reconnecting when the server closes, as
rosmaster's HTTP/1.0 does. By default the N connections are spread round-robin over
min(N, --procs) worker processes, each driving its connections from one epoll loop, so neither the
GIL nor one process's core bounds the rate; the workers count the calls completed inside one
window common to all of them (CLOCK_MONOTONIC). `--client threads` is the old client (one thread
per connection, all in this process).

  python3 bench/master_bench.py [--window 2] [--client procs|threads] [--procs 2]
                                [--kame-python .venv/bin/python] [--kame-before PYTHON] [--reps N]

Metrics: XML-RPC calls/s for registerPublisher, lookupNode and getSystemState with 1, 10 and 50
concurrent clients, with the master's and the client's CPU time per call; ms to register 100
publishers + 100 subscribers; getSystemState latency (median) on a graph of 1000 topics; a
registration storm: 1,000 nodes start at once, each connects and registers 10 publications and
then 10 subscriptions (topics shared by 100 nodes each, so subscribers get publisher lists back),
ms from the start until the last registration is answered.

  --only PREFIX [--only PREFIX ...]   just the metrics whose label starts with a PREFIX
"""

from __future__ import annotations

import argparse
import multiprocessing
import os
import select
import signal
import socket
import statistics
import subprocess
import sys
import tempfile
import threading
import time
import xmlrpc.client
from pathlib import Path

from bench_procs import cpu_seconds, free_port
from kame_bytecode import compile_kame

REPO = Path(__file__).resolve().parents[1]
NODE_API = "http://127.0.0.1:1/"  # never contacted: no subscriber is ever registered for these topics


class Master:
    def __init__(self, name: str, cmd: list[str]) -> None:
        self.name = name
        self.port = free_port()
        self.home = tempfile.mkdtemp(prefix="master_bench.")
        env = dict(os.environ, ROS_HOME=self.home, ROS_LOG_DIR=self.home, ROS_HOSTNAME="127.0.0.1",
                   ROS_MASTER_URI=f"http://127.0.0.1:{self.port}/")
        self.proc = subprocess.Popen([*cmd, "--core", "-p", str(self.port)], env=env,
                                     stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
        self.uri = f"http://127.0.0.1:{self.port}/"
        deadline = time.monotonic() + 20
        while True:
            try:
                if xmlrpc.client.ServerProxy(self.uri).getPid("/bench")[0] == 1:
                    break
            except OSError:
                pass
            if time.monotonic() > deadline or self.proc.poll() is not None:
                self.stop()
                raise RuntimeError(f"{name} master did not start")
            time.sleep(0.05)

    def stop(self) -> None:
        if self.proc.poll() is None:
            os.kill(self.proc.pid, signal.SIGINT)
            try:
                self.proc.wait(5)
            except subprocess.TimeoutExpired:
                os.kill(self.proc.pid, signal.SIGKILL)
                self.proc.wait()
        subprocess.run(["rm", "-rf", self.home], check=False)


class Client:
    """One keep-alive HTTP connection sending pre-encoded XML-RPC requests."""

    def __init__(self, port: int) -> None:
        self.port = port
        self.sock: socket.socket | None = None
        self.buf = b""

    def _connect(self) -> socket.socket:
        s = socket.create_connection(("127.0.0.1", self.port))
        s.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        self.buf = b""
        return s

    def call(self, request: bytes) -> bytes:
        for attempt in (0, 1):
            if self.sock is None:
                self.sock = self._connect()
            try:
                self.sock.sendall(request)
                return self._response()
            except OSError:
                self.sock.close()
                self.sock = None
                if attempt:
                    raise
        raise AssertionError("unreachable")

    def _response(self) -> bytes:
        assert self.sock is not None
        while b"\r\n\r\n" not in self.buf:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionResetError("closed before the response")
            self.buf += chunk
        head, _, rest = self.buf.partition(b"\r\n\r\n")
        lower = head.lower()
        i = lower.find(b"content-length:")
        length = int(head[i + 15: head.find(b"\r\n", i) if head.find(b"\r\n", i) > 0 else None])
        while len(rest) < length:
            chunk = self.sock.recv(65536)
            if not chunk:
                raise ConnectionResetError("closed inside the response")
            rest += chunk
        body, self.buf = rest[:length], rest[length:]
        if head.startswith(b"HTTP/1.0") or b"connection: close" in lower:
            self.sock.close()
            self.sock = None
        return body


def request(method: str, *params: object) -> bytes:
    body = xmlrpc.client.dumps(params, method).encode()
    return (f"POST / HTTP/1.1\r\nHost: 127.0.0.1\r\nContent-Type: text/xml\r\nContent-Length: {len(body)}\r\n"
            "\r\n").encode() + body


def ok(body: bytes) -> bool:
    return b"<int>1</int>" in body[:160] or b"<i4>1</i4>" in body[:160]


def requests_for(method: str, i: int) -> list[bytes]:
    """The pre-encoded requests client i cycles through."""
    me = f"/bench_rpc_{i}"
    if method == "registerPublisher":
        return [request(method, me, f"/bench_rpc/t{n}", "std_msgs/String", NODE_API) for n in range(100)]
    if method == "lookupNode":
        return [request(method, me, "/bench_node")]
    return [request(method, me)]


def setup_graph(m: Master) -> None:
    if not ok(Client(m.port).call(request("registerPublisher", "/bench_node", "/bench_topic", "std_msgs/String",
                                          NODE_API))):
        raise RuntimeError("setup failed")


def throughput_threads(m: Master, method: str, clients: int, window: float) -> tuple[float, float, float]:
    """The old single-process client (--client threads): one thread per connection, all in this process.

    Returns (calls/s, master CPU us per call, client CPU us per call)."""
    setup_graph(m)
    counts = [0] * clients
    errors: list[str] = []
    start = threading.Barrier(clients + 1)
    stop = threading.Event()

    def run(i: int) -> None:
        c = Client(m.port)
        reqs = requests_for(method, i)
        start.wait()
        n = 0
        try:
            while not stop.is_set():
                if not ok(c.call(reqs[n % len(reqs)])):
                    errors.append(f"{method} failed")
                    return
                n += 1
        except OSError as e:
            errors.append(repr(e))
        counts[i] = n

    workers = [threading.Thread(target=run, args=(i,)) for i in range(clients)]
    for w in workers:
        w.start()
    start.wait()
    t0, cpu0, own0 = time.perf_counter(), cpu_seconds(m.proc.pid), time.process_time()
    time.sleep(window)
    stop.set()
    for w in workers:
        w.join()
    elapsed, cpu = time.perf_counter() - t0, cpu_seconds(m.proc.pid) - cpu0
    own = time.process_time() - own0
    if errors:
        raise RuntimeError(f"{m.name}: {errors[0]}")
    calls = max(sum(counts), 1)
    return sum(counts) / elapsed, cpu / calls * 1e6, own / calls * 1e6


class Conn:
    """One keep-alive connection of a worker process, with one call in flight."""

    __slots__ = ("buf", "n", "reqs", "sock")

    def __init__(self, reqs: list[bytes]) -> None:
        self.sock: socket.socket | None = None
        self.buf = b""
        self.reqs = reqs
        self.n = 0


def worker(port: int, method: str, ids: list[int], pipe) -> None:  # type: ignore[no-untyped-def]
    """One client process: its connections driven by one epoll loop, each sending its next pre-encoded
    request as soon as the previous response is complete.

    Counts the calls completed inside [t0, t1) (CLOCK_MONOTONIC, the same clock in every process) and
    sends back (calls, CPU seconds this process used in that window, error text or "")."""
    ep = select.epoll()
    conns: dict[int, Conn] = {}

    def connect(c: Conn) -> None:
        if c.sock is not None:
            ep.unregister(c.sock.fileno())
            del conns[c.sock.fileno()]
            c.sock.close()
        c.sock = socket.create_connection(("127.0.0.1", port))
        c.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        c.buf = b""
        conns[c.sock.fileno()] = c
        ep.register(c.sock.fileno(), select.EPOLLIN)

    calls, cpu0, cpu1, error = 0, None, None, ""
    try:
        for i in ids:
            connect(Conn(requests_for(method, i)))
        pipe.send("ready")
        t0, t1 = pipe.recv()
        for c in list(conns.values()):
            c.sock.sendall(c.reqs[0])  # type: ignore[union-attr]
        while True:
            events = ep.poll(0.05)
            now = time.monotonic()
            if now >= t1:
                break
            if cpu0 is None and now >= t0:
                cpu0 = time.process_time()
            for fd, _ in events:
                c = conns[fd]
                s = c.sock
                chunk = s.recv(65536)  # type: ignore[union-attr]
                if not chunk:  # closed before answering (keep-alive expiry): reconnect, send again
                    connect(c)
                    c.sock.sendall(c.reqs[c.n % len(c.reqs)])  # type: ignore[union-attr]
                    continue
                buf = c.buf + chunk
                head, sep, rest = buf.partition(b"\r\n\r\n")
                if not sep:
                    c.buf = buf
                    continue
                lower = head.lower()
                i = lower.find(b"content-length:")
                j = head.find(b"\r\n", i)
                length = int(head[i + 15: j if j > 0 else None])
                if len(rest) < length:
                    c.buf = buf
                    continue
                if not ok(rest[:length]):
                    raise RuntimeError(f"{method} failed: {rest[:300]!r}")
                c.buf = rest[length:]
                if now >= t0:
                    calls += 1
                c.n += 1
                if head.startswith(b"HTTP/1.0") or b"connection: close" in lower:
                    connect(c)
                c.sock.sendall(c.reqs[c.n % len(c.reqs)])  # type: ignore[union-attr]
        cpu1 = time.process_time()
    except Exception as e:  # reported to the parent, which raises it
        error = repr(e)
    for c in conns.values():
        c.sock.close()  # type: ignore[union-attr]
    pipe.send((calls, (cpu1 - cpu0) if cpu0 is not None and cpu1 is not None else 0.0, error))


def throughput(m: Master, method: str, clients: int, window: float, procs: int) -> tuple[float, float, float]:
    """The default client: `clients` connections spread round-robin over `procs` worker processes.

    Returns (calls/s, master CPU us per call, client CPU us per call) over one window common to all
    workers."""
    setup_graph(m)
    procs = max(1, min(procs, clients))
    ctx = multiprocessing.get_context("fork")
    pipes, workers = [], []
    try:
        for p in range(procs):
            parent, child = ctx.Pipe()
            w = ctx.Process(target=worker, args=(m.port, method, list(range(p, clients, procs)), child),
                            daemon=True)
            w.start()
            child.close()
            pipes.append(parent)
            workers.append(w)
        for pipe in pipes:
            if not pipe.poll(30) or pipe.recv() != "ready":
                raise RuntimeError(f"{m.name}: a client process did not connect")
        t0 = time.monotonic() + 0.3  # warm-up: every connection is busy before the window opens
        t1 = t0 + window
        for pipe in pipes:
            pipe.send((t0, t1))
        time.sleep(max(0.0, t0 - time.monotonic()))
        cpu0 = cpu_seconds(m.proc.pid)
        time.sleep(max(0.0, t1 - time.monotonic()))
        cpu = cpu_seconds(m.proc.pid) - cpu0
        results = []
        for pipe in pipes:
            if not pipe.poll(30):
                raise RuntimeError(f"{m.name}: a client process did not report")
            results.append(pipe.recv())
    finally:
        for w in workers:
            w.join(5)
            if w.is_alive():
                w.kill()
                w.join()
    errors = [e for _, _, e in results if e]
    if errors:
        raise RuntimeError(f"{m.name}: {errors[0]}")
    calls = sum(n for n, _, _ in results)
    own = sum(c for _, c, _ in results)
    return calls / window, cpu / max(calls, 1) * 1e6, own / max(calls, 1) * 1e6


def register_200(m: Master) -> float:
    c = Client(m.port)
    reqs = [request("registerPublisher", "/graph", f"/graph/pub{i}", "std_msgs/String", NODE_API) for i in range(100)]
    reqs += [request("registerSubscriber", "/graph", f"/graph/sub{i}", "std_msgs/String", NODE_API)
             for i in range(100)]
    t0 = time.perf_counter()
    for r in reqs:
        if not ok(c.call(r)):
            raise RuntimeError("registration failed")
    return (time.perf_counter() - t0) * 1e3


def system_state_latency(m: Master) -> float:
    c = Client(m.port)
    for i in range(1000):
        node = f"/node{i % 50}"
        c.call(request("registerPublisher", node, f"/big/t{i}", "std_msgs/String", NODE_API))
        c.call(request("registerSubscriber", f"/sub{i % 50}", f"/big/t{i}", "std_msgs/String", NODE_API))
    req = request("getSystemState", "/bench")
    times = []
    for _ in range(30):
        t0 = time.perf_counter()
        body = c.call(req)
        times.append((time.perf_counter() - t0) * 1e3)
        if not ok(body):
            raise RuntimeError("getSystemState failed")
    state = xmlrpc.client.loads(body)[0][0][2]
    if len(state[0]) < 1000:
        raise RuntimeError("graph incomplete")
    return statistics.median(times)


def storm_worker(port: int, nodes: list[int], topics: int, pipe) -> None:  # type: ignore[no-untyped-def]
    """One client process of the storm: its nodes, each one connection sending its registrations one
    after the other, all driven by one epoll loop. Sends back (calls answered, error text or "")."""
    ep = select.epoll()
    conns: dict[int, Conn] = {}

    def connect(c: Conn) -> None:
        if c.sock is not None:
            ep.unregister(c.sock.fileno())
            del conns[c.sock.fileno()]
            c.sock.close()
        c.sock = socket.create_connection(("127.0.0.1", port))
        c.sock.setsockopt(socket.IPPROTO_TCP, socket.TCP_NODELAY, 1)
        c.buf = b""
        conns[c.sock.fileno()] = c
        ep.register(c.sock.fileno(), select.EPOLLIN)

    pending = [Conn(storm_requests(i, topics)) for i in nodes]
    calls, error = 0, ""
    try:
        pipe.send("ready")
        pipe.recv()  # go
        for c in pending:
            connect(c)
            c.sock.sendall(c.reqs[0])  # type: ignore[union-attr]
        left = len(pending)
        while left:
            for fd, _ in ep.poll(5.0) or [(None, None)]:
                if fd is None:
                    raise TimeoutError(f"no answer for 5 s, {left} nodes not done")
                c = conns[fd]
                chunk = c.sock.recv(65536)  # type: ignore[union-attr]
                if not chunk:  # closed before answering: reconnect, send again
                    connect(c)
                    c.sock.sendall(c.reqs[c.n])  # type: ignore[union-attr]
                    continue
                buf = c.buf + chunk
                head, sep, rest = buf.partition(b"\r\n\r\n")
                if not sep:
                    c.buf = buf
                    continue
                lower = head.lower()
                i = lower.find(b"content-length:")
                j = head.find(b"\r\n", i)
                length = int(head[i + 15: j if j > 0 else None])
                if len(rest) < length:
                    c.buf = buf
                    continue
                if not ok(rest[:length]):
                    raise RuntimeError(f"registration failed: {rest[:300]!r}")
                c.buf = rest[length:]
                calls += 1
                c.n += 1
                if c.n == len(c.reqs):  # this node is registered: it keeps its connection, quiet
                    left -= 1
                    continue
                if head.startswith(b"HTTP/1.0") or b"connection: close" in lower:
                    connect(c)
                c.sock.sendall(c.reqs[c.n])  # type: ignore[union-attr]
    except Exception as e:  # reported to the parent, which raises it
        error = repr(e)
    pipe.send((calls, error))
    pipe.recv()  # the parent has the time: now the nodes go away
    for c in conns.values():
        c.sock.close()  # type: ignore[union-attr]


STORM_NODES = 1000
STORM_TOPICS = 10
STORM_SHARING = 100  # nodes per topic


def storm_requests(i: int, topics: int) -> list[bytes]:
    node, api = f"/storm/node{i}", f"http://127.0.0.1:1/storm{i}"  # never contacted: see NODE_API
    names = [f"/storm/g{i // STORM_SHARING}/t{t}" for t in range(topics)]
    return ([request("registerPublisher", node, t, "std_msgs/String", api) for t in names]
            + [request("registerSubscriber", node, t + "_in", "std_msgs/String", api) for t in names])


def storm(m: Master, procs: int, nodes: int = STORM_NODES, topics: int = STORM_TOPICS) -> float:
    """ms for `nodes` nodes, started at once over `procs` client processes, to each register `topics`
    publications and `topics` subscriptions; the master's CPU per call as the second value."""
    ctx = multiprocessing.get_context("fork")
    pipes, workers = [], []
    try:
        for p in range(procs):
            parent, child = ctx.Pipe()
            w = ctx.Process(target=storm_worker, args=(m.port, list(range(p, nodes, procs)), topics, child),
                            daemon=True)
            w.start()
            child.close()
            pipes.append(parent)
            workers.append(w)
        for pipe in pipes:
            if not pipe.poll(30) or pipe.recv() != "ready":
                raise RuntimeError(f"{m.name}: a storm client did not start")
        cpu0 = cpu_seconds(m.proc.pid)
        t0 = time.perf_counter()
        for pipe in pipes:
            pipe.send("go")
        results = []
        for pipe in pipes:
            if not pipe.poll(120):
                raise RuntimeError(f"{m.name}: a storm client did not finish")
            results.append(pipe.recv())
        elapsed = time.perf_counter() - t0
        cpu = cpu_seconds(m.proc.pid) - cpu0
        for pipe in pipes:
            pipe.send("done")
    finally:
        for w in workers:
            w.join(10)
            if w.is_alive():
                w.kill()
                w.join()
    errors = [e for _, e in results if e]
    if errors:
        raise RuntimeError(f"{m.name}: {errors[0]}")
    calls = sum(n for n, _ in results)
    if calls != nodes * topics * 2:
        raise RuntimeError(f"{m.name}: {calls} registrations answered, not {nodes * topics * 2}")
    return elapsed * 1e3, cpu / calls * 1e6, 0.0


def main() -> int:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--window", type=float, default=2.0, help="seconds per throughput measurement")
    ap.add_argument("--kame-python", default=str(REPO / ".venv" / "bin" / "python"))
    ap.add_argument("--rosmaster", default="/usr/bin/rosmaster", help="Debian's rosmaster script")
    ap.add_argument("--client", choices=("procs", "threads"), default="procs",
                    help="procs (default): N connections spread over worker processes, an epoll loop each; "
                         "threads: the old client, one thread per connection in this one process")
    ap.add_argument("--procs", type=int, default=os.cpu_count() or 1,
                    help="client worker processes with --client procs (at most N; default: cpu count, %(default)s)")
    ap.add_argument("--only", action="append", default=[], metavar="PREFIX",
                    help="measure only the metrics whose label starts with PREFIX (repeatable)")
    ap.add_argument("--reps", type=int, default=1,
                    help="repetitions of each measurement, the masters taking turns; medians are shown, and "
                         "the spread of kame's ratio to the rosmaster of the same turn")
    ap.add_argument("--kame-before", metavar="PYTHON", default=None,
                    help="also measure kame's master run by this interpreter (e.g. a wrapper putting an older "
                         "tree on PYTHONPATH): a 'before' column")
    args = ap.parse_args()
    compile_kame()
    masters = {"rosmaster": ["/usr/bin/python3", args.rosmaster],
               "kame": [args.kame_python, "-m", "kame.cli.rosmaster"]}
    if args.kame_before:
        masters["before"] = [args.kame_before, "-m", "kame.cli.rosmaster"]
    # label, unit, median per master, [min, max] of each kame column's ratio to rosmaster per turn
    rows: list[tuple[str, str, dict[str, float], dict[str, tuple[float, float]]]] = []

    def measure(label: str, unit: str, fn) -> None:  # type: ignore[no-untyped-def]
        if args.only and not any(label.startswith(prefix) for prefix in args.only):
            return
        runs: list[dict[str, tuple[float, float, float]]] = []
        for _ in range(max(1, args.reps)):
            turn: dict[str, tuple[float, float, float]] = {}
            for name, cmd in masters.items():
                m = Master(name, cmd)
                try:
                    result = fn(m)
                finally:
                    m.stop()
                value, cpu, own = result if isinstance(result, tuple) else (result, 0.0, 0.0)
                turn[name] = (value, cpu, own)
                extra = ""
                if own:
                    extra = " (master %.1f us/call, client %.1f us/call = %.2f cores)" % (cpu, own, own * value / 1e6)
                print(f"  {label} [{name}]: {value:,.1f} {unit}{extra}", file=sys.stderr, flush=True)
            runs.append(turn)
        for index, (row, row_unit) in enumerate(((label, unit), ("  master CPU per call", "us"),
                                                 ("  client CPU per call", "us"))):
            per_turn = [{name: r[index] for name, r in turn.items()} for turn in runs]
            if not all(all(v.values()) for v in per_turn):
                continue  # on a shared machine the client and neighbours take CPU too: the master's own cost
            medians = {name: statistics.median(t[name] for t in per_turn) for name in masters}
            spread = {}
            for name in masters:
                if name != "rosmaster":
                    ratios = [t[name] / t["rosmaster"] for t in per_turn]
                    spread[name] = (min(ratios), max(ratios))
            rows.append((row, row_unit, medians, spread))

    for method in ("registerPublisher", "lookupNode", "getSystemState"):
        for clients in (1, 10, 50):
            def fn(m: Master, method: str = method, clients: int = clients) -> tuple[float, float, float]:
                if args.client == "threads":
                    return throughput_threads(m, method, clients, args.window)
                return throughput(m, method, clients, args.window, args.procs)

            measure(f"{method}, {clients} client{'s' if clients > 1 else ''}", "call/s", fn)
    measure("register 100 pubs + 100 subs", "ms", register_200)
    measure("getSystemState, 1000 topics (median)", "ms", system_state_latency)
    measure(f"storm: {STORM_NODES} nodes x {STORM_TOPICS} pubs + {STORM_TOPICS} subs", "ms",
            lambda m: storm(m, args.procs))

    if args.client == "threads":
        how = "client: --client threads, N threads (one connection each) in this one process"
    else:
        how = (f"client: --client procs, N connections spread over min(N, {args.procs}) worker processes "
               "(epoll loop each, one call in flight per connection)")
    reps = f"median of {args.reps} turns, [min-max] of the per-turn ratio; " if args.reps > 1 else ""
    print(f"window {args.window:g} s; {how}; fresh master per measurement; {reps}ratio = x/rosmaster")
    names = [n for n in masters if n != "rosmaster"]
    print(f"{'metric':<40} {'unit':<7} {'rosmaster':>12} " + " ".join(
        f"{n:>12} {n + '/rosmaster':>22}" for n in names))
    print("-" * (62 + 35 * len(names)))
    for label, unit, v, spread in rows:
        cells = []
        for n in names:
            ratio = v[n] / v["rosmaster"] if v["rosmaster"] else float("nan")
            low, high = spread[n]
            shown = f"{ratio:.2f}x" + (f" [{low:.2f}-{high:.2f}]" if args.reps > 1 else "")
            cells.append(f"{v[n]:>12,.1f} {shown:>22}")
        print(f"{label:<40} {unit:<7} {v['rosmaster']:>12,.1f} " + " ".join(cells))
    return 0


if __name__ == "__main__":
    sys.exit(main())
