"""`sva-tools geo mission|plan|cell|point`: missions from a map and plans onto it, through
the mission's geographic frame (docs/SPEC.md section 3, docs/flight-stack.md).

- `geo mission TARGETS.geojson --depot LAT,LON --cell-m M --tick-s S --t0 ISO
  [--alt-m M] [--uavs N] [--fuel F] [--name NAME] [--ticks-per-cell N | --speed V]`
  prints a mission whose frame has its origin at the depot, cell (0, 0). Each target
  feature (Point, or Polygon by its centroid in the frame's tangent plane) goes to the
  nearest cell (east and north in cells rounded half away from zero); its `start` and
  `end` (seconds after t0, or ISO 8601 date-times with a UTC offset) become ticks, start
  rounded up and end down, so the planned window lies inside the requested one.
- `geo plan MISSION.json PLAN.json` prints the plan as GeoJSON (RFC 7946, [lon, lat]):
  one LineString per UAV (its start, its targets in route order, the depot) with the
  UTC instant it reaches and leaves every vertex, one Point per target, and the depot.
- `geo cell LAT,LON --mission M.json`, `geo point X,Y --mission M.json`: one position
  each way.

Bad input is one line `sva-tools: error: FILE: FIELD: RULE`, exit status 2; a bad
option or argument is one line `sva-tools: error: geo: OPTION: RULE`, exit status 2.
"""
from __future__ import annotations

import argparse
import json
import math
import os
from decimal import Decimal
from fractions import Fraction
from typing import Any, Dict, List, NoReturn, Optional, Tuple

from . import check, io, schema
from . import frame as F
from . import model as M
from .text import Parser, shown

# GeoJSON coordinates are written to 1e-7 degree (about 1 cm), the frame's resolution.
COORD_DIGITS = 7
# RFC 7946 has no crs member; an old-style one naming WGS84 longitude/latitude is let pass.
WGS84_CRS = ("urn:ogc:def:crs:OGC:1.3:CRS84", "urn:ogc:def:crs:OGC::CRS84", "OGC:CRS84", "CRS84")
DEFAULT_ALT_M = 30.0
DEFAULT_UAVS = 1


def _fail(message: str, path: str) -> io.InputError:
    return io.InputError(message, path)


class _Parser(Parser):
    """The geo commands' argparse: a usage error (a bad, missing or unknown option or
    argument) is one line `sva-tools: error: geo: MESSAGE` with exit status 2, as a bad
    value of a file is; plain argparse prints the usage and `PROG: error:` first, and
    leaves unknown arguments to the top-level parser."""

    def error(self, message: str) -> NoReturn:
        name, sep, rest = message.partition(": ")
        if sep and name.startswith("argument "):  # "argument --depot: RULE"
            name = name[len("argument "):]
            message = rest if rest.startswith(name + ":") else f"{name}: {rest}"
        self.exit(2, f"sva-tools: error: geo: {shown(message)}\n")

    def parse_known_args(self, args=None, namespace=None):  # type: ignore[override]
        namespace, extras = super().parse_known_args(args, namespace)
        if extras:
            self.error(f"unrecognized arguments: {' '.join(extras)}")
        return namespace, extras


def _lat_lon(text: str) -> Tuple[float, float]:
    """`LAT,LON` in degrees (a usage error otherwise)."""
    parts = text.split(",")
    try:
        lat, lon = (float(p) for p in parts)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be LAT,LON in degrees, got {text!r}") from None
    if not (math.isfinite(lat) and math.isfinite(lon)) or not -90 <= lat <= 90 or not -180 <= lon <= 180:
        raise argparse.ArgumentTypeError(f"must be LAT in [-90, 90] and LON in [-180, 180], got {text!r}")
    return lat, lon


def _number(text: str):
    """A finite number: an integer when written as one (a usage error otherwise)."""
    try:
        return int(text)
    except ValueError:
        pass
    try:
        v = float(text)
    except ValueError:
        v = math.nan
    if not math.isfinite(v):
        raise argparse.ArgumentTypeError(f"must be a number, got {text!r}")
    return v


def _integer(text: str) -> int:
    try:
        return int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be an integer, got {text!r}") from None


# --- geo mission --------------------------------------------------------------------

def _frame_doc(args) -> Dict[str, Any]:
    lat, lon = args.depot
    return {"lat": lat, "lon": lon, "alt_m": args.alt_m, "cell_m": args.cell_m,
            "tick_s": args.tick_s, "t0": args.t0}


def _checked_frame(doc: Dict[str, Any]) -> F.Frame:
    """The frame of the command line, by the mission's own rules (named as options)."""
    err = schema.first_error({"name": "x", "depot": {"x": 0, "y": 0}, "uavs": [], "targets": [],
                              "frame": doc}, "mission")
    if err is not None:
        field, _, rule = err.partition(": ")
        option = {"frame.lat": "--depot (latitude)", "frame.lon": "--depot (longitude)",
                  "frame.alt_m": "--alt-m", "frame.cell_m": "--cell-m", "frame.tick_s": "--tick-s",
                  "frame.t0": "--t0"}.get(field, field)
        raise io.InputError(f"{option}: {rule}")
    return F.Frame.from_json(doc)


def _position(pos: Any, where: str, path: str) -> Tuple[float, float]:
    """(lat, lon) of a GeoJSON position [lon, lat(, height)]."""
    if (not isinstance(pos, list) or not 2 <= len(pos) <= 3
            or not all(isinstance(v, (int, float)) and not isinstance(v, bool) for v in pos)):
        raise _fail(f"{where}: must be a position [longitude, latitude] (RFC 7946), got "
                    f"{json.dumps(pos)[:60]}", path)
    lon, lat = pos[0], pos[1]
    if not -180 <= lon <= 180:
        raise _fail(f"{where}[0]: longitude must be in [-180, 180], got {lon}", path)
    if not -90 <= lat <= 90:
        raise _fail(f"{where}[1]: latitude must be in [-90, 90], got {lat}", path)
    return float(lat), float(lon)


def _enu(fr: F.Frame, lat: float, lon: float, where: str, path: str) -> Tuple[float, float]:
    try:
        return fr.geodetic_to_enu(lat, lon)
    except F.FrameError as e:
        raise _fail(f"{where}: {e}", path) from None


def _polygon_centroid(fr: F.Frame, rings: Any, where: str, path: str) -> Tuple[float, float]:
    """The centroid (east, north) of a GeoJSON Polygon's area in the tangent plane."""
    from shapely.geometry import Polygon
    from shapely.validation import explain_validity

    if not isinstance(rings, list) or not rings:
        raise _fail(f"{where}: must be an array of linear rings, got {json.dumps(rings)[:60]}", path)
    plane = []
    for r, ring in enumerate(rings):
        if not isinstance(ring, list) or len(ring) < 4:
            raise _fail(f"{where}[{r}]: a linear ring must have at least 4 positions (RFC 7946)", path)
        pts = [_enu(fr, *_position(p, f"{where}[{r}][{i}]", path), f"{where}[{r}][{i}]", path)
               for i, p in enumerate(ring)]
        if ring[0][:2] != ring[-1][:2]:
            raise _fail(f"{where}[{r}]: a linear ring must end where it starts (RFC 7946)", path)
        plane.append(pts)
    poly = Polygon(plane[0], plane[1:])
    if not poly.is_valid:
        raise _fail(f"{where}: must be a valid polygon, got {explain_validity(poly)}", path)
    if poly.area <= 0:
        raise _fail(f"{where}: must enclose an area", path)
    c = poly.centroid
    return c.x, c.y


def _cell(fr: F.Frame, east: float, north: float, where: str, path: str) -> Tuple[int, int]:
    x, y = F.snap(east / fr.cell_m), F.snap(north / fr.cell_m)
    for axis, v, metres in (("east", x, east), ("north", y, north)):
        if not M.SVA_COORD_MIN <= v <= M.SVA_COORD_MAX:
            raise _fail(f"{where}: {axis} {metres:.0f} m is cell {v}, beyond the grid "
                        f"[{M.SVA_COORD_MIN}, {M.SVA_COORD_MAX}] (SVA_COORD_MIN, SVA_COORD_MAX) "
                        f"at cell_m {fr.cell_m:g}", path)
    return x, y


def _instant(fr: F.Frame, value: Any, where: str, path: str) -> Fraction:
    """Ticks after t0 (exact) of a window bound: seconds after t0, or an ISO 8601 string."""
    if isinstance(value, str):
        try:
            return fr.utc_to_ticks(value)
        except F.FrameError as e:
            raise _fail(f"{where}: {e}, got {json.dumps(value)}", path) from None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(f"{where}: must be seconds after t0 (a number) or an ISO 8601 date-time, "
                    f"got {schema.json_type(value)}", path)
    exact = Fraction(value) if isinstance(value, int) else Fraction(Decimal(repr(value)))
    return fr.seconds_to_ticks(exact)


def _window(fr: F.Frame, props: Dict[str, Any], where: str, label: str, path: str) -> Tuple[int, int]:
    for key in ("start", "end"):
        if key not in props:
            raise _fail(f"{where}: missing key {json.dumps(key)}", path)
    start = _instant(fr, props["start"], f"{where}.start", path)
    end = _instant(fr, props["end"], f"{where}.end", path)
    s_tick, e_tick = math.ceil(start), math.floor(end)
    if s_tick < 0:
        raise _fail(f"{where}.start: must not be before t0, got {json.dumps(props['start'])}", path)
    if e_tick > M.SVA_MAX_TICK:
        raise _fail(f"{where}.end: must be at most SVA_MAX_TICK ({M.SVA_MAX_TICK}) ticks after t0, "
                    f"got tick {e_tick}", path)
    if e_tick <= s_tick:
        raise _fail(f"{where}: the window of {label} holds no tick interval: start rounds up to "
                    f"tick {s_tick}, end down to tick {e_tick} (tick_s "
                    f"{F.format_ms_offset(fr.tick_ms)[:-2]}); a window needs end > start", path)
    return s_tick, e_tick


def _int_prop(props: Dict[str, Any], key: str, lo: int, hi: int, hi_name: str, where: str,
              path: str) -> int:
    v = props[key]
    if isinstance(v, bool) or not isinstance(v, int):
        raise _fail(f"{where}.{key}: must be an integer, got {schema.json_type(v)}", path)
    if v < lo:
        raise _fail(f"{where}.{key}: must be >= {lo}, got {v}", path)
    if v > hi:
        raise _fail(f"{where}.{key}: must be <= {hi_name} ({hi}), got {v}", path)
    return v


def _features(doc: Any, path: str) -> List[Any]:
    if not isinstance(doc, dict):
        raise _fail(f"geojson: must be an object, got {schema.json_type(doc)}", path)
    crs = doc.get("crs")
    if crs is not None:
        name = crs.get("properties", {}).get("name") if isinstance(crs, dict) else None
        if name not in WGS84_CRS:
            raise _fail(f"crs: must be WGS84 longitude, latitude (RFC 7946; "
                        f"urn:ogc:def:crs:OGC:1.3:CRS84), got {json.dumps(crs)[:80]}", path)
    if doc.get("type") == "Feature":
        return [doc]
    if doc.get("type") != "FeatureCollection":
        raise _fail(f"type: must be \"FeatureCollection\" or \"Feature\", got "
                    f"{json.dumps(doc.get('type'))}", path)
    feats = doc.get("features")
    if not isinstance(feats, list):
        raise _fail(f"features: must be an array, got {schema.json_type(feats)}", path)
    if len(feats) > M.SVA_MAX_TARGETS:
        raise _fail(f"features: {len(feats)} entries exceed SVA_MAX_TARGETS ({M.SVA_MAX_TARGETS})", path)
    return feats


def mission_from_geojson(doc: Any, path: str, fr: F.Frame, name: str, uavs: int, fuel: int,
                         ticks_per_cell: int) -> Dict[str, Any]:
    """The mission (a SPEC section 3 document with its frame) of a GeoJSON of targets."""
    targets: List[Dict[str, Any]] = []
    ids: Dict[int, int] = {}
    feats = _features(doc, path)
    for i, feat in enumerate(feats):
        where = f"features[{i}]" if doc.get("type") == "FeatureCollection" else "feature"
        if not isinstance(feat, dict) or feat.get("type") != "Feature":
            raise _fail(f"{where}: must be a GeoJSON Feature", path)
        props = feat.get("properties")
        if not isinstance(props, dict):
            raise _fail(f"{where}.properties: must be an object, got {schema.json_type(props)}", path)
        pw = f"{where}.properties"
        if "need" not in props:
            raise _fail(f"{pw}: missing key \"need\"", path)
        need = _int_prop(props, "need", 1, M.SVA_MAX_UAVS, "SVA_MAX_UAVS", pw, path)
        tid = i + 1
        if "id" in props:
            tid = _int_prop(props, "id", 1, M.SVA_MAX_ID, "SVA_MAX_ID", pw, path)
        if tid in ids:
            raise _fail(f"{pw}.id: duplicate id {tid} (first at index {ids[tid]})", path)
        ids[tid] = i
        geom = feat.get("geometry")
        gw = f"{where}.geometry"
        if not isinstance(geom, dict) or geom.get("type") not in ("Point", "Polygon"):
            got = geom.get("type") if isinstance(geom, dict) else geom
            raise _fail(f"{gw}.type: must be \"Point\" or \"Polygon\", got {json.dumps(got)}", path)
        if geom["type"] == "Point":
            lat, lon = _position(geom.get("coordinates"), f"{gw}.coordinates", path)
            east, north = _enu(fr, lat, lon, f"{gw}.coordinates", path)
        else:
            east, north = _polygon_centroid(fr, geom.get("coordinates"), f"{gw}.coordinates", path)
        x, y = _cell(fr, east, north, gw, path)
        start, end = _window(fr, props, pw, f"target {tid}", path)
        targets.append({"id": tid, "x": x, "y": y, "start": start, "end": end, "need": need})
    mission = {"name": name, "frame": fr.to_json(), "depot": {"x": 0, "y": 0},
               "ticks_per_cell": ticks_per_cell,
               "uavs": [{"id": k, "x": 0, "y": 0, "fuel": fuel} for k in range(1, uavs + 1)],
               "targets": targets}
    io.check(mission, "mission")  # every other rule of SPEC sections 3 and 4
    return mission


def _ticks_per_cell(args, fr: F.Frame) -> int:
    if args.speed is None:
        return args.ticks_per_cell
    if not (math.isfinite(args.speed) and args.speed > 0):
        raise io.InputError(f"--speed: must be > 0 metres per second, got {args.speed}")
    # The planned crossing of a cell never takes less time than the flight does.
    tpc = math.ceil(Fraction(Decimal(repr(fr.cell_m))) /
                    (Fraction(Decimal(repr(args.speed))) * Fraction(fr.tick_ms, 1000)))
    if tpc > M.SVA_MAX_TICKS_PER_CELL:
        raise io.InputError(f"--speed: gives {tpc} ticks per cell, more than SVA_MAX_TICKS_PER_CELL "
                            f"({M.SVA_MAX_TICKS_PER_CELL}); use a larger --tick-s or smaller --cell-m")
    return max(1, tpc)


def run_mission(args) -> int:
    fr = _checked_frame(_frame_doc(args))
    tpc = _ticks_per_cell(args, fr)
    name = args.name or os.path.splitext(os.path.basename(args.targets))[0]
    for opt, v, lo, hi, hi_name in (("--uavs", args.uavs, 0, M.SVA_MAX_UAVS, "SVA_MAX_UAVS"),
                                    ("--fuel", args.fuel, 0, M.SVA_MAX_FUEL, "SVA_MAX_FUEL"),
                                    ("--ticks-per-cell", tpc, 1, M.SVA_MAX_TICKS_PER_CELL,
                                     "SVA_MAX_TICKS_PER_CELL")):
        if not lo <= v <= hi:
            raise io.InputError(f"{opt}: must be in [{lo}, {hi}] ({hi_name}), got {v}")
    try:
        doc = io.read_json(args.targets)
    except io.InputError as e:
        e.path = args.targets
        raise
    mission = mission_from_geojson(doc, args.targets, fr, name, args.uavs, args.fuel, tpc)
    io.write_json(mission, args.out)
    return 0


# --- geo plan -----------------------------------------------------------------------

def _mission_frame(doc: Dict[str, Any], path: str) -> F.Frame:
    if "frame" not in doc:
        raise _fail("mission: missing key \"frame\" (the geo commands need the mission's frame)", path)
    return F.Frame.from_json(doc["frame"])


def _lon_lat(fr: F.Frame, x: int, y: int) -> List[float]:
    lat, lon = fr.cell_to_geodetic(x, y)
    return [round(lon, COORD_DIGITS), round(lat, COORD_DIGITS)]


Timing = Tuple[List[Tuple[int, int]], List[int], List[Optional[int]]]


def route_timing(m: M.Mission, uav: M.Uav, targets: List[M.Target]) -> Timing:
    """The cells of a route (its start, its targets, the depot) and the tick the UAV
    reaches and leaves each (SPEC section 12.2's flight: it leaves as soon as it may,
    waits at a target for its window and leaves at its end; None: it stays at the
    depot)."""
    cells = [(uav.x, uav.y)] + [(t.x, t.y) for t in targets] + [m.depot]
    arrive, leave = [uav.ready_at], [uav.ready_at]
    for k, t in enumerate(targets):
        arrive.append(leave[-1] + M.dist_pt(cells[k], cells[k + 1]) * m.ticks_per_cell)
        leave.append(t.end)
    arrive.append(leave[-1] + M.dist_pt(cells[-2], cells[-1]) * m.ticks_per_cell)
    leave.append(None)
    return cells, arrive, leave


def plan_geojson(mdoc: Dict[str, Any], pdoc: Dict[str, Any], mpath: str, ppath: str) -> Dict[str, Any]:
    """The plan as a GeoJSON FeatureCollection through the mission's frame."""
    fr = _mission_frame(mdoc, mpath)
    if "frame" in pdoc and F.Frame.from_json(pdoc["frame"]) != fr:
        raise _fail("frame: must be the mission's frame", ppath)
    m, p = io.mission_from_json(mdoc), io.plan_from_json(pdoc)
    violations = check.check_plan(m, p)
    if violations:
        raise _fail(f"not a plan of this mission (SPEC section 1): {violations[0]}", ppath)
    tmap = m.target_by_id()
    stranded = set(p.stranded)
    served: Dict[int, List[int]] = {t.id: [] for t in m.targets}
    feats: List[Dict[str, Any]] = []

    def utc(tick: Optional[int], where: str) -> Optional[str]:
        if tick is None:
            return None
        try:
            return fr.tick_to_utc(tick)
        except F.FrameError as e:
            raise _fail(f"{where}: {e}", ppath) from None

    for u, r in zip(m.uavs, p.routes):
        for tid in r.targets:
            served[tid].append(u.id)
        if u.id in stranded:
            cells, arrive, leave = [(u.x, u.y), (u.x, u.y)], [u.ready_at, u.ready_at], [None, None]
        else:
            cells, arrive, leave = route_timing(m, u, [tmap[t] for t in r.targets])
        where = f"routes[uav {u.id}]"
        feats.append({"type": "Feature",
                      "geometry": {"type": "LineString", "coordinates": [_lon_lat(fr, *c) for c in cells]},
                      "properties": {"kind": "route", "uav": u.id, "targets": list(r.targets),
                                     "stranded": u.id in stranded, "distance": r.distance,
                                     "distance_m": round(r.distance * fr.cell_m, 2),
                                     "fuel_used": r.fuel_used, "alt_m": fr.alt_m,
                                     "cells": [list(c) for c in cells],
                                     "arrivals": [utc(t, where) for t in arrive],
                                     "departures": [utc(t, where) for t in leave],
                                     "arrival_ticks": arrive, "departure_ticks": leave}})
    uncovered = set(p.uncovered)
    for t in m.targets:
        feats.append({"type": "Feature",
                      "geometry": {"type": "Point", "coordinates": _lon_lat(fr, t.x, t.y)},
                      "properties": {"kind": "target", "id": t.id, "x": t.x, "y": t.y,
                                     "start": utc(t.start, f"targets[id {t.id}]"),
                                     "end": utc(t.end, f"targets[id {t.id}]"),
                                     "start_tick": t.start, "end_tick": t.end, "need": t.need,
                                     "covered": t.id not in uncovered, "served_by": served[t.id]}})
    feats.append({"type": "Feature",
                  "geometry": {"type": "Point", "coordinates": _lon_lat(fr, *m.depot)},
                  "properties": {"kind": "depot", "x": m.depot[0], "y": m.depot[1]}})
    return {"type": "FeatureCollection", "mission": m.name, "algorithm": p.algorithm,
            "frame": fr.to_json(), "features": feats}


def _read(path: str) -> Any:
    try:
        return io.read_json(path)
    except io.InputError as e:
        e.path = path
        raise


def _checked(path: str, kind: str) -> Dict[str, Any]:
    doc = _read(path)
    try:
        io.check(doc, kind)
    except io.InputError as e:
        e.path = path
        raise
    return doc


def run_plan(args) -> int:
    mdoc, pdoc = _checked(args.mission, "mission"), _checked(args.plan, "plan")
    io.write_json(plan_geojson(mdoc, pdoc, args.mission, args.plan), args.out)
    return 0


# --- geo cell, geo point ------------------------------------------------------------

def run_cell(args) -> int:
    mdoc = _checked(args.mission, "mission")
    fr = _mission_frame(mdoc, args.mission)
    lat, lon = args.position
    try:
        east, north = fr.geodetic_to_enu(lat, lon)
    except F.FrameError as e:
        raise io.InputError(f"position: {e}") from None
    x, y = _cell(fr, east, north, "position", None)
    print(json.dumps({"x": x, "y": y, "east_m": round(east, 3), "north_m": round(north, 3)}))
    return 0


def _cell_arg(text: str) -> Tuple[int, int]:
    try:
        x, y = (int(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be X,Y (integers), got {text!r}") from None
    if not all(M.SVA_COORD_MIN <= v <= M.SVA_COORD_MAX for v in (x, y)):
        raise argparse.ArgumentTypeError(f"must be cells in [{M.SVA_COORD_MIN}, {M.SVA_COORD_MAX}], got {text!r}")
    return x, y


def run_point(args) -> int:
    mdoc = _checked(args.mission, "mission")
    fr = _mission_frame(mdoc, args.mission)
    lat, lon = fr.cell_to_geodetic(*args.cell)
    print(json.dumps({"lat": round(lat, COORD_DIGITS), "lon": round(lon, COORD_DIGITS),
                      "alt_m": fr.alt_m}))
    return 0


def add_parser(sub) -> None:
    ap = sub.add_parser("geo", help="missions from GeoJSON, plans to GeoJSON (the mission frame)",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.__class__ = _Parser  # made by the top-level parser; its own errors one line too
    geo = ap.add_subparsers(dest="geo_command", metavar="GEO_COMMAND", parser_class=_Parser)
    geo.required = True

    mp = geo.add_parser("mission", help="a mission from a GeoJSON of targets")
    mp.add_argument("targets", metavar="TARGETS.geojson")
    mp.add_argument("--depot", required=True, type=_lat_lon,
                    metavar="LAT,LON", help="the depot, cell (0, 0) and the frame's origin "
                    "(a negative latitude: --depot=-33.86,151.21)")
    mp.add_argument("--cell-m", required=True, type=_number, metavar="M", help="cell size, metres")
    mp.add_argument("--tick-s", required=True, type=_number, metavar="S", help="tick length, seconds")
    mp.add_argument("--t0", required=True, metavar="ISO", help="UTC instant of tick 0 (ISO 8601, Z or +hh:mm)")
    mp.add_argument("--alt-m", type=_number, default=DEFAULT_ALT_M, metavar="M",
                    help=f"flight altitude above home, metres (default {DEFAULT_ALT_M:g})")
    mp.add_argument("--uavs", type=_integer, default=DEFAULT_UAVS, metavar="N",
                    help=f"UAVs at the depot (default {DEFAULT_UAVS})")
    mp.add_argument("--fuel", type=_integer, default=M.SVA_MAX_FUEL, metavar="F",
                    help="fuel of each UAV, cells (default SVA_MAX_FUEL: no limit in practice)")
    mp.add_argument("--name", default="", help="mission name (default: the file's name)")
    speed = mp.add_mutually_exclusive_group()
    speed.add_argument("--ticks-per-cell", type=_integer, default=M.DEFAULT_TICKS_PER_CELL, metavar="N",
                       help="travel ticks per cell (default 1)")
    speed.add_argument("--speed", type=_number, default=None, metavar="V",
                       help="ground speed, m/s: ticks_per_cell = ceil(cell_m / (V * tick_s))")
    mp.add_argument("-o", "--out", default="-", help="output file (default: stdout)")
    mp.set_defaults(func=run_mission)

    pp = geo.add_parser("plan", help="a plan as GeoJSON (routes, targets, depot)")
    pp.add_argument("mission", metavar="MISSION.json")
    pp.add_argument("plan", metavar="PLAN.json")
    pp.add_argument("-o", "--out", default="-", help="output file (default: stdout)")
    pp.set_defaults(func=run_plan)

    cp = geo.add_parser("cell", help="the cell of a position")
    cp.add_argument("position", type=_lat_lon, metavar="LAT,LON")
    cp.add_argument("--mission", required=True, metavar="M.json", help="a mission with a frame")
    cp.set_defaults(func=run_cell)

    pt = geo.add_parser("point", help="the position of a cell")
    pt.add_argument("cell", type=_cell_arg, metavar="X,Y")
    pt.add_argument("--mission", required=True, metavar="M.json", help="a mission with a frame")
    pt.set_defaults(func=run_point)

