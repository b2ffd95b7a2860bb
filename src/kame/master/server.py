"""The master on the network: XML-RPC over kame.net's HTTP server, notifications sent behind.

Rules:
- Calls are served inline on the event loop by the pure core (`MasterApi`): registration never
  waits for any node.
- Notifications (publisherUpdate, paramUpdate, shutdown) go out asynchronously. Calls to one
  node URI are serialised, different URIs proceed independently, and each call has a timeout,
  so a dead or slow node delays only its own notifications. Pending notifications to one URI
  are coalesced by (method, topic or key): both carry complete state, so only the newest one
  matters, and the queue for a URI never grows beyond the number of topics and keys.
- Bodies are encoded when the change happens, not when sent: parameter values are live parts of
  the tree and could change before the send.
- Errors in requests answer as rosmaster does: a fault with code 1 and `<class ...>:message`.
"""

from __future__ import annotations

import asyncio
import logging
import os
import time

from kame.master.api import CallResult, MasterApi
from kame.master.notifications import Notification
from kame.net.address import uri_host
from kame.net.http_server import HttpRequest, HttpResponse, HttpServer, ServerLimits
from kame.net.xmlrpc_client import post
from kame.protocol.xmlrpc import (
    Fault,
    MalformedError,
    Value,
    decode_request,
    decode_response,
    encode_fault,
    encode_request,
    encode_response,
)

log = logging.getLogger("kame.master")

RPC_PATHS = ("/", "/RPC2")
NOTIFY_TIMEOUT = 10.0
_READ_ONLY = frozenset({"getUri", "getPid", "getParam", "hasParam", "getParamNames", "searchParam",
                        "lookupService", "lookupNode", "getPublishedTopics", "getTopicTypes", "getSystemState"})


_CHANGE = "%s %s -> %s"
_change_template: dict[str, object] = {}


def _log_change(method: str, params: list[Value], value: object) -> None:
    """`log.info(_CHANGE, method, params, value)`, the line logged per change, a microsecond
    cheaper: the record is a copy of one the logger made itself, with this call's arguments and
    time. Only where records name no source line (the rosmaster process turns that lookup off)
    and come from logging's own factory; elsewhere it is `log.info`."""
    if not log.isEnabledFor(logging.INFO):  # log.handle below does not look at levels
        return
    if logging._srcfile is not None or logging.getLogRecordFactory() is not logging.LogRecord:
        log.info(_CHANGE, method, params, value)
        return
    if not _change_template:
        _change_template.update(log.makeRecord(log.name, logging.INFO, "(unknown file)", 0, _CHANGE, (), None,
                                               "(unknown function)").__dict__)
    fields = _change_template.copy()
    now = time.time()  # the time fields as LogRecord sets them
    fields["args"] = (method, params, value)
    fields["created"] = now
    fields["msecs"] = int((now - int(now)) * 1000) + 0.0
    fields["relativeCreated"] = (now - logging._startTime) * 1000  # type: ignore[attr-defined]
    record = logging.LogRecord.__new__(logging.LogRecord)
    record.__dict__ = fields
    log.handle(record)


class Notifier:
    """Sends notifications to node URIs: serialised per URI, concurrent across URIs, with timeouts."""

    def __init__(self, timeout: float = NOTIFY_TIMEOUT, max_in_flight: int = 256) -> None:
        self.timeout = timeout
        self._pending: dict[str, dict[tuple[str, str], bytes]] = {}
        self._workers: dict[str, asyncio.Task[None]] = {}
        self._slots = asyncio.Semaphore(max_in_flight)  # bounds open sockets to nodes

    def send(self, note: Notification) -> None:
        method, params = note.call
        what = "" if method == "shutdown" else str(params[1])
        queue = self._pending.setdefault(note.node_api, {})
        queue.pop((method, what), None)
        queue[(method, what)] = encode_request(method, params)
        if note.node_api not in self._workers:
            self._workers[note.node_api] = asyncio.get_running_loop().create_task(self._drain(note.node_api))

    @property
    def busy(self) -> int:
        """Number of node URIs with notifications under way."""
        return len(self._workers)

    async def _drain(self, api: str) -> None:
        queue = self._pending[api]
        loop = asyncio.get_running_loop()
        try:
            while queue:
                (method, what), body = next(iter(queue.items()))
                del queue[(method, what)]
                start = loop.time()
                async with self._slots:
                    try:
                        outcome = f"result={decode_response(await post(api, body, self.timeout))!r}"
                    except Exception as e:  # a node's failure is logged, never ours to raise
                        outcome = f"exception={type(e).__name__}: {e}"
                log.info("%s[%s] -> %s: sec=%0.2f, %s", method, what, api, loop.time() - start, outcome)
        finally:
            del self._pending[api]
            del self._workers[api]

    async def close(self) -> None:
        tasks = list(self._workers.values())
        for t in tasks:
            t.cancel()
        await asyncio.gather(*tasks, return_exceptions=True)


class MasterServer:
    """A master serving on (host, port); `uri` is what it advertises, built from `advertise`."""

    def __init__(self, host: str, port: int, advertise: str, limits: ServerLimits | None = None,
                 notify_timeout: float = NOTIFY_TIMEOUT) -> None:
        self._http = HttpServer(self.handle, host, port, limits)
        self._advertise = advertise
        self._notify_timeout = notify_timeout
        self._stopped: asyncio.Event | None = None
        self.notifier: Notifier | None = None
        self.api: MasterApi | None = None

    @property
    def port(self) -> int:
        return self._http.port

    @property
    def http(self) -> HttpServer:
        return self._http

    async def start(self) -> str:
        """Bind and start serving; returns the master URI."""
        self._stopped = asyncio.Event()
        self.notifier = Notifier(self._notify_timeout)
        port = await self._http.start()
        uri = f"http://{uri_host(self._advertise)}:{port}/"
        self.api = MasterApi(uri, os.getpid())
        log.info("Master initialized: port[%d], uri[%s]", port, uri)
        return uri

    async def wait_shutdown(self) -> None:
        """Returns when a client called shutdown."""
        assert self._stopped is not None
        await self._stopped.wait()

    async def close(self) -> None:
        await self._http.close()
        if self.notifier is not None:
            await self.notifier.close()

    def handle(self, request: HttpRequest) -> HttpResponse:
        if request.method != "POST":
            return HttpResponse(501, f"Unsupported method ({request.method!r})".encode(), "text/plain")
        if request.path not in RPC_PATHS:
            return HttpResponse(404, b"", "text/plain")
        return HttpResponse(200, self._xmlrpc(request))

    def _xmlrpc(self, request: HttpRequest) -> bytes:
        assert self.api is not None and self.notifier is not None and self._stopped is not None
        try:
            method, params = decode_request(request.body)
        except MalformedError as e:
            log.warning("malformed XML-RPC request from %s: %s", request.peer, e)
            return encode_fault(1, f"{type(e.__cause__ or e)}:{e}")
        try:
            result = self.api.call(method, params)
        except Fault as f:
            log.warning("%s from %s: %s", method, request.peer, f.message)
            return encode_fault(f.code, f.message)
        try:
            body = encode_response(result.value)
        except (OverflowError, TypeError) as e:
            # e.g. a parameter stored from an <i8> that does not fit the 32-bit <int> we write
            log.error("cannot encode the answer to %s: %s", method, e)
            return encode_fault(1, f"{type(e)}:{e}")
        self._after(method, params, result)
        return body

    def _after(self, method: str, params: list[Value], result: CallResult) -> None:
        assert self.notifier is not None and self._stopped is not None
        if result.failure:
            log.error("%s%s failed:\n%s", method, tuple(params), result.failure)
        if method not in _READ_ONLY and log.isEnabledFor(logging.INFO):
            value = result.value
            _log_change(method, params[:3], value[:2] if isinstance(value, list) else value)
        for note in result.notifications:
            self.notifier.send(note)
        if result.shutdown is not None:
            message = params[1] if len(params) > 1 else ""
            # rosmaster's words, typo included
            print(f"shutdown request: {message!s}" if message else "shutdown requst", flush=True)
            log.info(result.shutdown)
            self._stopped.set()

