"""The ground server's limits and timeouts, with their defaults (docs/ground.md "Limits").

Apart from the server so that the command line can name the defaults without aiohttp.
"""
from __future__ import annotations

from dataclasses import dataclass


@dataclass(frozen=True)
class Limits:
    """The server's limits and timeouts (docs/ground.md "Limits"; the command's options)."""
    max_connections: int = 64        # TCP connections at once, HTTP and websocket
    client_queue: int = 4            # updates queued per websocket client (oldest dropped)
    send_timeout_s: float = 10.0     # a client that takes no update for this long is cut
    handshake_timeout_s: float = 10.0  # from accept to a complete request; idle keep-alive
    heartbeat_s: float = 10.0        # websocket ping period; no pong within half: closed
    max_message_bytes: int = 4096    # what a client may send (it has nothing to say)
