"""`sva-tools ground`: a live ground view of the LCM link in the browser (docs/ground.md).

A small web server (aiohttp) that listens to the node's channels (<prefix>FLEET,
MISSION, PLAN, EVENT, REPLAN, STATUS) and pushes what they say to the page over a
websocket: a map of the mission in cells (or metres and degrees with a mission frame),
a Gantt of windows, visits and replans, an event log and the node's health. It can
also play an LCM log (--lcm-log) or a simulator flight log (--flight-log) at --speed.
"""
from __future__ import annotations

import argparse
import json
import os
import sys

from ..ground import DEFAULT_URL
from ..ground.limits import Limits


def add_parser(sub) -> None:
    ap = sub.add_parser("ground", help="a live ground view of the LCM link in the browser",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--url", default=DEFAULT_URL, help=f"LCM provider (default {DEFAULT_URL})")
    ap.add_argument("--prefix", default="SVA_", help="channel prefix (default SVA_)")
    ap.add_argument("--host", default="127.0.0.1", help="address to serve on (default 127.0.0.1)")
    ap.add_argument("--port", type=int, default=8765, help="port to serve on (default 8765)")
    lim = Limits()
    ap.add_argument("--token", default=os.environ.get("SVA_GROUND_TOKEN"),
                    help="secret every page, /state.json and /ws request must carry "
                         "(?token= or Authorization: Bearer); required when --host is beyond "
                         "loopback; default $SVA_GROUND_TOKEN")
    ap.add_argument("--allow-host", action="append", default=[], metavar="NAME[:PORT]",
                    help="a further name the browser uses for this server (Host and Origin "
                         "checks; the loopback names and --host are always accepted)")
    ap.add_argument("--max-connections", type=int, default=lim.max_connections,
                    help=f"TCP connections at once (default {lim.max_connections}); one "
                         "more gets 503")
    ap.add_argument("--client-queue", type=int, default=lim.client_queue,
                    help=f"updates queued per websocket client, the oldest dropped when full "
                         f"(default {lim.client_queue})")
    ap.add_argument("--send-timeout", type=float, default=lim.send_timeout_s, metavar="S",
                    help="a websocket client that takes no update for S seconds is "
                         f"disconnected (default {lim.send_timeout_s:g})")
    ap.add_argument("--handshake-timeout", type=float, default=lim.handshake_timeout_s,
                    metavar="S", help="a connection must send a complete request within S "
                    f"seconds; idle keep-alive connections close after S (default "
                    f"{lim.handshake_timeout_s:g})")
    ap.add_argument("--heartbeat", type=float, default=lim.heartbeat_s, metavar="S",
                    help="websocket ping every S seconds of silence; no pong within S/2: "
                         f"closed (default {lim.heartbeat_s:g})")
    src = ap.add_mutually_exclusive_group()
    src.add_argument("--lcm-log", metavar="FILE", help="play an lcm-logger file instead of "
                     "listening")
    src.add_argument("--flight-log", metavar="LOG.json",
                     help="play a `sva-tools sim` flight log instead of listening")
    ap.add_argument("--speed", type=float, default=1.0,
                    help="playback speed (multiplier, default 1; a flight log plays one tick "
                         "per frame.tick_s, else 1 s)")
    ap.add_argument("--frame", metavar="FILE",
                    help="mission frame: a JSON file holding {lat, lon, alt_m, cell_m, tick_s, "
                         "t0}, or a mission or scenario with a `frame` object")
    ap.set_defaults(func=run)


def _fail(msg: str) -> int:
    print(f"sva-tools: error: ground: {msg}", file=sys.stderr)
    return 2


def _frame_from(doc, where: str):
    from ..ground.state import check_frame

    if isinstance(doc, dict) and "mission" in doc and isinstance(doc["mission"], dict):
        doc, where = doc["mission"], f"{where}: mission"
    if isinstance(doc, dict) and "frame" in doc:
        return check_frame(doc["frame"], f"{where}: frame")
    return check_frame(doc, where)


def run(args) -> int:
    try:
        import aiohttp  # noqa: F401
    except ImportError as e:
        return _fail(f"needs aiohttp ({e}); scripts/setup.sh installs it")
    from ..ground import server
    from ..ground.guard import MIN_TOKEN_CHARS, WILDCARDS, Access, is_loopback
    from ..ground.state import FrameError, Ground

    if not args.speed > 0:
        return _fail(f"--speed: must be > 0, got {args.speed}")
    if not 0 <= args.port <= 65535:
        return _fail(f"--port: must be in [0, 65535], got {args.port}")
    for name, value, low in (("--max-connections", args.max_connections, 1),
                             ("--client-queue", args.client_queue, 1),
                             ("--send-timeout", args.send_timeout, 0.1),
                             ("--handshake-timeout", args.handshake_timeout, 0.1),
                             ("--heartbeat", args.heartbeat, 0.1)):
        if not value >= low:
            return _fail(f"{name}: must be >= {low}, got {value}")
    if args.token is not None and len(args.token) < MIN_TOKEN_CHARS:
        return _fail(f"--token: must be at least {MIN_TOKEN_CHARS} characters, got "
                     f"{len(args.token)}")
    if args.token is None and not is_loopback(args.host):
        return _fail(f"--host {args.host}: serving beyond loopback needs --token (or "
                     "$SVA_GROUND_TOKEN)")
    try:
        access = Access(args.host, args.allow_host, args.token)
    except ValueError as e:
        return _fail(str(e))
    limits = Limits(max_connections=args.max_connections, client_queue=args.client_queue,
                    send_timeout_s=args.send_timeout,
                    handshake_timeout_s=args.handshake_timeout, heartbeat_s=args.heartbeat)
    frame = None
    log = None
    try:
        if args.frame:
            with open(args.frame, encoding="utf-8") as f:
                frame = _frame_from(json.load(f), args.frame)
        if args.flight_log:
            with open(args.flight_log, encoding="utf-8") as f:
                log = json.load(f)
            if not isinstance(log, dict) or not {"scenario", "uavs", "targets", "replans",
                                                 "end_tick"} <= set(log):
                return _fail(f"{args.flight_log}: not a flight log (needs scenario, uavs, "
                             "targets, replans, end_tick)")
            mframe = log["scenario"]["mission"].get("frame")
            if frame is None and mframe is not None:
                frame = _frame_from(log["scenario"], args.flight_log)
    except (OSError, json.JSONDecodeError) as e:
        return _fail(str(e))
    except FrameError as e:
        return _fail(str(e))
    if args.lcm_log:
        ground = Ground(args.prefix, frame, source=f"lcm log {args.lcm_log}")
        try:
            source = server.lcm_log_source(ground, args.lcm_log, args.speed)
        except (OSError, ValueError) as e:
            return _fail(f"{args.lcm_log}: {e}")
    elif log is not None:
        ground = Ground(args.prefix, frame, source=f"flight log {args.flight_log}")
        source = server.flight_log_source(ground, log, args.speed)
    else:
        ground = Ground(args.prefix, frame, source=f"live {args.url}")
        try:
            source = server.live_source(ground, args.url, args.prefix)
        except (OSError, RuntimeError, ValueError) as e:
            return _fail(f"--url {args.url}: {e}")

    def ready(port: int) -> None:
        host = f"[{args.host}]" if ":" in args.host else args.host
        hint = " (open it with ?token=TOKEN)" if args.token else ""
        if args.host in WILDCARDS and not args.allow_host:
            hint += " (from elsewhere, give the name browsers use for the server with --allow-host)"
        print(f"sva-tools ground: serving http://{host}:{port}/{hint} ({ground.source})",
              file=sys.stderr, flush=True)
    try:
        server.serve(ground, args.host, args.port, source, ready, limits, access)
    except OSError as e:
        return _fail(f"--host {args.host} --port {args.port}: {e}")
    return 0
