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
from typing import Any, NoReturn

from .. import frame, io, model
from ..geo import (
    COORD_DIGITS,
    DEFAULT_ALT_M,
    DEFAULT_UAVS,
    checked_frame,
    mission_frame,
    mission_from_geojson,
    plan_geojson,
    to_cell,
)
from ..text import shown
from .common import Parser


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

    def parse_known_args(self, args=None, namespace=None):
        namespace, extras = super().parse_known_args(args, namespace)
        if extras:
            self.error(f"unrecognized arguments: {' '.join(extras)}")
        return namespace, extras


def _lat_lon(text: str) -> tuple[float, float]:
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

def _frame_doc(args) -> dict[str, Any]:
    lat, lon = args.depot
    return {"lat": lat, "lon": lon, "alt_m": args.alt_m, "cell_m": args.cell_m,
            "tick_s": args.tick_s, "t0": args.t0}


def _ticks_per_cell(args, fr: frame.Frame) -> int:
    if args.speed is None:
        return args.ticks_per_cell
    if not (math.isfinite(args.speed) and args.speed > 0):
        raise io.InputError(f"--speed: must be > 0 metres per second, got {args.speed}")
    # The planned crossing of a cell never takes less time than the flight does.
    tpc = math.ceil(Fraction(Decimal(repr(fr.cell_m))) /
                    (Fraction(Decimal(repr(args.speed))) * Fraction(fr.tick_ms, 1000)))
    if tpc > model.SVA_MAX_TICKS_PER_CELL:
        raise io.InputError(f"--speed: gives {tpc} ticks per cell, more than SVA_MAX_TICKS_PER_CELL "
                            f"({model.SVA_MAX_TICKS_PER_CELL}); use a larger --tick-s or smaller --cell-m")
    return max(1, tpc)


def run_mission(args) -> int:
    fr = checked_frame(_frame_doc(args))
    tpc = _ticks_per_cell(args, fr)
    name = args.name or os.path.splitext(os.path.basename(args.targets))[0]
    for opt, v, lo, hi, hi_name in (("--uavs", args.uavs, 0, model.SVA_MAX_UAVS, "SVA_MAX_UAVS"),
                                    ("--fuel", args.fuel, 0, model.SVA_MAX_FUEL, "SVA_MAX_FUEL"),
                                    ("--ticks-per-cell", tpc, 1, model.SVA_MAX_TICKS_PER_CELL,
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


def _read(path: str) -> Any:
    try:
        return io.read_json(path)
    except io.InputError as e:
        e.path = path
        raise


def _checked(path: str, kind: str) -> dict[str, Any]:
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
    fr = mission_frame(mdoc, args.mission)
    lat, lon = args.position
    try:
        east, north = fr.geodetic_to_enu(lat, lon)
    except frame.FrameError as e:
        raise io.InputError(f"position: {e}") from None
    x, y = to_cell(fr, east, north, "position", None)
    print(json.dumps({"x": x, "y": y, "east_m": round(east, 3), "north_m": round(north, 3)}))
    return 0


def _cell_arg(text: str) -> tuple[int, int]:
    try:
        x, y = (int(v) for v in text.split(","))
    except ValueError:
        raise argparse.ArgumentTypeError(f"must be X,Y (integers), got {text!r}") from None
    if not all(model.SVA_COORD_MIN <= v <= model.SVA_COORD_MAX for v in (x, y)):
        raise argparse.ArgumentTypeError(f"must be cells in [{model.SVA_COORD_MIN}, {model.SVA_COORD_MAX}], "
                                         f"got {text!r}")
    return x, y


def run_point(args) -> int:
    mdoc = _checked(args.mission, "mission")
    fr = mission_frame(mdoc, args.mission)
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
    mp.add_argument("--fuel", type=_integer, default=model.SVA_MAX_FUEL, metavar="F",
                    help="fuel of each UAV, cells (default SVA_MAX_FUEL: no limit in practice)")
    mp.add_argument("--name", default="", help="mission name (default: the file's name)")
    speed = mp.add_mutually_exclusive_group()
    speed.add_argument("--ticks-per-cell", type=_integer, default=model.DEFAULT_TICKS_PER_CELL, metavar="N",
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
