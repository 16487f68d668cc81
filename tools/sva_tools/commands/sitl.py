"""`sva-tools sitl SCENARIO.json [--algo A] [--speedup N] [--frame LAT,LON,ALT_M,CELL_M,TICK_S]
[--sitl PATH] [--out LOG.json] [--plot PNG]`: a scenario flown by real autopilots.

One ArduCopter SITL process per UAV of the mission (home at its start cell), sva_node
and sva_mavlink_bridge over LCM, all in a network namespace made for the run (root).
The node plans, the bridge uploads each route as a MAVLink mission and reports every
vehicle's telemetry back to the node; the tool is the ground operator (it arms each
vehicle in AUTO once it holds a mission) and makes the scenario's events real at their
ticks on the vehicles' GPS clock: uav_lost kills a vehicle's process, uav_back starts a
fresh one on its cell, the other events are published as a ground station would.

The frame is the mission's, else --frame (default 47.3977,8.5456,30,25,6: 25 m cells,
6 s ticks, 30 m above home; t0 chosen on the vehicles' clock). A frame whose plan speed
cell_m / (ticks_per_cell * tick_s) exceeds 6 m/s, or whose cell is shorter in time than
the copter needs for a one-cell leg from a hold, is refused; the vehicles are commanded
10 m/s. Coverage is judged from
each vehicle's telemetry: present within max(cell_m / 2, 5 m) of the target for its
whole window. The last line: `covered C of K coverable (plan promised P); arrival slack
p50 X s, p1 Y s; late arrivals N`. --fault KIND:UAV_ID[:T_S] (repeatable) makes a vehicle
fail: silent-upload (its link to the bridge goes silent at an upload), reject-item (the
vehicle refuses an upload), reboot (a fresh SITL where it is). docs/sitl.md has the
details and measurements.
"""
from __future__ import annotations

import argparse
import os
import shutil
import signal
import subprocess
import sys
import tempfile
import time
from pathlib import Path

from .. import cbin, io
from ..sim import load_scenario
from ..sitl.settings import (
    DEFAULT_FRAME,
    FRAME_KEYS,
    MAX_FAULT_S,
    Refused,
    check_speed,
    check_takeoff,
    parse_faults,
    parse_frame,
)
from ..text import shown


def add_parser(sub) -> None:
    ap = sub.add_parser("sitl", help="fly a scenario with ArduCopter SITL vehicles, sva_node and "
                                     "the MAVLink bridge (root)",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
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


def _argv(args) -> list[str]:
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


STOP_SIGNALS = (signal.SIGINT, signal.SIGTERM)
FOLDER_ENV = "SVA_SITL_FOLDER"  # the working folder the namespace's run uses (made outside)
# In that folder once the run inside stops on SIGINT itself: before, its interpreter is
# still starting, and a SIGINT there ends it with Python's fatal error, which no code of
# the tool can catch. A stop asked before it is up waits for it (UP_WAIT_S at most).
UP_MARK = ".up"
UP_WAIT_S = 30.0


def _default_signals() -> None:
    """SIGINT and SIGTERM as a terminal gives them (an ignored signal stays ignored across
    exec, and a shell cannot trap one ignored on entry), and not blocked (a blocked mask is
    inherited too)."""
    for sig in STOP_SIGNALS:
        signal.signal(sig, signal.SIG_DFL)
    signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)


def _ended(rc: int, stopped: bool) -> int:
    """The run's status, said once when the run inside could not say it itself."""
    if rc == 77:
        print("sva-tools: error: sitl: could not create a network namespace (ip netns: needs "
              "root and iproute2)", file=sys.stderr)
        return 2
    if rc > 128 and not (stopped and rc == 130):
        try:
            name = signal.Signals(rc - 128).name
        except ValueError:
            name = f"signal {rc - 128}"
        print(f"sva-tools: error: sitl: the flight was ended by {name}; its vehicles, node and "
              "bridge ended with it", file=sys.stderr)
    return rc


def _netns(argv: list[str]) -> int:
    """Runs `python -m sva_tools ARGV` in a network namespace of its own: the vehicles'
    TCP ports and the LCM multicast stay inside it. The working folder is made here and
    removed here, so it goes even when the run inside is killed."""
    from ..lcm import simnode
    from ..sitl.flight import FOLDER_PREFIX

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
    stopped = False
    forwarded = False
    asked = 0.0  # when the stop was asked (monotonic)

    def pass_on() -> None:
        nonlocal forwarded
        forwarded = True
        try:
            os.killpg(proc.pid, signal.SIGINT)
        except ProcessLookupError:
            pass

    def forward(_signum, _frame):
        nonlocal stopped, asked
        if not stopped:
            stopped = True
            asked = time.monotonic()
        if os.path.exists(os.path.join(folder, UP_MARK)):
            pass_on()

    # The run gets a session of its own; Ctrl-C or SIGTERM here is passed on to all of
    # it as SIGINT, so the run inside stops its vehicles, node and bridge and the helper
    # deletes the namespace. The signals wait, blocked, until the forwarding is in place.
    folder = tempfile.mkdtemp(prefix=FOLDER_PREFIX)
    env[FOLDER_ENV] = folder
    old = {sig: signal.getsignal(sig) for sig in STOP_SIGNALS}
    try:
        signal.pthread_sigmask(signal.SIG_BLOCK, STOP_SIGNALS)
        proc = subprocess.Popen([str(helper), sys.executable, "-m", "sva_tools", *argv], env=env,
                                start_new_session=True, preexec_fn=_default_signals)
        for sig in STOP_SIGNALS:
            signal.signal(sig, forward)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)
        while True:
            try:
                rc = proc.wait(timeout=0.05)
                break
            except subprocess.TimeoutExpired:
                if stopped and not forwarded and (
                        os.path.exists(os.path.join(folder, UP_MARK))
                        or time.monotonic() - asked > UP_WAIT_S):
                    pass_on()
    finally:
        for sig, handler in old.items():
            signal.signal(sig, handler)
        signal.pthread_sigmask(signal.SIG_UNBLOCK, STOP_SIGNALS)
        shutil.rmtree(folder, ignore_errors=True)
    return _ended(rc, stopped)


def _settings(args):
    from ..sitl.flight import Settings
    from ..sitl.vehicle import SitlError, sitl_binary

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
                    "SVA_", not args.quiet, faults,
                    Path(os.environ[FOLDER_ENV]) if os.environ.get(FOLDER_ENV) else None)


def run(args) -> int:
    try:
        settings = _settings(args)
    except Refused as e:
        print(f"sva-tools: error: {shown(e)}", file=sys.stderr)
        return 2
    if not os.environ.get("SVA_LCM_NETNS"):
        return _netns(_argv(args))
    return fly(args, settings)


def _stop(_signum, _frame):
    """The first SIGINT or SIGTERM stops the flight; later ones wait for its cleanup."""
    from ..sitl.flight import ask_stop

    for sig in STOP_SIGNALS:
        signal.signal(sig, signal.SIG_IGN)
    ask_stop()  # raised again by the flight's loop if this raise is lost
    raise KeyboardInterrupt


def fly(args, settings) -> int:
    from ..sitl.flight import Flight, stop_asked
    from ..sitl.ground import GroundError
    from ..sitl.judge import end_line
    from ..sitl.vehicle import SitlError

    for sig in STOP_SIGNALS:
        signal.signal(sig, _stop)
    if settings.folder is not None:
        (settings.folder / UP_MARK).touch()  # the outside may pass a stop on from now
    flight: Flight | None = None
    try:
        flight = Flight(settings)
        flight.start()
        flight.fly()
        flight.wall_s = time.monotonic() - flight.wall0
        flight.close(args.keep)
        log = flight.log()
        if stop_asked():
            raise KeyboardInterrupt  # asked after the last pump, its own raise lost
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
        from ..sitl.plot import render
        render(log, args.plot)
    print(end_line(log))
    return 0
