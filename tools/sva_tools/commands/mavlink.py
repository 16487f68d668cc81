"""`sva-tools mavlink upload PLAN.json --mission MISSION.json --vehicle UAV_ID=udp|tcp:HOST:PORT[:SYSID]`:
a plan's routes as MAVLink missions, uploaded to the vehicles (docs/mavlink.md).

Per UAV with a vehicle: MAV_CMD_NAV_TAKEOFF at its start cell, MAV_CMD_DO_CHANGE_SPEED
to the plan's ground speed, per target a MAV_CMD_NAV_WAYPOINT at the target cell
(MAV_FRAME_GLOBAL_RELATIVE_ALT_INT, the frame's alt_m) and a MAV_CMD_NAV_DELAY until the
UTC time of day of the window's end, then MAV_CMD_NAV_RETURN_TO_LAUNCH. The frame comes
from the plan's `frame` when it has one, else from the mission's. Each vehicle gets the
MAVLink mission protocol (MISSION_COUNT, MISSION_REQUEST_INT -> MISSION_ITEM_INT,
MISSION_ACK) with pymavlink's codec, all vehicles at once, over UDP (datagrams from the
vehicle's address and port only) or TCP; only the vehicle's autopilot (its system id,
component 1) is heard, and stray or broken bytes lose no good frame. One line per
vehicle tells how it went. Exit 0 when every upload was accepted, 1 when one failed, 2
on bad input (files, frame, command line, a route the items cannot carry).
"""
from __future__ import annotations

import argparse
import sys
import threading

from .. import io
from ..check import check_plan
from ..mavlink import (
    RETRIES,
    TIMEOUT_MS,
    Item,
    Vehicle,
    build_items,
    frame_from_json,
    parse_vehicle,
    prepend_home,
    resolve,
    upload,
)
from ..text import shown
from .common import fail


def _load(path: str, kind: str):
    """The mission or plan in path, validated with its frame (SPEC sections 3 and 4),
    and its frame object (None when it has none)."""
    try:
        doc = io.read_json(path)
        parsed = io.mission_from_json(doc) if kind == "mission" else io.plan_from_json(doc)
    except io.InputError as e:
        e.path = path
        raise
    return parsed, doc.get("frame")


def add_parser(sub) -> None:
    ap = sub.add_parser("mavlink", help="upload a plan's routes as MAVLink missions",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    msub = ap.add_subparsers(dest="mavlink_command", metavar="COMMAND")
    msub.required = True
    up = msub.add_parser("upload", help="upload the routes to the vehicles (MAVLink over UDP or TCP)")
    up.add_argument("plan", metavar="PLAN.json")
    up.add_argument("--mission", required=True, metavar="MISSION.json")
    up.add_argument("--vehicle", action="append", required=True,
                    metavar="UAV_ID=udp|tcp:HOST:PORT[:SYSID]",
                    help="a UAV's vehicle: UDP to its address and port (only datagrams from "
                    "there are read), or a TCP connection; SYSID its system id (default 1)")
    up.add_argument("--timeout-ms", type=int, default=TIMEOUT_MS,
                    help=f"wait per message before resending (default {TIMEOUT_MS})")
    up.add_argument("--ardupilot", action="store_true",
                    help="put a home item 0 first (ArduPilot overwrites item 0 with home)")
    up.add_argument("--retries", type=int, default=RETRIES,
                    help=f"resends of one message before giving up (default {RETRIES})")
    up.set_defaults(func=run)


def run(args) -> int:
    if not 1 <= args.timeout_ms <= 600_000 or not 0 <= args.retries <= 100:
        print("sva-tools: error: mavlink upload: --timeout-ms must be in [1, 600000] and "
              "--retries in [0, 100]", file=sys.stderr)
        return 2
    vehicles: dict[int, tuple[Vehicle, str]] = {}
    for text in args.vehicle:
        try:
            vehicle = parse_vehicle(text)
        except io.InputError as e:
            return fail("mavlink upload", e)
        if vehicle.uav in vehicles:
            return fail("mavlink upload",
                           io.InputError(f"--vehicle: UAV {vehicle.uav} given twice"))
        vehicles[vehicle.uav] = (vehicle, text.split("=", 1)[1])
    for uid, (vehicle, text) in vehicles.items():
        try:
            vehicles[uid] = (resolve(vehicle), text)
        except io.InputError as e:
            return fail("mavlink upload", e)
    mission, mframe = _load(args.mission, "mission")
    plan, pframe = _load(args.plan, "plan")
    where = pframe if pframe is not None else mframe
    if where is None:
        return fail(args.plan, io.InputError(
            "frame: missing: neither the plan nor the mission has a \"frame\" (lat, lon, alt_m, "
            "cell_m, tick_s, t0): cells and ticks cannot be placed on the Earth"))
    frame = frame_from_json(where)
    problems = check_plan(mission, plan)
    if problems:
        return fail(args.plan, io.InputError(f"plan: does not fit {shown(args.mission)}: "
                                                f"{problems[0]}"))
    uavs = {u.id: u for u in mission.uavs}
    routes = {r.uav: r.targets for r in plan.routes}
    for uid in vehicles:
        if uid not in uavs:
            return fail("mavlink upload", io.InputError(
                f"--vehicle: UAV {uid} is not in the mission"))
    work: list[tuple[int, list[Item]]] = []
    results: dict[int, str] = {}
    status = 0
    for uid in sorted(vehicles, key=lambda u: [x.id for x in mission.uavs].index(u)):
        try:
            items = build_items(frame, mission, uavs[uid], routes.get(uid, []))
        except io.InputError as e:
            results[uid] = f"error: {e}"
            status = 1
            continue
        if not items:
            results[uid] = "nothing to upload: the plan gives it no targets"
            continue
        if args.ardupilot:
            items = [prepend_home(items[0])] + items
        work.append((uid, items))

    def one(uid: int, items: list[Item]) -> None:
        vehicle = vehicles[uid][0]
        try:
            why = upload(vehicle, items, args.timeout_ms, args.retries)
        except OSError as e:
            why = f"{vehicle.transport}: {e.strerror or e}"
        except Exception as e:  # noqa: BLE001 -- one vehicle's fault must not stop the others
            why = f"{type(e).__name__}: {shown(e)}"
        results[uid] = f"uploaded {len(items)} items" if why is None else f"error: {why}"

    threads = [threading.Thread(target=one, args=w) for w in work]
    for t in threads:
        t.start()
    for t in threads:
        t.join()
    for uid in vehicles:
        line = results[uid]
        if line.startswith("error"):
            status = 1
        print(f"uav {uid}: {shown(vehicles[uid][1])}: {shown(line)}")
    return status
