"""`sva-tools sim SCENARIO.json [--algo A] [--out LOG.json] [--plot FILE.png]`: a live
mission flown tick by tick as ground truth, steered by the on-board planner.

The scenario is `{"mission": MISSION, "events": [EVENT, ...], "change_penalty": N}`
(the last optional). This module flies its own physics (SPEC section 12.2): a UAV flies
each leg x first, then y, one cell per ticks_per_cell ticks, paying 1 fuel when a cell's
step starts; it waits at a target until its start, pays hover_fuel at the start and
leaves at the end; arriving after a start it does not stop; a step in progress is
finished before new orders; with no orders it flies home. A lost UAV vanishes at its
event and reappears on uav_back. A position event puts a UAV in service on its cell
with its fuel (blown off course), a step in progress dropped; off its target's cell
during a visit, it breaks the visit as a loss there would.

At tick 0 (cause "start") and at every tick with events (after applying them) it runs
the C CLI's `sva replan` over the whole history (mission, events so far, now) and gives
every UAV in service the new plan's route as its orders. With `--via lcm` the planner
is a real sva_node over LCM instead (sva_tools.lcm.simnode, in a network namespace of
its own; root); `--kill-node N` then kills it N times with SIGKILL at seeded moments
(`--seed`) and starts it again on its journal (`--state-dir`): it must resume by itself,
and the flight log lists the kills (`node_kills`). It stops when every UAV in
service is home with no orders (or out of fuel) and no window or event is left. The
flight log (docs/live.md) is JSON: tracks, visits, every target's outcome, every
replan with its residual mission and plan, and a summary.

Order of work within tick t: steps ending at t complete and visits ending at t end;
UAVs standing at their next target at its start begin to hover (hover_fuel paid); the
events at t are applied and the planner replans; then every free UAV takes its next
step (its fuel paid). A track entry [t, x, y, fuel] is the state after all of that.
"""
from __future__ import annotations

import argparse
import os
import subprocess
import sys
from pathlib import Path

from .. import cbin, io
from ..lcm.simnode import netns_helper
from ..sim import SimError, load_scenario, simulate, simulate_via_lcm, timeline

# --- the command ---------------------------------------------------------------------


def add_parser(sub) -> None:
    ap = sub.add_parser("sim", help="fly a live-mission scenario, steered by `sva replan`",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("scenario", help="SCENARIO.json: {mission, events, change_penalty}")
    ap.add_argument("--algo", default="sva", choices=list(cbin.C_ALGORITHMS),
                    help="the on-board planner's algorithm (default sva)")
    ap.add_argument("--out", help="flight log JSON (default: stdout, or none with --timeline)")
    ap.add_argument("--timeline", action="store_true",
                    help="print a timeline of events and replans on stdout instead of the log")
    ap.add_argument("--plot", metavar="FILE.png", help="also draw the flight (map and Gantt)")
    ap.add_argument("--via", choices=["cli", "lcm"], default="cli",
                    help="how the planner is reached: cli (`sva replan`, default) or lcm (a "
                         "real sva_node over LCM multicast, in a network namespace made for "
                         "the run; needs root)")
    ap.add_argument("--attach", action="store_true",
                    help="--via lcm: use the sva_node already running (started with the same "
                         "--algorithm and --change-penalty) instead of starting one, and no "
                         "namespace of its own")
    ap.add_argument("--url", default=None,
                    help="--via lcm: LCM provider (default udpm://239.255.76.67:7667?ttl=0)")
    ap.add_argument("--prefix", default=None, help="--via lcm: channel prefix (default SVA_)")
    ap.add_argument("--timeout", type=float, default=10.0,
                    help="--via lcm: seconds to wait for each answer of the node (default 10)")
    ap.add_argument("--kill-node", type=int, default=0, metavar="N",
                    help="--via lcm: SIGKILL the node N times at seeded moments of the flight and "
                         "start it again on its journal (sva_node --state-dir, a temporary folder "
                         "of the run's own); it must resume by itself (default 0)")
    ap.add_argument("--seed", type=int, default=0,
                    help="--kill-node: the seed of the moments (default 0)")
    ap.set_defaults(func=run)


def _argv(args) -> list[str]:
    """The command line of this run, for its re-execution inside a network namespace."""
    argv = ["sim", args.scenario, "--algo", args.algo, "--via", "lcm",
            "--timeout", str(args.timeout), "--kill-node", str(args.kill_node),
            "--seed", str(args.seed)]
    for opt in ("out", "plot", "url", "prefix"):
        if getattr(args, opt) is not None:
            argv += [f"--{opt}", getattr(args, opt)]
    if args.timeline:
        argv.append("--timeline")
    if args.attach:
        argv.append("--attach")
    return argv


def _fly_via_lcm(args, mission, events, penalty) -> dict:
    kw = {k: getattr(args, k) for k in ("url", "prefix") if getattr(args, k) is not None}
    return simulate_via_lcm(mission, events, penalty, args.algo, kill_node=args.kill_node,
                            seed=args.seed, attach=args.attach, timeout=args.timeout, **kw)


def run(args) -> int:
    if args.via == "cli" and (args.attach or args.url or args.prefix):
        print("sva-tools: error: sim: --attach, --url and --prefix need --via lcm",
              file=sys.stderr)
        return 2
    if args.kill_node and (args.via != "lcm" or args.attach or args.kill_node < 0):
        print("sva-tools: error: sim: --kill-node: needs --via lcm and a node of the run's own "
              f"(not --attach), and a count >= 0, got {args.kill_node}", file=sys.stderr)
        return 2
    if args.via == "lcm" and not args.attach and not os.environ.get("SVA_LCM_NETNS"):
        load_scenario(args.scenario)  # a bad scenario is reported before any namespace
        from ..lcm import simnode
        return reexec_in_netns(_argv(args))
    mission, events, penalty = load_scenario(args.scenario)
    try:
        if args.via == "lcm":
            from ..lcm import simnode
            try:
                log = _fly_via_lcm(args, mission, events, penalty)
            except simnode.NodeError as e:
                print(f"sva-tools: error: {args.scenario}: --via lcm: {e}", file=sys.stderr)
                return e.status
        else:
            log = simulate(mission, events, penalty, args.algo)
    except cbin.CliMissing as e:
        print(f"sva-tools: error: sim: {e}", file=sys.stderr)
        return 2
    except SimError as e:
        print(f"sva-tools: error: {args.scenario}: {e}", file=sys.stderr)
        return e.status
    if args.timeline:
        sys.stdout.write(timeline(log))
    if args.out or not args.timeline:
        io.write_json(log, args.out or "-")
    if args.plot:
        from .. import simplot
        simplot.render_flight(log, args.plot)
    return 0


def reexec_in_netns(argv: list[str]) -> int:
    """Runs `python -m sva_tools ARGV` in a fresh network namespace (netns_run.sh) and
    returns its exit status; 2 with a clear message when that cannot be done."""
    if os.geteuid() != 0:
        print("sva-tools: error: sim --via lcm: needs root to create the network namespace "
              "the node and the simulator talk in (ip netns); run it as root, or inside a "
              "namespace made for it (SVA_LCM_NETNS set, as tools/netns/netns_run.sh does)",
              file=sys.stderr)
        return 2
    helper = netns_helper()
    if not os.access(helper, os.X_OK):
        print(f"sva-tools: error: sim --via lcm: the network namespace helper {helper} is "
              "missing (point SVA_NETNS_RUN at tools/netns/netns_run.sh)", file=sys.stderr)
        return 2
    env = dict(os.environ)
    tools = str(Path(__file__).resolve().parents[2])
    env["PYTHONPATH"] = tools + (os.pathsep + env["PYTHONPATH"] if env.get("PYTHONPATH") else "")
    rc = subprocess.run([str(helper), sys.executable, "-m", "sva_tools", *argv], env=env).returncode
    if rc == 77:
        print("sva-tools: error: sim --via lcm: could not create a network namespace "
              "(ip netns: needs root and iproute2)", file=sys.stderr)
        return 2
    return rc
