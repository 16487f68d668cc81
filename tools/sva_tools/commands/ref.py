"""`sva-tools ref MISSION`: the exact optimum of SPEC 1's lexicographic objective.

Model (OR-tools CP-SAT): because a UAV stays at a target from its start to its end,
"b may follow a" (a.end + travel(a, b) <= b.start) is a fixed relation that forms a
DAG, so a UAV's route is a path UAV -> targets -> depot over that DAG: per UAV, a
boolean per feasible first target, per feasible pair, per last target and one for
"serves nothing"; flow conservation per UAV and target; fuel (legs + hover per target)
within the UAV's fuel; z_t <=> exactly need UAVs serve t, otherwise none (SPEC 1).
Two solves: maximise sum(z), then fix it and minimise the sum of route distances.
Limits are repeatable: one CP-SAT worker and a deterministic time limit (--det-limit,
CP-SAT's max_deterministic_time, a count of work, not seconds) shared by both solves,
so the result does not depend on machine load; --time-limit is a wall-clock safety net
that a normal run does not reach.
stats: "optimal" (both solves proven optimal), "feasible" (a plan was found),
"lower_bound" (proven lower bound on the cost at the covered count found; equals the
cost when optimal), "covered_upper_bound" (proven bound on coverage),
"deterministic_time" (used) and "det_limit", "stopped_by": proven, det_limit or
time_limit (the safety net: that result is not repeatable).

`ref --bound MISSION`: the fuel-free lower bound. A min-cost flow (OR-tools
SimpleMinCostFlow) over the time-feasibility graph: each UAV sends one unit from its
position, through targets (each target in/out pair carries exactly need units) to the
depot. Ignoring fuel makes it a relaxation: when it is infeasible no complete plan
exists; otherwise its cost is a lower bound on the cost of every complete plan.
Prints {"complete_possible": bool, "lower_bound": int|null, "solve_us": int}.
"""
from __future__ import annotations

import argparse

from .. import io
from ..ref import DET_LIMIT, SAFETY_TIME_LIMIT, fuel_free_bound, solve_ref


def add_parser(sub) -> None:
    ap = sub.add_parser("ref", help="exact optimum (CP-SAT) or fuel-free lower bound",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mission")
    ap.add_argument("--bound", action="store_true", help="print the fuel-free min-cost-flow bound")
    ap.add_argument("--det-limit", type=float, default=DET_LIMIT,
                    help=f"CP-SAT deterministic time for both solves (default {DET_LIMIT:g}; "
                         f"repeatable, unlike a wall-clock limit)")
    ap.add_argument("--time-limit", type=float, default=SAFETY_TIME_LIMIT,
                    help=f"wall-clock safety net in seconds (default {SAFETY_TIME_LIMIT:g}); "
                         f"stats.stopped_by is time_limit when it ended the search")
    ap.add_argument("--workers", type=int, default=1, help="CP-SAT workers (default 1: deterministic)")
    ap.add_argument("-o", "--out", default="-")
    ap.set_defaults(func=run)


def run(args) -> int:
    m = io.load_mission(args.mission)
    if args.bound:
        io.write_json(fuel_free_bound(m), args.out)
        return 0
    p = solve_ref(m, args.time_limit, args.workers, args.det_limit)
    io.write_json(p.to_json(), args.out)
    return 0
