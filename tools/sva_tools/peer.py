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
import time
from typing import Dict, List

from . import io
from . import model as M

SOLUTION_LIMIT = 100
SAFETY_TIME_LIMIT = 300.0


def solve_peer(m: M.Mission, solution_limit: int = SOLUTION_LIMIT,
               time_limit: float = SAFETY_TIME_LIMIT,
               hard_all_or_none: bool = False) -> M.Plan:
    from ortools.constraint_solver import pywrapcp, routing_enums_pb2
    from ortools.util import optional_boolean_pb2

    t0 = time.perf_counter()
    vehicles = [u for u in m.uavs if not M.is_stranded(m, u)]
    nv = len(vehicles)
    # node 0: depot; 1..nv: vehicle starts; then target copies
    locs = [m.depot] + [(u.x, u.y) for u in vehicles]
    copy_target: List[M.Target] = []
    for t in m.targets:
        for _ in range(t.need):
            copy_target.append(t)
            locs.append((t.x, t.y))
    first_copy = 1 + nv
    nn = len(locs)
    if nv == 0 or not copy_target:
        return M.make_plan(m, "peer", {}, {"solve_us": int((time.perf_counter() - t0) * 1e6),
                                           "solution_limit": solution_limit, "stopped_by": "trivial"})
    starts = list(range(1, nv + 1))
    ends = [0] * nv
    mgr = pywrapcp.RoutingIndexManager(nn, nv, starts, ends)
    routing = pywrapcp.RoutingModel(mgr)
    tpc = m.ticks_per_cell

    def d(i, j):
        return abs(locs[i][0] - locs[j][0]) + abs(locs[i][1] - locs[j][1])

    def dist_cb(a, b):
        return d(mgr.IndexToNode(a), mgr.IndexToNode(b))

    def time_cb(a, b):
        i, j = mgr.IndexToNode(a), mgr.IndexToNode(b)
        stay = 0
        if i >= first_copy:
            t = copy_target[i - first_copy]
            stay = t.end - t.start
        return stay + d(i, j) * tpc

    def fuel_cb(a, b):
        i, j = mgr.IndexToNode(a), mgr.IndexToNode(b)
        return d(i, j) + (m.hover_fuel if i >= first_copy else 0)

    dist_i = routing.RegisterTransitCallback(dist_cb)
    time_i = routing.RegisterTransitCallback(time_cb)
    fuel_i = routing.RegisterTransitCallback(fuel_cb)
    routing.SetArcCostEvaluatorOfAllVehicles(dist_i)
    horizon = max([t.end for t in m.targets] + [u.ready_at for u in vehicles]) \
        + 2 * (M.SVA_COORD_MAX - M.SVA_COORD_MIN) * tpc + 1
    routing.AddDimension(time_i, horizon, horizon, False, "time")
    tdim = routing.GetDimensionOrDie("time")
    routing.AddDimensionWithVehicleCapacity(fuel_i, 0, [u.fuel for u in vehicles], True, "fuel")
    for v, u in enumerate(vehicles):
        tdim.CumulVar(routing.Start(v)).SetRange(u.ready_at, horizon)
    penalty = sum(u.fuel for u in vehicles) + 1
    solver = routing.solver()
    k = 0
    for t in m.targets:
        idx = [mgr.NodeToIndex(first_copy + k + c) for c in range(t.need)]
        k += t.need
        for i in idx:
            tdim.CumulVar(i).SetRange(t.start, t.start)
        routing.AddDisjunction(idx, penalty, t.need,
                               routing_enums_pb2.BoundCost.PENALIZE_ONCE
                               if hasattr(routing_enums_pb2, "BoundCost") else
                               pywrapcp.RoutingModel.PENALIZE_ONCE)
        if hard_all_or_none:
            for i in idx[1:]:
                solver.Add(routing.ActiveVar(i) == routing.ActiveVar(idx[0]))
    params = pywrapcp.DefaultRoutingSearchParameters()
    params.first_solution_strategy = routing_enums_pb2.FirstSolutionStrategy.PATH_CHEAPEST_ARC
    params.local_search_metaheuristic = (
        routing_enums_pb2.LocalSearchMetaheuristic.GREEDY_DESCENT)
    ops = params.local_search_operators
    for name in ("use_path_lns", "use_full_path_lns", "use_tsp_lns", "use_inactive_lns"):
        # CP-completion LNS: each neighbour is bounded by lns_time_limit (wall clock).
        setattr(ops, name, optional_boolean_pb2.BOOL_FALSE)
    params.solution_limit = solution_limit
    params.time_limit.FromMilliseconds(int(time_limit * 1000))
    sol = routing.SolveWithParameters(params)
    start_from = "first_solution"
    if sol is None:
        empty = routing.ReadAssignmentFromRoutes([[] for _ in range(nv)], True)
        sol = routing.SolveFromAssignmentWithParameters(empty, params)
        start_from = "all_dropped"
    elapsed = time.perf_counter() - t0
    assignment: Dict[int, List[int]] = {}
    if sol is not None:
        for v, u in enumerate(vehicles):
            seq = []
            i = routing.Start(v)
            while not routing.IsEnd(i):
                n = mgr.IndexToNode(i)
                if n >= first_copy:
                    seq.append(copy_target[n - first_copy].id)
                i = sol.Value(routing.NextVar(i))
            assignment[u.id] = seq
    # All or none, enforced after the search: a partly served target's copies are
    # removed (SPEC 1). Removing a visit keeps a route feasible: by the triangle
    # inequality the shortcut is no longer in distance, fuel or time.
    count: Dict[int, int] = {}
    for seq in assignment.values():
        for tid in seq:
            count[tid] = count.get(tid, 0) + 1
    partial = {t.id for t in m.targets if 0 < count.get(t.id, 0) < t.need}
    for uid in assignment:
        assignment[uid] = [tid for tid in assignment[uid] if tid not in partial]
    status = routing.status()
    if status in (routing_enums_pb2.RoutingSearchStatus.ROUTING_SUCCESS,
                  routing_enums_pb2.RoutingSearchStatus.ROUTING_OPTIMAL):
        stopped = "local_optimum"
    elif status == routing_enums_pb2.RoutingSearchStatus.ROUTING_FAIL_TIMEOUT or \
            elapsed >= 0.98 * time_limit:
        stopped = "time_limit"
    elif status == routing_enums_pb2.RoutingSearchStatus.ROUTING_PARTIAL_SUCCESS_LOCAL_OPTIMUM_NOT_REACHED:
        stopped = "solution_limit"
    else:
        stopped = "no_solution"
    stats = {"solve_us": int(elapsed * 1e6), "solution_limit": solution_limit,
             "start": start_from, "stopped_by": stopped,
             "found": sol is not None, "repaired_targets": len(partial)}
    return M.make_plan(m, "peer", assignment, stats)


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
