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
"""
from __future__ import annotations

import asyncio
import json
import re
import time
from pathlib import Path
from typing import Optional

from aiohttp import WSMsgType, web

from .state import Ground, flight_at

STATIC = Path(__file__).resolve().parent / "static"
PUSH_PERIOD_S = 0.1


class Server:
    def __init__(self, ground: Ground):
        self.ground = ground
        self.clients: set = set()
        self.sent_version = -1
        self.done = False

    # --- http ---------------------------------------------------------------------------

    async def index(self, request):
        return web.FileResponse(STATIC / "index.html")

    async def state(self, request):
        return web.json_response(self.ground.snapshot())

    async def ws(self, request):
        ws = web.WebSocketResponse(heartbeat=20)
        await ws.prepare(request)
        self.clients.add(ws)
        try:
            await ws.send_str(json.dumps({"type": "state", **self.ground.snapshot()}))
            async for msg in ws:
                if msg.type in (WSMsgType.ERROR, WSMsgType.CLOSE):
                    break
        finally:
            self.clients.discard(ws)
        return ws

    def app(self) -> web.Application:
        app = web.Application()
        app.router.add_get("/", self.index)
        app.router.add_get("/state.json", self.state)
        app.router.add_get("/ws", self.ws)
        app.router.add_static("/static/", STATIC, show_index=False)
        app.on_startup.append(self._start_pusher)
        app.on_shutdown.append(self._close_clients)
        return app

    async def _start_pusher(self, app):
        app["pusher"] = asyncio.get_running_loop().create_task(self._push_loop())

    async def _close_clients(self, app):
        for ws in list(self.clients):
            await ws.close()

    async def _push_loop(self):
        while True:
            await asyncio.sleep(PUSH_PERIOD_S)
            if self.ground.version == self.sent_version or not self.clients:
                continue
            self.sent_version = self.ground.version
            text = json.dumps({"type": "state", **self.ground.snapshot()})
            for ws in list(self.clients):
                try:
                    await ws.send_str(text)
                except (ConnectionError, RuntimeError):
                    self.clients.discard(ws)


# --- sources ----------------------------------------------------------------------------

def live_source(ground: Ground, url: str, prefix: str):
    """Subscribes to every channel of the prefix; the LCM socket is read by the loop."""
    import lcm

    lc = lcm.LCM(url)
    sub = lc.subscribe(re.escape(prefix) + ".*", ground.on_message)
    sub.set_queue_capacity(10000)

    async def start(app):
        asyncio.get_running_loop().add_reader(lc.fileno(), lc.handle)

    async def stop(app):
        asyncio.get_running_loop().remove_reader(lc.fileno())
        lc.unsubscribe(sub)
    return start, stop


def lcm_log_source(ground: Ground, path: str, speed: float):
    """Plays an lcm-logger file at `speed` times its recorded pace."""
    import lcm

    log = lcm.EventLog(path, "r")

    async def play():
        first_log: Optional[int] = None
        first_wall = time.monotonic()
        for ev in log:
            if first_log is None:
                first_log = ev.timestamp
            due = first_wall + (ev.timestamp - first_log) / 1e6 / speed
            wait = due - time.monotonic()
            if wait > 0:
                await asyncio.sleep(wait)
            ground.on_message(ev.channel, ev.data)
        ground._log("end", f"end of the LCM log {Path(path).name}")
        ground._changed()
    return _task(play)


def flight_log_source(ground: Ground, log: dict, speed: float):
    """Plays a flight log tick by tick: frame.tick_s (else 1 s) per tick, over speed."""
    tick_s = (ground.frame or {}).get("tick_s", 1.0)

    async def play():
        for t in range(0, log["end_tick"] + 1):
            flight_at(ground, log, t)
            await asyncio.sleep(tick_s / speed)
        ground._log("end", f"end of the flight at tick {log['end_tick']}")
        ground._changed()
    return _task(play)


def _task(play):
    async def start(app):
        app["player"] = asyncio.get_running_loop().create_task(play())

    async def stop(app):
        app["player"].cancel()
    return start, stop


def serve(ground: Ground, host: str, port: int, source, ready=None) -> None:
    srv = Server(ground)
    app = srv.app()
    start, stop = source
    app.on_startup.append(start)
    app.on_cleanup.append(stop)

    async def say_ready(app):
        if ready is not None:
            ready(app)
    app.on_startup.append(say_ready)
    web.run_app(app, host=host, port=port, print=None, handle_signals=True)
