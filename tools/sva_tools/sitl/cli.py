"""`sva-tools sitl SCENARIO.json`: the command line (docs/sitl.md)."""
from __future__ import annotations

import argparse
import math
import os
import signal
import subprocess
import sys
from pathlib import Path
from typing import List, Optional

from .. import cbin
from .. import io
from .. import schema
from ..sim import load_scenario
from ..text import shown

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


def parse_frame(text: str) -> dict:
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


def parse_fault(text: str, uav_ids: List[int]) -> dict:
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


def parse_faults(texts: List[str], uav_ids: List[int]) -> List[dict]:
    faults: List[dict] = []
    for text in texts:
        f = parse_fault(text, uav_ids)
        if any(g["uav"] == f["uav"] for g in faults):
            raise Refused(f"--fault: uav {f['uav']} has a fault already: at most one per UAV")
        faults.append(f)
    return faults


def check_speed(frame: dict, ticks_per_cell: int) -> float:
    """The plan's ground speed; Refused when the copter cannot fly it with margin."""
    v = frame["cell_m"] / (ticks_per_cell * frame["tick_s"])
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


def check_takeoff(frame: dict, mission) -> int:
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


def add_parser(sub) -> None:
    from . import __doc__ as doc

    ap = sub.add_parser("sitl", help="fly a scenario with ArduCopter SITL vehicles, sva_node and "
                                     "the MAVLink bridge (root)",
                        description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", help="SCENARIO.json: {mission, events, change_penalty}")
    ap.add_argument("--algo", default="sva", choices=list(cbin.C_ALGORITHMS),
                    help="the node's algorithm (default sva)")
    ap.add_argument("--speedup", type=float, default=10.0,
                    help="simulated seconds per wall second of every vehicle (default 10)")
    ap.add_argument("--frame", default=None, metavar="LAT,LON,ALT_M,CELL_M,TICK_S",
                    help=f"the frame when the mission has none (default {DEFAULT_FRAME}); t0 is "
                         "chosen on the vehicles' clock")
    ap.add_argument("--sitl", default=None, metavar="PATH",
                    help="the arducopter binary (default $SVA_SITL, else ../shared/sitl/arducopter "
                         "beside the repository); its copter.parm is read from the same folder")
    ap.add_argument("--fault", action="append", default=[], metavar="KIND:UAV_ID[:T_S]",
                    help="inject a fault (repeatable, one per UAV): silent-upload (the vehicle's "
                         "link to the bridge goes silent at the next upload's MISSION_COUNT), "
                         "reject-item (one item of the next upload rewritten so the vehicle refuses "
                         "it), reboot (its SITL killed and a fresh one started where it is); T_S: "
                         f"armed at t0 + T_S vehicle seconds, in [0, {MAX_FAULT_S}] (default: "
                         "upload faults from the first upload, reboot at t0)")
    ap.add_argument("-o", "--out", default=None, metavar="LOG.json", help="write the flight log")
    ap.add_argument("--plot", default=None, metavar="PNG", help="draw flown tracks over planned routes")
    ap.add_argument("--quiet", action="store_true", help="no progress bar")
    ap.add_argument("--keep", default=None, metavar="DIR",
                    help="copy the working folders (vehicle, node and bridge output) to DIR")
    ap.set_defaults(func=run)


def _argv(args) -> List[str]:
    argv = ["sitl", args.scenario, "--algo", args.algo, "--speedup", repr(args.speedup)]
    for opt in ("frame", "sitl", "out", "plot", "keep"):
        v = getattr(args, opt)
        if v is not None:
            argv += [f"--{opt}", os.path.abspath(v) if opt in ("sitl", "out", "plot", "keep") else v]
    for fault in args.fault:
        argv += ["--fault", fault]
    if args.quiet:
        argv.append("--quiet")
    return argv


def _default_signals() -> None:
    """SIGINT and SIGTERM as a terminal gives them (an ignored signal stays ignored across
    exec, and a shell cannot trap one ignored on entry)."""
    signal.signal(signal.SIGINT, signal.SIG_DFL)
    signal.signal(signal.SIGTERM, signal.SIG_DFL)


def _netns(argv: List[str]) -> int:
    """Runs `python -m sva_tools ARGV` in a network namespace of its own: the vehicles'
    TCP ports and the LCM multicast stay inside it."""
    from ..lcm import simnode

    if os.geteuid() != 0:
        print("sva-tools: error: sitl: needs root to create the network namespace the vehicles, "
              "the node and the bridge talk in (ip netns)", file=sys.stderr)
        return 2
    helper = simnode.netns_helper()
    if not os.access(helper, os.X_OK):
        print(f"sva-tools: error: sitl: the network namespace helper {helper} is missing "
              "(point SVA_NETNS_RUN at tools/netns/netns_run.sh)", file=sys.stderr)
        return 2
    env = dict(os.environ)
    tools = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = tools + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    # The run gets a session of its own; Ctrl-C or SIGTERM here is passed on to all of
    # it as SIGINT, so the run inside stops its vehicles, node and bridge and the helper
    # deletes the namespace.
    proc = subprocess.Popen([str(helper), sys.executable, "-m", "sva_tools", *argv], env=env,
                            start_new_session=True, preexec_fn=_default_signals)

    def forward(_signum, _frame):
        try:
            os.killpg(proc.pid, signal.SIGINT)
        except ProcessLookupError:
            pass

    old_int = signal.signal(signal.SIGINT, forward)
    old_term = signal.signal(signal.SIGTERM, forward)
    try:
        rc = proc.wait()
    finally:
        signal.signal(signal.SIGINT, old_int)
        signal.signal(signal.SIGTERM, old_term)
    if rc == 77:
        print("sva-tools: error: sitl: could not create a network namespace (ip netns: needs "
              "root and iproute2)", file=sys.stderr)
        return 2
    return rc


def _settings(args):
    from .flight import Settings
    from .vehicle import SitlError, sitl_binary

    mission, events, penalty = load_scenario(args.scenario)
    raw = io.read_json(args.scenario)
    mframe = raw["mission"].get("frame")
    if args.speedup <= 0 or args.speedup > 100:
        raise Refused(f"--speedup: must be in (0, 100], got {args.speedup:g}")
    if mframe is not None:
        if args.frame is not None:
            raise Refused("--frame: the mission has a frame of its own")
        frame = {k: mframe[k] for k in FRAME_KEYS} | {"t0": mframe["t0"]}
    else:
        frame = parse_frame(args.frame or DEFAULT_FRAME) | {"t0": None}
    check_speed(frame, mission.ticks_per_cell)
    check_takeoff(frame, mission)
    faults = parse_faults(args.fault, [u.id for u in mission.uavs])
    for i, e in enumerate(events):
        if e["type"] == "position":
            raise Refused(f"events[{i}].type: position is not flown in SITL (a vehicle cannot be "
                          "blown off course here); the bridge reports positions itself")
    try:
        binary = sitl_binary(args.sitl)
    except SitlError as e:
        raise Refused(str(e)) from None
    defaults = binary.parent / "copter.parm"
    if not defaults.is_file():
        raise Refused(f"--sitl: {defaults} is missing (copter.parm beside the binary)")
    return Settings(args.scenario, mission, events, penalty, frame, args.algo, args.speedup,
                    binary, defaults, os.environ.get("SVA_LCM_URL", "udpm://239.255.76.67:7667?ttl=0"),
                    "SVA_", not args.quiet, faults)


def run(args) -> int:
    try:
        settings = _settings(args)
    except Refused as e:
        print(f"sva-tools: error: {shown(e)}", file=sys.stderr)
        return 2
    if not os.environ.get("SVA_LCM_NETNS"):
        return _netns(_argv(args))
    return fly(args, settings)


def _term(_signum, _frame):
    raise KeyboardInterrupt


def fly(args, settings) -> int:
    import time

    from .flight import Flight
    from .ground import GroundError
    from .judge import end_line
    from .vehicle import SitlError

    signal.signal(signal.SIGTERM, _term)
    signal.signal(signal.SIGINT, _term)
    flight: Optional[Flight] = None
    try:
        flight = Flight(settings)
        flight.start()
        flight.fly()
        flight.wall_s = time.monotonic() - flight.wall0
        flight.close(args.keep)
        log = flight.log()
    except (SitlError, GroundError) as e:
        print(f"sva-tools: error: {shown(args.scenario)}: sitl: {shown(e)}", file=sys.stderr)
        return getattr(e, "status", 1)
    except KeyboardInterrupt:
        print("sva-tools: sitl: interrupted; vehicles, node and bridge stopped", file=sys.stderr)
        return 130
    finally:
        if flight is not None:
            flight.close(args.keep)
    if args.out:
        io.write_json(log, args.out)
    if args.plot:
        from .plot import render
        render(log, args.plot)
    print(end_line(log))
    return 0
