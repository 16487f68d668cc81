"""The ground view's web server (aiohttp): the page, its files and a websocket of updates.

Sources of traffic, one per run:
- live: subscribes to <prefix>.* on the LCM URL (the socket is read by the event loop);
- an LCM log (lcm-logger format, read with the lcm package's EventLog), played at
  --speed times the recorded pace;
- a simulator flight log (docs/live.md), played tick by tick, one tick per frame.tick_s
  seconds (1 s without a frame) divided by --speed.

Routes: GET / (the page), GET /static/NAME (its script and style, from the package),
GET /state.json (the current picture), GET /ws (websocket: a {"type": "state", ...}
message on connect and after every change, at most every 100 ms).

Limits (docs/ground.md "Limits"): every request passes the Host/Origin/token guard
(guard.Access) and the connection cap (guard.ConnectionGate); each websocket client has
its own bounded queue and sender (Client), a send deadline and aiohttp's ping/pong
heartbeat; aiohttp's keep-alive timer is the handshake deadline.
"""
from __future__ import annotations

import asyncio
import collections
import json
import re
import signal
import time
from collections.abc import Awaitable, Coroutine
from pathlib import Path
from typing import Any, Callable

from aiohttp import WSMsgType, web
from aiohttp.typedefs import Handler

from .guard import Access, ConnectionGate, RefusalLog, peer
from .limits import Limits
from .state import Ground, flight_at

STATIC = Path(__file__).resolve().parent / "static"
PUSH_PERIOD_S = 0.1
LOG_YIELD_EVERY = 64     # a log played faster than it is read still lets the server answer

# A source of traffic: its (start, stop) hooks, run at the application's startup and cleanup.
Hook = Callable[[web.Application], Awaitable[None]]
Source = tuple[Hook, Hook]


class Client:
    """One websocket client: its own bounded queue of updates and its own sender, so a
    client that does not read holds up nobody else. Each update is the whole picture,
    so dropping the oldest loses nothing the next one does not say."""

    def __init__(self, ws: web.WebSocketResponse, request: web.BaseRequest, queue: int) -> None:
        self.ws = ws
        self.request = request
        self.peer = peer(request.transport)
        self.frames: collections.deque[str] = collections.deque(maxlen=queue)
        self.ready = asyncio.Event()
        self.sent = 0
        self.dropped = 0

    def offer(self, text: str) -> None:
        if len(self.frames) == self.frames.maxlen:
            self.dropped += 1
        self.frames.append(text)
        self.ready.set()

    def abort(self) -> None:
        """Drops the connection now: a graceful close would wait for the client to read
        what is buffered, which a stalled client never does."""
        transport = self.request.transport
        if transport is not None:
            transport.abort()


class Server:
    def __init__(self, ground: Ground, limits: Limits = Limits(),
                 access: Access | None = None) -> None:
        self.ground = ground
        self.limits = limits
        self.access = access if access is not None else Access("127.0.0.1", (), None)
        self.refusals = RefusalLog()
        self.gate = ConnectionGate(limits.max_connections, limits.handshake_timeout_s,
                                   self.refusals)
        self.clients: set[Client] = set()
        self.sent_version = -1
        self._frame_version = -1
        self._frame_text = ""

    # --- http ---------------------------------------------------------------------------

    @web.middleware
    async def guard(self, request: web.Request, handler: Handler) -> web.StreamResponse:
        self.gate.requested.add(request.protocol)
        why = self.access.refusal(request.headers, request.query_string, request.path)
        if why is not None:
            self.refusals.refused("forbidden", f"{peer(request.transport)} {request.method} "
                                               f"{request.path}: {why}")
            raise web.HTTPForbidden(text=f"sva-tools ground: {why}\n")
        return await handler(request)

    async def index(self, request: web.Request) -> web.FileResponse:
        return web.FileResponse(STATIC / "index.html")

    async def state(self, request: web.Request) -> web.Response:
        """The picture once; a reader that takes none of it for --send-timeout is cut
        (aiohttp would wait on it for ever)."""
        resp = web.Response(body=json.dumps(self.ground.snapshot()).encode(),
                            content_type="application/json")
        await resp.prepare(request)
        try:
            await asyncio.wait_for(resp.write_eof(), self.limits.send_timeout_s)
        except asyncio.TimeoutError:
            self.refusals.refused("stalled client", f"{peer(request.transport)} GET "
                                  f"/state.json: took nothing for {self.limits.send_timeout_s:g}"
                                  " s (--send-timeout), disconnected")
            if request.transport is not None:
                request.transport.abort()
        return resp

    def _frame(self) -> str:
        if self._frame_version != self.ground.version:
            self._frame_version = self.ground.version
            self._frame_text = json.dumps({"type": "state", **self.ground.snapshot()})
        return self._frame_text

    async def ws(self, request: web.Request) -> web.WebSocketResponse:
        lim = self.limits
        ws = web.WebSocketResponse(heartbeat=lim.heartbeat_s,
                                   max_msg_size=lim.max_message_bytes)
        await ws.prepare(request)
        client = Client(ws, request, lim.client_queue)
        self.clients.add(client)
        client.offer(self._frame())
        sender = asyncio.get_running_loop().create_task(self._send_loop(client))
        try:
            async for msg in ws:
                if msg.type in (WSMsgType.ERROR, WSMsgType.CLOSE):
                    break
        finally:
            self.clients.discard(client)
            sender.cancel()
            if ws.close_code not in (None, 1000, 1001) or (
                    request.transport is not None
                    and request.transport.get_write_buffer_size() > 0):
                client.abort()
        return ws

    async def _send_loop(self, client: Client) -> None:
        while True:
            await client.ready.wait()
            client.ready.clear()
            while client.frames:
                text = client.frames.popleft()
                try:
                    await asyncio.wait_for(client.ws.send_str(text), self.limits.send_timeout_s)
                except asyncio.TimeoutError:
                    self.refusals.refused(
                        "stalled client",
                        f"{client.peer}: took no update for {self.limits.send_timeout_s:g} s "
                        f"(--send-timeout; {client.dropped} updates dropped), disconnected")
                    client.abort()
                    return
                except (ConnectionError, RuntimeError):
                    return
                client.sent += 1

    def app(self) -> web.Application:
        app = web.Application(middlewares=[self.guard])
        app.router.add_get("/", self.index)
        app.router.add_get("/state.json", self.state)
        app.router.add_get("/ws", self.ws)
        app.router.add_static("/static/", STATIC, show_index=False)
        app.on_startup.append(self._start_pusher)
        app.on_shutdown.append(self._close_clients)
        return app

    async def _start_pusher(self, app: web.Application) -> None:
        app["pusher"] = asyncio.get_running_loop().create_task(self._push_loop())

    async def _close_clients(self, app: web.Application) -> None:
        app["pusher"].cancel()
        for client in list(self.clients):
            if client.frames or (client.request.transport is not None and
                                 client.request.transport.get_write_buffer_size() > 0):
                client.abort()
            else:
                await client.ws.close(code=1001, message=b"server shutdown")

    async def _push_loop(self) -> None:
        while True:
            await asyncio.sleep(PUSH_PERIOD_S)
            if self.ground.version == self.sent_version or not self.clients:
                continue
            self.sent_version = self.ground.version
            text = self._frame()
            for client in list(self.clients):
                client.offer(text)


# --- sources ----------------------------------------------------------------------------

def live_source(ground: Ground, url: str, prefix: str) -> Source:
    """Subscribes to every channel of the prefix; the LCM socket is read by the loop."""
    import lcm

    lc = lcm.LCM(url)
    sub = lc.subscribe(re.escape(prefix) + ".*", ground.on_message)
    sub.set_queue_capacity(10000)

    async def start(app: web.Application) -> None:
        asyncio.get_running_loop().add_reader(lc.fileno(), lc.handle)

    async def stop(app: web.Application) -> None:
        asyncio.get_running_loop().remove_reader(lc.fileno())
        lc.unsubscribe(sub)
    return start, stop


def lcm_log_source(ground: Ground, path: str, speed: float) -> Source:
    """Plays an lcm-logger file at `speed` times its recorded pace."""
    import lcm

    log = lcm.EventLog(path, "r")

    async def play() -> None:
        first_log: int | None = None
        first_wall = time.monotonic()
        for n, ev in enumerate(log):
            if first_log is None:
                first_log = ev.timestamp
            due = first_wall + (ev.timestamp - first_log) / 1e6 / speed
            wait = due - time.monotonic()
            if wait > 0:
                await asyncio.sleep(wait)
            elif n % LOG_YIELD_EVERY == 0:
                await asyncio.sleep(0)
            ground.on_message(ev.channel, ev.data)
        ground._log("end", f"end of the LCM log {Path(path).name}")
        ground._changed()
    return _task(play)


def flight_log_source(ground: Ground, log: dict[str, Any], speed: float) -> Source:
    """Plays a flight log tick by tick: frame.tick_s (else 1 s) per tick, over speed."""
    tick_s = (ground.frame or {}).get("tick_s", 1.0)

    async def play() -> None:
        for t in range(0, log["end_tick"] + 1):
            flight_at(ground, log, t)
            await asyncio.sleep(tick_s / speed)
        ground._log("end", f"end of the flight at tick {log['end_tick']}")
        ground._changed()
    return _task(play)


def _task(play: Callable[[], Coroutine[Any, Any, None]]) -> Source:
    async def start(app: web.Application) -> None:
        app["player"] = asyncio.get_running_loop().create_task(play())

    async def stop(app: web.Application) -> None:
        app["player"].cancel()
    return start, stop


def serve(ground: Ground, host: str, port: int, source: Source,
          ready: Callable[[int], object] | None = None,
          limits: Limits = Limits(), access: Access | None = None) -> None:
    """Serves until SIGINT or SIGTERM. `ready(port)` once listening (port: the bound one).
    OSError if the address cannot be bound."""
    asyncio.run(_serve(Server(ground, limits, access or Access(host, (), None)), host, port,
                       source, ready))


async def _serve(srv: Server, host: str, port: int, source: Source,
                 ready: Callable[[int], object] | None) -> None:
    app = srv.app()
    start, stop = source
    app.on_startup.append(start)
    app.on_cleanup.append(stop)
    # keepalive_timeout runs from the accept: a connection that sends no complete request
    # within it (half-open, or slow on purpose) is closed, as is an idle keep-alive one.
    runner = web.AppRunner(app, keepalive_timeout=srv.limits.handshake_timeout_s,
                           shutdown_timeout=2.0, access_log=None)
    await runner.setup()
    try:
        assert runner.server is not None
        srv.gate.install(runner.server)
        site = web.TCPSite(runner, host, port, backlog=128)
        await site.start()
        srv.access.port = runner.addresses[0][1]
        if ready is not None:
            ready(srv.access.port)
        done = asyncio.Event()
        loop = asyncio.get_running_loop()
        for sig in (signal.SIGINT, signal.SIGTERM):
            loop.add_signal_handler(sig, done.set)
        await done.wait()
    finally:
        await runner.cleanup()
