"""The live ground view of the LCM link: its state, web server and access guard
(`sva-tools ground`, docs/ground.md)."""
from __future__ import annotations

DEFAULT_URL = "udpm://239.255.76.67:7667?ttl=0"
