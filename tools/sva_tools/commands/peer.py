"""`sva-tools peer MISSION`: the general-purpose alternative, OR-tools' routing solver.

Model (docs/tools.md): one vehicle per UAV that can get home (start node at its
position, end node at the depot); each target t becomes t.need copies, nodes with
the time cumul fixed to t.start (arrive by the start, wait allowed) and a transit of
(t.end - t.start) + travel out of them, so every copy is synchronised at t.start and
no UAV can take two copies of one target. Fuel is a dimension with per-vehicle
capacity (the UAV's fuel): transit = leg distance + hover_fuel out of a copy. The
copies of a target form one disjunction (max cardinality need, penalty paid once when
not all are served: partial service only adds cost), and the penalty exceeds any
possible cost, so coverage comes first. Arc cost = distance. All or none is then
enforced on the solution: copies of a target served only in part are removed (always
feasible: a shortcut is no longer in distance, fuel or time; stats.repaired_targets
counts them). The hard form (a constraint keeping a target's copies all active or all
inactive, --hard-all-or-none) is available but makes the routing heuristics fail to
find any first solution on most missions of 25 targets (measured: docs/tools.md).

Search limits are fixed so runs repeat: first solution PATH_CHEAPEST_ARC (starting
from the all-dropped solution when that heuristic finds nothing), then greedy descent
(local search until no neighbour improves: a local optimum) capped at --solution-limit
solutions (default 100). Neither depends on the clock or on machine load. The
routing library has no iteration or branch limit in its search parameters, only
solution_limit and two wall-clock limits: time_limit and lns_time_limit, which bounds
the completion search of the CP-based LNS operators (path, full path, TSP, inactive
LNS); those operators are switched off here (they are off by default too), so
lns_time_limit plays no part. Guided local search was tried and dropped: it never
stops on its own, so only a wall-clock limit ends it, and that is not repeatable.
--time-limit (default 300 s) is a safety net only; stats.stopped_by says what ended
the search: local_optimum, solution_limit, time_limit (not repeatable) or no_solution.
"""
from __future__ import annotations

import argparse

from .. import io
from ..peer import SAFETY_TIME_LIMIT, SOLUTION_LIMIT, solve_peer


def add_parser(sub) -> None:
    ap = sub.add_parser("peer", help="OR-tools routing solver with synchronised copies",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mission")
    ap.add_argument("--solution-limit", type=int, default=SOLUTION_LIMIT,
                    help=f"stop the greedy descent after this many solutions (default {SOLUTION_LIMIT})")
    ap.add_argument("--time-limit", type=float, default=SAFETY_TIME_LIMIT,
                    help=f"wall-clock safety net in seconds (default {SAFETY_TIME_LIMIT:g}); "
                         f"stats.stopped_by is time_limit when it ended the search")
    ap.add_argument("--hard-all-or-none", action="store_true",
                    help="constrain each target's copies to be all active or all inactive")
    ap.add_argument("-o", "--out", default="-")
    ap.set_defaults(func=run)


def run(args) -> int:
    m = io.load_mission(args.mission)
    p = solve_peer(m, args.solution_limit, args.time_limit, args.hard_all_or_none)
    io.write_json(p.to_json(), args.out)
    return 0
