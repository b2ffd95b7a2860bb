"""A WebSocket server whose clients each have a bounded send buffer (the web bridges' I/O shell).

- The WebSocket protocol is the `websockets` library's (its asyncio server); this module only
  runs it on a thread of its own and bounds what each client can make us hold.
- Who may connect is kame.net.peers' allowlist, asked before the handshake: a refused peer gets
  HTTP 403 and one log line per address.
- Every client has one send buffer, counted in bytes: what is queued here plus what its socket
  has not taken. `send_data` (messages a client may miss: a topic's next message replaces them)
  is dropped while the buffer is over `send_buffer_limit`; `send_control` (the protocol's answers and
  announcements) is never dropped, and a client that lets it pile past twice the limit is not
  reading and is disconnected. So one slow or hostile client costs at most about twice the limit
  plus one message, and never slows another.
- What a client sends is bounded by `max_message_size` (larger: the connection is closed, 1009)
  and by `websockets`' own queue of 16 frames, which stops reading the socket when full.
- The handler is called on the server's thread, in the order frames arrive; it must not block
  (the bridges hand their blocking work to threads of their own).
- `close()` stops accepting, closes every client, ends the thread and joins it.
"""

from __future__ import annotations

import asyncio
import itertools
import logging
import threading
from collections import deque
from typing import Protocol

from websockets.asyncio.server import Server, ServerConnection, serve
from websockets.exceptions import ConnectionClosed
from websockets.http11 import Request, Response

from kame.net import peers

log = logging.getLogger("kame.net.websocket_hub")

STARTUP_TIMEOUT = 10.0
JOIN_TIMEOUT = 5.0


class HubHandler(Protocol):
    def opened(self, client: HubClient) -> None: ...

    def received(self, client: HubClient, message: str | bytes) -> None: ...

    def closed(self, client: HubClient) -> None: ...


class HubClient:
    """One connected client: what may be sent to it, from any thread."""

    def __init__(self, client_id: int, connection: ServerConnection, loop: asyncio.AbstractEventLoop,
                 send_buffer_limit: int) -> None:
        self.id = client_id
        address = connection.remote_address
        self.peer = f"{address[0]}:{address[1]}" if isinstance(address, tuple) else str(address)
        self._connection = connection
        self._loop = loop
        self._limit = send_buffer_limit
        self._lock = threading.Lock()
        self._queued = 0  # bytes handed to send_* and not yet handed to the socket's write buffer
        self._outgoing: deque[str | bytes] = deque()
        self._wake = asyncio.Event()  # set on the loop when _outgoing has something
        self._gone = False
        self.dropped = 0  # messages send_data dropped because the buffer was full

    def _buffered(self) -> int:
        transport = self._connection.transport
        return self._queued + (transport.get_write_buffer_size() if transport is not None else 0)

    def send_data(self, data: bytes) -> bool:
        """Queue a message the client may miss; False (and counted) when its buffer is full."""
        with self._lock:
            if self._gone:
                return False
            if self._buffered() + len(data) > self._limit and self._queued > 0:
                self.dropped += 1
                return False
            self._queued += len(data)
        self._loop.call_soon_threadsafe(self._push, data)
        return True

    def send_control(self, message: str | bytes) -> None:
        """Queue a message the client must get; a client that lets these pile up is closed."""
        with self._lock:
            if self._gone:
                return
            self._queued += len(message)
            stuck = self._buffered() > 2 * self._limit
        if stuck:
            log.warning("client %s reads too slowly for the protocol's answers: disconnecting it", self.peer)
            self.close(1008, "send buffer limit reached")
            return
        self._loop.call_soon_threadsafe(self._push, message)

    def close(self, code: int = 1000, reason: str = "") -> None:
        with self._lock:
            self._gone = True
        self._loop.call_soon_threadsafe(lambda: asyncio.ensure_future(self._connection.close(code, reason)))

    def _push(self, message: str | bytes) -> None:
        self._outgoing.append(message)
        self._wake.set()

    async def _send_loop(self) -> None:
        while True:
            await self._wake.wait()
            self._wake.clear()
            while self._outgoing:
                message = self._outgoing.popleft()
                with self._lock:  # from here on the socket's write buffer counts it
                    self._queued -= len(message)
                await self._connection.send(message)

    def _ended(self) -> None:
        with self._lock:
            self._gone = True


class WebSocketHub:
    """Serves `subprotocol` on host:port (port 0: any free one); see the module's rules."""

    def __init__(self, host: str, port: int, subprotocol: str, handler: HubHandler, where: str,
                 send_buffer_limit: int, max_message_size: int) -> None:
        self._handler = handler
        self._where = where
        self._limit = send_buffer_limit
        self._ids = itertools.count(1)
        self._loop = asyncio.new_event_loop()
        self._server: Server | None = None
        self._started = threading.Event()
        self._failure: BaseException | None = None
        self._stopped: asyncio.Event | None = None
        self._thread = threading.Thread(target=self._run, args=(host, port, subprotocol, max_message_size),
                                        name=f"kame-{where}", daemon=True)
        self._thread.start()
        if not self._started.wait(STARTUP_TIMEOUT):
            raise OSError(f"the {where} did not start listening in {STARTUP_TIMEOUT:.0f} s")
        if self._failure is not None:
            raise self._failure

    @property
    def port(self) -> int:
        assert self._server is not None
        port: int = self._server.sockets[0].getsockname()[1]
        return port

    def _run(self, host: str, port: int, subprotocol: str, max_message_size: int) -> None:
        asyncio.set_event_loop(self._loop)
        try:
            self._loop.run_until_complete(self._serve(host, port, subprotocol, max_message_size))
        finally:
            self._loop.close()

    async def _serve(self, host: str, port: int, subprotocol: str, max_message_size: int) -> None:
        self._stopped = asyncio.Event()
        try:
            # compression off: the bridges forward large binary messages as they are (and
            # foxglove_bridge, rosbridge default to none)
            self._server = await serve(self._connected, host or None, port, subprotocols=[subprotocol],  # type: ignore[list-item]
                                       process_request=self._admit, compression=None, max_size=max_message_size,
                                       max_queue=16, ping_interval=None)
        except BaseException as exc:
            self._failure = exc
            self._started.set()
            return
        self._started.set()
        await self._stopped.wait()
        self._server.close()
        await self._server.wait_closed()

    def _admit(self, connection: ServerConnection, request: Request) -> Response | None:
        if peers.admit(connection.remote_address, self._where):
            return None
        return connection.respond(403, "not in the allowed peers\n")

    async def _connected(self, connection: ServerConnection) -> None:
        client = HubClient(next(self._ids), connection, self._loop, self._limit)
        sender = asyncio.ensure_future(client._send_loop())
        try:
            self._handler.opened(client)
            async for message in connection:
                self._handler.received(client, message)
        except ConnectionClosed:
            pass
        finally:
            client._ended()
            sender.cancel()
            await asyncio.gather(sender, return_exceptions=True)
            self._handler.closed(client)

    def close(self) -> None:
        if self._thread.is_alive() and self._stopped is not None:
            stopped = self._stopped
            self._loop.call_soon_threadsafe(stopped.set)
        self._thread.join(JOIN_TIMEOUT)
