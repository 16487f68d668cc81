"""The MAVLink tests' judge: every item of a UAV's mission against its route in the plan,
the mission and the frame, recomputed here from pymap3d and the standard library (never
from the bridge's code).

Items are tuples (command, frame, p1, p2, p3, p4, x, y, z). Positions must be within
1e-7 degree of pymap3d's East-North-Up conversion of the cell; every hold must end at
the UTC time of day of the window's end (rounded up to a second); and at the commanded
speed, the path from each leg's planned departure (ready_at for the first, the previous
window's end after) must reach the waypoint no later than the window's start. The path
length is measured at the flight altitude along the ellipsoid's geodesic (many short
chords in ECEF), not taken from a formula of the bridge.
"""
from __future__ import annotations

import datetime as dt
import json
import math
import os
import subprocess
from typing import Dict, List, Sequence, Tuple

import pymap3d
from pymap3d import vincenty

NAV_WAYPOINT, NAV_RTL, NAV_TAKEOFF, NAV_DELAY, DO_CHANGE_SPEED = 16, 20, 22, 93, 178
FRAME_MISSION, FRAME_GLOBAL_REL_ALT_INT = 2, 6


def frame_ints(fr: dict) -> dict:
    def r(v):
        return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)
    t0 = dt.datetime.fromisoformat(fr["t0"].replace("Z", "+00:00"))
    return {"lat_e7": r(fr["lat"] * 1e7), "lon_e7": r(fr["lon"] * 1e7), "alt_cm": r(fr["alt_m"] * 100),
            "cell_cm": r(fr["cell_m"] * 100), "tick_ms": r(fr["tick_s"] * 1000),
            "t0_ms": round(t0.timestamp() * 1000)}


def cell_geo(fi: dict, x: int, y: int) -> Tuple[float, float]:
    cell = fi["cell_cm"] / 100.0
    lat, lon, _ = pymap3d.enu2geodetic(x * cell, y * cell, 0.0, fi["lat_e7"] / 1e7,
                                       fi["lon_e7"] / 1e7, 0.0)
    return float(lat), float(lon)


def path_m(a: Tuple[float, float], b: Tuple[float, float], alt: float, pieces: int = 64) -> float:
    """Length of the geodesic from a to b flown at height alt (sum of ECEF chords)."""
    if a == b:
        return 0.0
    lats, lons = vincenty.track2(a[0], a[1], b[0], b[1], npts=pieces + 1)
    pts = [pymap3d.geodetic2ecef(float(la), float(lo), alt) for la, lo in zip(lats, lons)]
    return sum(math.dist(p, q) for p, q in zip(pts, pts[1:]))


def tod_of(ms: int) -> Tuple[int, int, int]:
    s = -(-ms // 1000)
    t = dt.datetime.fromtimestamp(s, tz=dt.timezone.utc)
    return t.hour, t.minute, t.second


def check_route(items: Sequence[tuple], mission: dict, fr: dict, uav_id: int,
                target_ids: List[int]) -> List[str]:
    """Problems of one UAV's items (empty: all good)."""
    fi = frame_ints(fr)
    uav = next(u for u in mission["uavs"] if u["id"] == uav_id)
    by_id = {t["id"]: t for t in mission["targets"]}
    tpc = mission.get("ticks_per_cell", 1)
    alt = fi["alt_cm"] / 100.0
    tick_s = fi["tick_ms"] / 1000.0
    bad: List[str] = []
    if not target_ids:
        return [f"uav {uav_id}: items for a route without targets"] if items else []
    if len(items) != 3 + 2 * len(target_ids):
        return [f"uav {uav_id}: {len(items)} items for {len(target_ids)} targets"]

    def near(it, lat, lon, what):
        if abs(it[6] / 1e7 - lat) > 1e-7 or abs(it[7] / 1e7 - lon) > 1e-7:
            bad.append(f"uav {uav_id}: {what}: ({it[6]}, {it[7]}) e7 is not within 1e-7 deg of "
                       f"pymap3d's ({lat:.9f}, {lon:.9f})")
        if abs(it[8] - alt) > 1e-3:
            bad.append(f"uav {uav_id}: {what}: alt {it[8]} != {alt}")

    tk, sp = items[0], items[1]
    if (tk[0], tk[1]) != (NAV_TAKEOFF, FRAME_GLOBAL_REL_ALT_INT):
        bad.append(f"uav {uav_id}: item 0 is {tk[0]}/{tk[1]}, not a take-off")
    start_geo = cell_geo(fi, uav["x"], uav["y"])
    near(tk, *start_geo, "take-off")
    if (sp[0], sp[1], sp[2], sp[4]) != (DO_CHANGE_SPEED, FRAME_MISSION, 1, -1):
        bad.append(f"uav {uav_id}: item 1 is not DO_CHANGE_SPEED of the ground speed")
    speed = sp[3]
    plan_speed = (fi["cell_cm"] / 100.0) / (tpc * tick_s)
    if not plan_speed <= speed <= plan_speed * 1.001:
        bad.append(f"uav {uav_id}: speed {speed} m/s is not the plan's {plan_speed} m/s")
    at, at_cell, departure = start_geo, (uav["x"], uav["y"]), uav.get("ready_at", 0)
    for i, tid in enumerate(target_ids):
        t = by_id[tid]
        wp, hold = items[2 + 2 * i], items[3 + 2 * i]
        if (wp[0], wp[1]) != (NAV_WAYPOINT, FRAME_GLOBAL_REL_ALT_INT):
            bad.append(f"uav {uav_id}: item {2 + 2 * i} is {wp[0]}/{wp[1]}, not a waypoint")
        geo = cell_geo(fi, t["x"], t["y"])
        near(wp, *geo, f"target {tid}")
        end_ms = fi["t0_ms"] + t["end"] * fi["tick_ms"]
        if (hold[0], hold[1], hold[2]) != (NAV_DELAY, FRAME_MISSION, -1) or \
                tuple(int(v) for v in hold[3:6]) != tod_of(end_ms):
            bad.append(f"uav {uav_id}: target {tid}: hold {hold[:6]} does not end at "
                       f"{tod_of(end_ms)} UTC")
        if end_ms - (fi["t0_ms"] + departure * fi["tick_ms"]) >= 86_400_000:
            bad.append(f"uav {uav_id}: target {tid}: hold of a day or more")
        # the timing argument: planned departure + path / speed <= window start
        arrive_s = departure * tick_s + path_m(at, geo, alt) / speed
        if arrive_s > t["start"] * tick_s:
            bad.append(f"uav {uav_id}: target {tid}: arrives at {arrive_s:.6f} s, after the "
                       f"start {t['start'] * tick_s:.6f} s")
        at, at_cell, departure = geo, (t["x"], t["y"]), t["end"]
    rtl = items[-1]
    if rtl[0] != NAV_RTL:
        bad.append(f"uav {uav_id}: last item is {rtl[0]}, not RETURN_TO_LAUNCH")
    return bad


def plan_mission(mission: dict, tmp) -> dict:
    """`sva plan` of the mission without its frame (the CLI of this branch)."""
    bare = {k: v for k, v in mission.items() if k != "frame"}
    path = os.path.join(str(tmp), f"{mission['name']}.bare.json")
    with open(path, "w") as f:
        json.dump(bare, f)
    out = subprocess.run([os.environ["SVA_BIN"], "plan", path], check=True,
                         capture_output=True, text=True).stdout
    return json.loads(out)


def tool_input(mission: dict, fr: dict, plan: dict, vehicles: Dict[int, str],
               timeout: str = "") -> str:
    fi = frame_ints(fr)
    lines = ([f"timeout {timeout}"] if timeout else []) + [f"frame {fi['lat_e7']} {fi['lon_e7']} {fi['alt_cm']} {fi['cell_cm']} "
             f"{fi['tick_ms']} {fi['t0_ms']}", f"tpc {mission.get('ticks_per_cell', 1)}"]
    by_id = {t["id"]: t for t in mission["targets"]}
    for r in plan["routes"]:
        u = next(u for u in mission["uavs"] if u["id"] == r["uav"])
        lines.append(f"route {u['id']} {u['x']} {u['y']} {u.get('ready_at', 0)}")
        for tid in r["targets"]:
            t = by_id[tid]
            lines.append(f"target {tid} {t['x']} {t['y']} {t['start']} {t['end']}")
    for uid, spec in vehicles.items():
        lines.append(f"vehicle {uid}={spec}")
    return "\n".join(lines) + "\n"


def run_tool(text: str, timeout: float = 120):
    """The C library's items and upload results: ({uav: [items]}, {uav: result}, rc)."""
    p = subprocess.run([os.environ["SVA_MAVLINK_TOOL"]], input=text, capture_output=True,
                       text=True, timeout=timeout)
    items: Dict[int, list] = {}
    results: Dict[int, str] = {}
    for line in p.stdout.splitlines():
        w = line.split()
        if w[0] == "item":
            items.setdefault(int(w[1]), []).append(
                (int(w[3]), int(w[4]), float(w[5]), float(w[6]), float(w[7]), float(w[8]),
                 int(w[9]), int(w[10]), float(w[11])))
        elif w[0] == "result":
            results[int(w[1])] = " ".join(w[2:])
    return items, results, p.returncode, p.stderr


# --- reports: telemetry in mission terms, recomputed with pymap3d -----------------------

def round_half_away(v: float) -> int:
    return int(math.floor(abs(v) + 0.5)) * (1 if v >= 0 else -1)


def position_e7(fr: dict, east_cells: float, north_cells: float) -> Tuple[int, int]:
    """A WGS84 position (1e-7 degree) east_cells and north_cells (fractions allowed) from
    the frame's origin in its East-North-Up plane."""
    fi = frame_ints(fr)
    cell = fi["cell_cm"] / 100.0
    lat, lon, _ = pymap3d.enu2geodetic(east_cells * cell, north_cells * cell, 0.0,
                                       fi["lat_e7"] / 1e7, fi["lon_e7"] / 1e7, 0.0)
    return round_half_away(float(lat) * 1e7), round_half_away(float(lon) * 1e7)


def cell_of(fr: dict, lat_e7: int, lon_e7: int) -> Tuple[int, int]:
    """The cell a report must give for a position (docs/flight-stack.md: east / cell_m and
    north / cell_m rounded half away from zero)."""
    fi = frame_ints(fr)
    cell = fi["cell_cm"] / 100.0
    e, n, _ = pymap3d.geodetic2enu(lat_e7 / 1e7, lon_e7 / 1e7, 0.0, fi["lat_e7"] / 1e7,
                                   fi["lon_e7"] / 1e7, 0.0)
    return round_half_away(float(e) / cell), round_half_away(float(n) / cell)


def tick_of(fr: dict, gps_ms: int) -> int:
    """report_t.at_ticks for a fix taken at GPS time gps_ms: floor((gps - t0) / tick), >= 0."""
    fi = frame_ints(fr)
    return max(0, (gps_ms - fi["t0_ms"]) // fi["tick_ms"])
