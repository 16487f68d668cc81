"""The settings of a SITL flight: its frame, its faults and the checks of its speed and take-off
against what a copter can fly (docs/sitl.md)."""
from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any

from .. import schema
from ..text import shown

if TYPE_CHECKING:
    from ..model import Mission

DEFAULT_FRAME = "47.3977,8.5456,30,25,6"
# The copter's default horizontal speed (WPNAV_SPEED 1000 cm/s; 9.7 m/s measured) and
# the share of it a plan may use: the rest is room to catch up (docs/sitl.md).
COPTER_SPEED_M_S = 10.0
MAX_SPEED_SHARE = 0.6
# A one-cell leg from a hold (the shortest the grid plans): seconds until the copter is
# within the coverage radius (half a cell) of the next cell's point, fitted to
# `tools/bench/sitl_bench.py --legs` at 15, 25 and 30 m cells (4.7 to 5.8 s; jerk-limited
# acceleration and braking), plus a 0.5 s margin: ONE_CELL_BASE_S + ONE_CELL_ROOT_S *
# sqrt(cell_m). The plan must give a cell at least that long.
ONE_CELL_BASE_S = 3.8
ONE_CELL_ROOT_S = 0.4
FRAME_KEYS = ("lat", "lon", "alt_m", "cell_m", "tick_s")
FAULT_KINDS = ("silent-upload", "reject-item", "reboot")
MAX_FAULT_S = 86400


class Refused(Exception):
    """A bad command line or scenario for SITL: one line, exit 2."""


def parse_frame(text: str) -> dict[str, Any]:
    parts = text.split(",")
    if len(parts) != 5:
        raise Refused(f"--frame: must be LAT,LON,ALT_M,CELL_M,TICK_S, got \"{shown(text)[:60]}\"")
    try:
        vals = [float(p) for p in parts]
    except ValueError:
        raise Refused(f"--frame: must be five numbers LAT,LON,ALT_M,CELL_M,TICK_S, got "
                      f"\"{shown(text)[:60]}\"") from None
    doc = dict(zip(FRAME_KEYS, vals))
    errs = schema.errors(dict(doc, t0="2000-01-01T00:00:00Z"), "mission", "frame", "frame")
    if errs:
        raise Refused(f"--frame: {errs[0]}")
    return doc


def parse_fault(text: str, uav_ids: list[int]) -> dict[str, Any]:
    """One --fault KIND:UAV_ID[:T_S] value: {kind, uav, t_s (None: from the start)}."""
    parts = text.split(":")
    if len(parts) not in (2, 3):
        raise Refused(f"--fault: must be KIND:UAV_ID[:T_S], got \"{shown(text)[:60]}\"")
    kind = parts[0]
    if kind not in FAULT_KINDS:
        raise Refused(f"--fault: KIND must be one of {', '.join(FAULT_KINDS)}, got "
                      f"\"{shown(kind)[:40]}\"")
    try:
        uav = int(parts[1])
    except ValueError:
        uav = None
    if uav is None or uav not in uav_ids:
        raise Refused(f"--fault: UAV_ID must be the id of a UAV of the mission "
                      f"({', '.join(map(str, uav_ids))}), got \"{shown(parts[1])[:20]}\"")
    t_s = None
    if len(parts) == 3:
        try:
            t_s = float(parts[2])
        except ValueError:
            t_s = math.nan
        if not (0 <= t_s <= MAX_FAULT_S):
            raise Refused(f"--fault: T_S must be a number of seconds after t0 in [0, {MAX_FAULT_S}], "
                          f"got \"{shown(parts[2])[:20]}\"")
    return {"kind": kind, "uav": uav, "t_s": t_s}


def parse_faults(texts: list[str], uav_ids: list[int]) -> list[dict[str, Any]]:
    faults: list[dict[str, Any]] = []
    for text in texts:
        f = parse_fault(text, uav_ids)
        if any(g["uav"] == f["uav"] for g in faults):
            raise Refused(f"--fault: uav {f['uav']} has a fault already: at most one per UAV")
        faults.append(f)
    return faults


def check_speed(frame: dict[str, Any], ticks_per_cell: int) -> float:
    """The plan's ground speed; Refused when the copter cannot fly it with margin."""
    v: float = frame["cell_m"] / (ticks_per_cell * frame["tick_s"])
    limit = COPTER_SPEED_M_S * MAX_SPEED_SHARE
    if v > limit + 1e-9:
        raise Refused(f"frame: the plan's speed cell_m / (ticks_per_cell * tick_s) = "
                      f"{frame['cell_m']:g} / ({ticks_per_cell} * {frame['tick_s']:g}) = {v:.3g} m/s "
                      f"must be <= {limit:g} m/s ({MAX_SPEED_SHARE:.0%} of the copter's "
                      f"{COPTER_SPEED_M_S:g} m/s WPNAV_SPEED)")
    one_cell_s = ticks_per_cell * frame["tick_s"]
    need_s = one_cell_time_s(frame["cell_m"])
    if one_cell_s < need_s - 1e-9:
        raise Refused(f"frame: a cell takes ticks_per_cell * tick_s = {ticks_per_cell} * "
                      f"{frame['tick_s']:g} = {one_cell_s:.3g} s in the plan, must be >= "
                      f"{need_s:.2f} s: the copter's time from a hold into the coverage radius "
                      f"of a target one {frame['cell_m']:g} m cell away, with margin")
    return v


def check_takeoff(frame: dict[str, Any], mission: Mission) -> int:
    """The ticks a copter on the ground needs before it leaves (arming and the climb to the
    frame's altitude: flight.takeoff_allowance_s): a mission without takeoff_ticks (or 0)
    gets them; Refused when the mission's own are fewer."""
    from .flight import takeoff_allowance_s

    allowance_s = takeoff_allowance_s(frame["alt_m"])
    need = int(math.ceil(allowance_s / frame["tick_s"] - 1e-9))
    if mission.takeoff_ticks == 0:
        mission.takeoff_ticks = need
    elif mission.takeoff_ticks < need:
        raise Refused(f"mission.takeoff_ticks: must be >= {need} (the copter's take-off to "
                      f"{frame['alt_m']:g} m, {allowance_s} s, in {frame['tick_s']:g} s ticks), "
                      f"got {mission.takeoff_ticks}")
    return mission.takeoff_ticks


def one_cell_time_s(cell_m: float) -> float:
    """The least plan time for one cell (see ONE_CELL_BASE_S)."""
    return ONE_CELL_BASE_S + ONE_CELL_ROOT_S * math.sqrt(cell_m)
