"""The OR-tools routing peer (`sva-tools peer`)."""
from __future__ import annotations

import time

from . import model

SOLUTION_LIMIT = 100
SAFETY_TIME_LIMIT = 300.0


def solve_peer(m: model.Mission, solution_limit: int = SOLUTION_LIMIT,
               time_limit: float = SAFETY_TIME_LIMIT,
               hard_all_or_none: bool = False) -> model.Plan:
    from ortools.constraint_solver import pywrapcp, routing_enums_pb2
    from ortools.util import optional_boolean_pb2

    t0 = time.perf_counter()
    vehicles = [u for u in m.uavs if not model.is_stranded(m, u)]
    nv = len(vehicles)
    # node 0: depot; 1..nv: vehicle starts; then target copies
    locs = [m.depot] + [(u.x, u.y) for u in vehicles]
    copy_target: list[model.Target] = []
    for t in m.targets:
        for _ in range(t.need):
            copy_target.append(t)
            locs.append((t.x, t.y))
    first_copy = 1 + nv
    nn = len(locs)
    if nv == 0 or not copy_target:
        return model.make_plan(m, "peer", {}, {"solve_us": int((time.perf_counter() - t0) * 1e6),
                                           "solution_limit": solution_limit, "stopped_by": "trivial"})
    starts = list(range(1, nv + 1))
    ends = [0] * nv
    mgr = pywrapcp.RoutingIndexManager(nn, nv, starts, ends)
    routing = pywrapcp.RoutingModel(mgr)
    tpc = m.ticks_per_cell

    def d(i: int, j: int) -> int:
        return abs(locs[i][0] - locs[j][0]) + abs(locs[i][1] - locs[j][1])

    def dist_cb(a: int, b: int) -> int:
        return d(mgr.IndexToNode(a), mgr.IndexToNode(b))

    def time_cb(a: int, b: int) -> int:
        i, j = mgr.IndexToNode(a), mgr.IndexToNode(b)
        stay = 0
        if i >= first_copy:
            t = copy_target[i - first_copy]
            stay = t.end - t.start
        return stay + d(i, j) * tpc

    def fuel_cb(a: int, b: int) -> int:
        i, j = mgr.IndexToNode(a), mgr.IndexToNode(b)
        return d(i, j) + (m.hover_fuel if i >= first_copy else 0)

    dist_i = routing.RegisterTransitCallback(dist_cb)
    time_i = routing.RegisterTransitCallback(time_cb)
    fuel_i = routing.RegisterTransitCallback(fuel_cb)
    routing.SetArcCostEvaluatorOfAllVehicles(dist_i)
    horizon = max([t.end for t in m.targets] + [u.ready_at for u in vehicles]) \
        + 2 * (model.SVA_COORD_MAX - model.SVA_COORD_MIN) * tpc + 1
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
    assignment: dict[int, list[int]] = {}
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
    count: dict[int, int] = {}
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
    return model.make_plan(m, "peer", assignment, stats)
