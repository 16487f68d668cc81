"""Who may talk to the ground view, and how many at once (docs/ground.md "Limits").

- `Access`: the Host and Origin of every request must name this server (the loopback
  names, the bound address, each --allow-host) at the served port, so that neither a
  page from another site (Origin) nor a DNS-rebound name (Host) can read the mission;
  with a token (--token, required beyond loopback), every route but /static/ also needs
  `?token=` or `Authorization: Bearer`. A refusal is an HTTP 403 before any upgrade.
- `ConnectionGate`: at most --max-connections TCP connections; one more is answered 503
  and closed at once. Half-open connections (no complete request) are closed by
  aiohttp's keep-alive timer, which runs from the accept (`keepalive_timeout`, set to
  --handshake-timeout); the gate logs them.
- `RefusalLog`: every refusal is logged once, as its own line or, past a burst, in a
  count line for its kind, so a flood cannot flood the log.
"""
from __future__ import annotations

import asyncio
import hmac
import ipaddress
import sys
import time
from collections.abc import Iterable
from typing import Any
from urllib.parse import parse_qs, urlsplit

from ..text import shown

LOOPBACK_NAMES = ("localhost", "127.0.0.1", "::1")
WILDCARDS = ("", "0.0.0.0", "::")
MIN_TOKEN_CHARS = 16
BURST_LINES = 20         # refusal lines of one kind per window; the rest are counted
BURST_WINDOW_S = 10.0


def is_loopback(host: str) -> bool:
    """True for the names and addresses that reach only the host they are used on."""
    name = host.strip("[]").lower()
    if name == "localhost":
        return True
    try:
        return ipaddress.ip_address(name).is_loopback
    except ValueError:
        return False


def log_line(text: str) -> None:
    print(f"sva-tools ground: {text}", file=sys.stderr, flush=True)


class RefusalLog:
    """Each refusal logged once: up to BURST_LINES lines per kind and window, then one
    line per window counting the rest."""

    def __init__(self) -> None:
        self.total: dict[str, int] = {}
        self._window: dict[str, tuple[float, int, int]] = {}  # kind: start, lines, held

    def refused(self, kind: str, text: str) -> None:
        self.total[kind] = self.total.get(kind, 0) + 1
        now = time.monotonic()
        start, lines, held = self._window.get(kind, (now, 0, 0))
        if now - start >= BURST_WINDOW_S:
            self._flush(kind, held)
            start, lines, held = now, 0, 0
        if lines < BURST_LINES:
            log_line(f"refused: {text}")
            lines += 1
        else:
            if held == 0:
                asyncio.get_running_loop().call_later(BURST_WINDOW_S, self._flush_due, kind)
            held += 1
        self._window[kind] = (start, lines, held)

    def _flush_due(self, kind: str) -> None:
        start, lines, held = self._window.get(kind, (0.0, 0, 0))
        self._flush(kind, held)
        self._window[kind] = (time.monotonic(), 0, 0)

    @staticmethod
    def _flush(kind: str, held: int) -> None:
        if held:
            log_line(f"refused: {held} more ({kind}) in the last {BURST_WINDOW_S:g} s")


def _host_port(netloc: str, default_port: int) -> tuple[str, int] | None:
    try:
        parts = urlsplit("//" + netloc)
        name, port = parts.hostname, parts.port
    except ValueError:
        return None
    if not name or parts.username is not None or parts.path:
        return None
    return name.lower(), port if port is not None else default_port


class Access:
    """The Host, Origin and token rules for one served address."""

    def __init__(self, host: str, allow_hosts: Iterable[str], token: str | None):
        self.names: set[str] = set(LOOPBACK_NAMES)
        if host not in WILDCARDS:
            self.names.add(host.strip("[]").lower())
        self.extra: set[tuple[str, int | None]] = set()
        for entry in allow_hosts:
            hp = _host_port(entry, -1)
            if hp is None:
                raise ValueError(f"--allow-host: must be NAME or NAME:PORT, got {entry!r}")
            self.extra.add((hp[0], None if hp[1] == -1 else hp[1]))
        self.token = token.encode() if token else None
        self.port = 0  # the served port, known once listening

    def _ours(self, name: str, port: int) -> bool:
        if port == self.port and (name in self.names or (name, None) in self.extra):
            return True
        return (name, port) in self.extra

    def refusal(self, headers: Any, query: str, path: str) -> str | None:
        """Why a request may not be served, or None."""
        host = headers.get("Host", "")
        hp = _host_port(host, 80)
        if hp is None or not self._ours(*hp):
            return f"Host {shown(host)!s} is not this server (--allow-host adds a name)"
        origin = headers.get("Origin")
        if origin is not None:
            parts = urlsplit(origin)
            op = _host_port(parts.netloc, 443 if parts.scheme == "https" else 80) \
                if parts.scheme in ("http", "https") else None
            if op is None or not self._ours(*op):
                return f"Origin {shown(origin)} is not this server"
        if self.token is not None and not path.startswith("/static/"):
            given = parse_qs(query).get("token", [""])[-1]
            auth = headers.get("Authorization", "")
            if auth.startswith("Bearer "):
                given = auth[len("Bearer "):]
            if not hmac.compare_digest(given.encode(), self.token):
                return "no token or a wrong one (?token= or Authorization: Bearer)"
        return None


class ConnectionGate:
    """Caps the server's TCP connections and logs the half-open ones it closes.

    aiohttp has no connection cap; its `web.Server` (the protocol factory) is told of
    every connection made and lost, so the gate wraps those two methods of the runner's
    server instance."""

    def __init__(self, max_connections: int, handshake_timeout_s: float, refusals: RefusalLog):
        self.max_connections = max_connections
        self.handshake_timeout_s = handshake_timeout_s
        self.refusals = refusals
        self.live: dict[Any, tuple[Any, float]] = {}  # handler: transport, accepted at
        self.requested: set[Any] = set()     # handlers that received a complete request
        self.peak = 0

    def install(self, server: Any) -> None:
        made, lost = server.connection_made, server.connection_lost

        def connection_made(handler: Any, transport: Any) -> None:
            made(handler, transport)
            if len(self.live) >= self.max_connections:
                self.refusals.refused(
                    "too many connections",
                    f"{peer(transport)}: {len(self.live)} connections open "
                    f"(--max-connections {self.max_connections})")
                transport.write(b"HTTP/1.1 503 Service Unavailable\r\nConnection: close\r\n"
                                b"Content-Length: 0\r\n\r\n")
                transport.close()
                return
            self.live[handler] = (transport, asyncio.get_running_loop().time())
            self.peak = max(self.peak, len(self.live))

        def connection_lost(handler: Any, exc: BaseException | None = None) -> None:
            entry = self.live.pop(handler, None)
            if entry is not None and handler not in self.requested:
                transport, since = entry
                if asyncio.get_running_loop().time() - since >= 0.9 * self.handshake_timeout_s:
                    self.refusals.refused(
                        "half-open",
                        f"{peer(transport)}: no complete request within "
                        f"{self.handshake_timeout_s:g} s (--handshake-timeout), closed")
            self.requested.discard(handler)
            lost(handler, exc)

        server.connection_made = connection_made
        server.connection_lost = connection_lost


def peer(transport: Any) -> str:
    name = transport.get_extra_info("peername") if transport is not None else None
    if isinstance(name, tuple) and len(name) >= 2:
        return f"{name[0]}:{name[1]}" if ":" not in str(name[0]) else f"[{name[0]}]:{name[1]}"
    return "?"
