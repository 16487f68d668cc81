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
import sys
import time
from typing import Dict, List, Optional, Tuple

from . import io
from . import model as M

# CP-SAT deterministic time for both solves (docs/tools.md: how it was chosen) and the
# wall-clock safety net, which a normal run never reaches.
DET_LIMIT = 10.0
SAFETY_TIME_LIMIT = 600.0


def _dag(m: M.Mission):
    ts = m.targets
    follow = [[j for j, b in enumerate(ts) if j != i and M.can_follow(m, a, b)]
              for i, a in enumerate(ts)]
    return follow


def solve_ref(m: M.Mission, time_limit: float = SAFETY_TIME_LIMIT, workers: int = 1,
              det_limit: float = DET_LIMIT) -> M.Plan:
    """Both solves share det_limit (CP-SAT deterministic time, a work count: with one
    worker the result does not depend on machine load); time_limit (seconds, wall
    clock) is a safety net only, and stats.stopped_by says when it was hit."""
    from ortools.sat.python import cp_model  # imported here: keeps start-up fast

    t0 = time.perf_counter()
    ts = m.targets
    nt = len(ts)
    follow = _dag(m)
    dep = m.depot
    model = cp_model.CpModel()
    z = [model.NewBoolVar(f"z{k}") for k in range(nt)]
    serve: List[List] = [[] for _ in range(nt)]  # per target: x[u, t] vars
    cost_terms = []
    uav_vars = []  # per uav: (first arcs {k: var}, pair arcs {(a, b): var}, x {k: var})
    for ui, u in enumerate(m.uavs):
        if M.is_stranded(m, u):
            uav_vars.append(None)
            continue
        home = M.dist_pt(u, dep)
        # Targets u can ever serve: reachable as first target, with fuel for
        # position -> t -> depot (triangle inequality: any route through t needs that).
        ok = [k for k, t in enumerate(ts)
              if u.fuel >= M.dist_pt(u, t) + m.hover_fuel + M.dist_pt(t, dep)]
        okset = set(ok)
        first = {k: model.NewBoolVar(f"f{ui}_{k}") for k in ok if M.can_start(m, u, ts[k])}
        idle = model.NewBoolVar(f"idle{ui}")
        pair = {}
        for a in ok:
            for b in follow[a]:
                if b in okset:
                    pair[(a, b)] = model.NewBoolVar(f"p{ui}_{a}_{b}")
        last = {k: model.NewBoolVar(f"l{ui}_{k}") for k in ok}
        x = {k: model.NewBoolVar(f"x{ui}_{k}") for k in ok}
        model.AddExactlyOne(list(first.values()) + [idle])
        inn: Dict[int, list] = {k: [] for k in ok}
        out: Dict[int, list] = {k: [] for k in ok}
        for (a, b), v in pair.items():
            out[a].append(v)
            inn[b].append(v)
        for k in ok:
            fk = [first[k]] if k in first else []
            model.Add(sum(fk + inn[k]) == x[k])
            model.Add(sum(out[k] + [last[k]]) == x[k])
            serve[k].append(x[k])
        legs = ([(M.dist_pt(u, ts[k]), v) for k, v in first.items()]
                + [(M.dist_pt(ts[a], ts[b]), v) for (a, b), v in pair.items()]
                + [(M.dist_pt(ts[k], dep), v) for k, v in last.items()]
                + [(home, idle)])
        dist = sum(c * v for c, v in legs if c)
        model.Add(dist + m.hover_fuel * sum(x.values()) <= u.fuel)
        cost_terms += [(c, v) for c, v in legs if c]
        uav_vars.append((first, pair, x))
    for k, t in enumerate(ts):
        model.Add(sum(serve[k]) == t.need * z[k])
    def make_solver(det: float, wall: float):
        sol = cp_model.CpSolver()
        sol.parameters.num_workers = workers
        sol.parameters.max_deterministic_time = det
        sol.parameters.max_time_in_seconds = wall
        return sol

    solver = make_solver(det_limit, time_limit)
    model.Maximize(sum(z))
    st1 = solver.Solve(model)
    det_used = solver.deterministic_time
    feasible = st1 in (cp_model.OPTIMAL, cp_model.FEASIBLE)
    optimal1 = st1 == cp_model.OPTIMAL
    cov_ub = int(round(solver.BestObjectiveBound())) if feasible else nt
    assignment: Dict[int, List[int]] = {}
    lower = None
    optimal = False
    if feasible:
        best = int(round(solver.ObjectiveValue()))
        for k in range(nt):
            model.AddHint(z[k], solver.Value(z[k]))
        model.Add(sum(z) == best)
        model.Minimize(sum(c * v for c, v in cost_terms))
        # The second solve gets what the first left of det_limit, and at least a
        # tenth of it (deterministic either way).
        left = max(0.1 * det_limit, det_limit - det_used)
        wall_left = max(1.0, time_limit - (time.perf_counter() - t0))
        solver2 = make_solver(left, wall_left)
        st2 = solver2.Solve(model)
        det_used += solver2.deterministic_time
        if st2 in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            solver = solver2
            optimal = optimal1 and st2 == cp_model.OPTIMAL
            lower = int(round(solver2.BestObjectiveBound()))
        else:
            # Keep the first solve's plan; its cost is not minimised.
            optimal = False
        for ui, u in enumerate(m.uavs):
            if uav_vars[ui] is None:
                continue
            first, pair, x = uav_vars[ui]
            cur = next((k for k, v in first.items() if solver.Value(v)), None)
            seq = []
            while cur is not None:
                seq.append(ts[cur].id)
                cur = next((b for (a, b), v in pair.items() if a == cur and solver.Value(v)), None)
            assignment[u.id] = seq
    elapsed = time.perf_counter() - t0
    us = int(elapsed * 1e6)
    p = M.make_plan(m, "ref", assignment, None)
    if optimal:
        stopped = "proven"
    elif elapsed >= 0.98 * time_limit:
        stopped = "time_limit"  # the wall-clock safety net: this result is not repeatable
    else:
        stopped = "det_limit"
    stats = {"optimal": bool(optimal), "feasible": bool(feasible),
             "lower_bound": lower if lower is not None else 0,
             "covered_upper_bound": cov_ub, "solve_us": us,
             "det_limit": det_limit, "deterministic_time": round(det_used, 3),
             "stopped_by": stopped}
    p.stats = stats
    return p


def fuel_free_bound(m: M.Mission) -> dict:
    """Min-cost flow lower bound of a complete plan, fuel ignored (see module doc)."""
    from ortools.graph.python import min_cost_flow

    t0 = time.perf_counter()
    ts = m.targets
    us = [u for u in m.uavs if not M.is_stranded(m, u)]
    nu, nt = len(us), len(ts)
    # nodes: uavs [0, nu), target in [nu, nu+nt), target out [nu+nt, nu+2nt), depot
    depot = nu + 2 * nt
    smcf = min_cost_flow.SimpleMinCostFlow()
    for i, u in enumerate(us):
        smcf.add_arc_with_capacity_and_unit_cost(i, depot, 1, M.dist_pt(u, m.depot))
        for k, t in enumerate(ts):
            if M.can_start(m, u, t):
                smcf.add_arc_with_capacity_and_unit_cost(i, nu + k, 1, M.dist_pt(u, t))
    for a, ta in enumerate(ts):
        smcf.add_arc_with_capacity_and_unit_cost(nu + nt + a, depot, ta.need, M.dist_pt(ta, m.depot))
        for b, tb in enumerate(ts):
            if a != b and M.can_follow(m, ta, tb):
                smcf.add_arc_with_capacity_and_unit_cost(nu + nt + a, nu + b,
                                                         min(ta.need, tb.need), M.dist_pt(ta, tb))
    for i in range(nu):
        smcf.set_node_supply(i, 1)
    for k, t in enumerate(ts):
        smcf.set_node_supply(nu + k, -t.need)
        smcf.set_node_supply(nu + nt + k, t.need)
    smcf.set_node_supply(depot, -nu)
    if nu == 0 and nt == 0:
        return {"complete_possible": True, "lower_bound": 0, "solve_us": 0}
    st = smcf.solve()
    us_ = int((time.perf_counter() - t0) * 1e6)
    if st == smcf.OPTIMAL:
        return {"complete_possible": True, "lower_bound": int(smcf.optimal_cost()), "solve_us": us_}
    return {"complete_possible": False, "lower_bound": None, "solve_us": us_}


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
