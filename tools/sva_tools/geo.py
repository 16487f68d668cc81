"""Missions from a map and plans onto it, through the mission's geographic frame
(`sva-tools geo`)."""
from __future__ import annotations

import json
import math
from decimal import Decimal
from fractions import Fraction
from typing import Any, Optional

from . import check, frame, io, model, schema

# GeoJSON coordinates are written to 1e-7 degree (about 1 cm), the frame's resolution.
COORD_DIGITS = 7
# RFC 7946 has no crs member; an old-style one naming WGS84 longitude/latitude is let pass.
WGS84_CRS = ("urn:ogc:def:crs:OGC:1.3:CRS84", "urn:ogc:def:crs:OGC::CRS84", "OGC:CRS84", "CRS84")
DEFAULT_ALT_M = 30.0
DEFAULT_UAVS = 1


def _fail(message: str, path: str | None) -> io.InputError:
    return io.InputError(message, path)


def checked_frame(doc: dict[str, Any]) -> frame.Frame:
    """The frame of the command line, by the mission's own rules (named as options)."""
    err = schema.first_error({"name": "x", "depot": {"x": 0, "y": 0}, "uavs": [], "targets": [],
                              "frame": doc}, "mission")
    if err is not None:
        field, _, rule = err.partition(": ")
        option = {"frame.lat": "--depot (latitude)", "frame.lon": "--depot (longitude)",
                  "frame.alt_m": "--alt-m", "frame.cell_m": "--cell-m", "frame.tick_s": "--tick-s",
                  "frame.t0": "--t0"}.get(field, field)
        raise io.InputError(f"{option}: {rule}")
    return frame.Frame.from_json(doc)


def _position(pos: Any, where: str, path: str) -> tuple[float, float]:
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


def _enu(fr: frame.Frame, lat: float, lon: float, where: str, path: str) -> tuple[float, float]:
    try:
        return fr.geodetic_to_enu(lat, lon)
    except frame.FrameError as e:
        raise _fail(f"{where}: {e}", path) from None


def _polygon_centroid(fr: frame.Frame, rings: Any, where: str, path: str) -> tuple[float, float]:
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


def to_cell(fr: frame.Frame, east: float, north: float, where: str, path: str | None) -> tuple[int, int]:
    x, y = frame.snap(east / fr.cell_m), frame.snap(north / fr.cell_m)
    for axis, v, metres in (("east", x, east), ("north", y, north)):
        if not model.SVA_COORD_MIN <= v <= model.SVA_COORD_MAX:
            raise _fail(f"{where}: {axis} {metres:.0f} m is cell {v}, beyond the grid "
                        f"[{model.SVA_COORD_MIN}, {model.SVA_COORD_MAX}] (SVA_COORD_MIN, SVA_COORD_MAX) "
                        f"at cell_m {fr.cell_m:g}", path)
    return x, y


def _instant(fr: frame.Frame, value: Any, where: str, path: str) -> Fraction:
    """Ticks after t0 (exact) of a window bound: seconds after t0, or an ISO 8601 string."""
    if isinstance(value, str):
        try:
            return fr.utc_to_ticks(value)
        except frame.FrameError as e:
            raise _fail(f"{where}: {e}, got {json.dumps(value)}", path) from None
    if isinstance(value, bool) or not isinstance(value, (int, float)) or not math.isfinite(value):
        raise _fail(f"{where}: must be seconds after t0 (a number) or an ISO 8601 date-time, "
                    f"got {schema.json_type(value)}", path)
    exact = Fraction(value) if isinstance(value, int) else Fraction(Decimal(repr(value)))
    return fr.seconds_to_ticks(exact)


def _window(fr: frame.Frame, props: dict[str, Any], where: str, label: str, path: str) -> tuple[int, int]:
    for key in ("start", "end"):
        if key not in props:
            raise _fail(f"{where}: missing key {json.dumps(key)}", path)
    start = _instant(fr, props["start"], f"{where}.start", path)
    end = _instant(fr, props["end"], f"{where}.end", path)
    s_tick, e_tick = math.ceil(start), math.floor(end)
    if s_tick < 0:
        raise _fail(f"{where}.start: must not be before t0, got {json.dumps(props['start'])}", path)
    if e_tick > model.SVA_MAX_TICK:
        raise _fail(f"{where}.end: must be at most SVA_MAX_TICK ({model.SVA_MAX_TICK}) ticks after t0, "
                    f"got tick {e_tick}", path)
    if e_tick <= s_tick:
        raise _fail(f"{where}: the window of {label} holds no tick interval: start rounds up to "
                    f"tick {s_tick}, end down to tick {e_tick} (tick_s "
                    f"{frame.format_ms_offset(fr.tick_ms)[:-2]}); a window needs end > start", path)
    return s_tick, e_tick


def _int_prop(props: dict[str, Any], key: str, lo: int, hi: int, hi_name: str, where: str,
              path: str) -> int:
    v = props[key]
    if isinstance(v, bool) or not isinstance(v, int):
        raise _fail(f"{where}.{key}: must be an integer, got {schema.json_type(v)}", path)
    if v < lo:
        raise _fail(f"{where}.{key}: must be >= {lo}, got {v}", path)
    if v > hi:
        raise _fail(f"{where}.{key}: must be <= {hi_name} ({hi}), got {v}", path)
    return v


def _features(doc: Any, path: str) -> list[Any]:
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
    if len(feats) > model.SVA_MAX_TARGETS:
        raise _fail(f"features: {len(feats)} entries exceed SVA_MAX_TARGETS ({model.SVA_MAX_TARGETS})", path)
    return feats


def mission_from_geojson(doc: Any, path: str, fr: frame.Frame, name: str, uavs: int, fuel: int,
                         ticks_per_cell: int) -> dict[str, Any]:
    """The mission (a SPEC section 3 document with its frame) of a GeoJSON of targets."""
    targets: list[dict[str, Any]] = []
    ids: dict[int, int] = {}
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
        need = _int_prop(props, "need", 1, model.SVA_MAX_UAVS, "SVA_MAX_UAVS", pw, path)
        tid = i + 1
        if "id" in props:
            tid = _int_prop(props, "id", 1, model.SVA_MAX_ID, "SVA_MAX_ID", pw, path)
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
        x, y = to_cell(fr, east, north, gw, path)
        start, end = _window(fr, props, pw, f"target {tid}", path)
        targets.append({"id": tid, "x": x, "y": y, "start": start, "end": end, "need": need})
    mission = {"name": name, "frame": fr.to_json(), "depot": {"x": 0, "y": 0},
               "ticks_per_cell": ticks_per_cell,
               "uavs": [{"id": k, "x": 0, "y": 0, "fuel": fuel} for k in range(1, uavs + 1)],
               "targets": targets}
    io.check(mission, "mission")  # every other rule of SPEC sections 3 and 4
    return mission


# --- geo plan -----------------------------------------------------------------------

def mission_frame(doc: dict[str, Any], path: str) -> frame.Frame:
    if "frame" not in doc:
        raise _fail("mission: missing key \"frame\" (the geo commands need the mission's frame)", path)
    return frame.Frame.from_json(doc["frame"])


def _lon_lat(fr: frame.Frame, x: int, y: int) -> list[float]:
    lat, lon = fr.cell_to_geodetic(x, y)
    return [round(lon, COORD_DIGITS), round(lat, COORD_DIGITS)]


Timing = tuple[list[tuple[int, int]], list[int], list[Optional[int]]]


def route_timing(m: model.Mission, uav: model.Uav, targets: list[model.Target]) -> Timing:
    """The cells of a route (its start, its targets, the depot) and the tick the UAV
    reaches and leaves each (SPEC section 12.2's flight: it leaves as soon as it may,
    waits at a target for its window and leaves at its end; None: it stays at the
    depot)."""
    cells = [(uav.x, uav.y)] + [(t.x, t.y) for t in targets] + [m.depot]
    arrive: list[int] = [uav.ready_at]
    leave: list[int | None] = [uav.ready_at]
    left = uav.ready_at
    for k, t in enumerate(targets):
        arrive.append(left + model.dist_pt(cells[k], cells[k + 1]) * m.ticks_per_cell)
        leave.append(t.end)
        left = t.end
    arrive.append(left + model.dist_pt(cells[-2], cells[-1]) * m.ticks_per_cell)
    leave.append(None)
    return cells, arrive, leave


def plan_geojson(mdoc: dict[str, Any], pdoc: dict[str, Any], mpath: str, ppath: str) -> dict[str, Any]:
    """The plan as a GeoJSON FeatureCollection through the mission's frame."""
    fr = mission_frame(mdoc, mpath)
    if "frame" in pdoc and frame.Frame.from_json(pdoc["frame"]) != fr:
        raise _fail("frame: must be the mission's frame", ppath)
    m, p = io.mission_from_json(mdoc), io.plan_from_json(pdoc)
    violations = check.check_plan(m, p)
    if violations:
        raise _fail(f"not a plan of this mission (SPEC section 1): {violations[0]}", ppath)
    tmap = m.target_by_id()
    stranded = set(p.stranded)
    served: dict[int, list[int]] = {t.id: [] for t in m.targets}
    feats: list[dict[str, Any]] = []

    def utc(tick: int | None, where: str) -> str | None:
        if tick is None:
            return None
        try:
            return fr.tick_to_utc(tick)
        except frame.FrameError as e:
            raise _fail(f"{where}: {e}", ppath) from None

    for u, r in zip(m.uavs, p.routes):
        for tid in r.targets:
            served[tid].append(u.id)
        if u.id in stranded:
            stay: Timing = ([(u.x, u.y), (u.x, u.y)], [u.ready_at, u.ready_at], [None, None])
            cells, arrive, leave = stay
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
