"""The exact reference: CP-SAT on the mission's time-expanded DAG, and the fuel-free bound
(`sva-tools ref`)."""
from __future__ import annotations

import time
from typing import TYPE_CHECKING, Any

from .model import Mission, Plan, can_follow, can_start, dist_pt, is_stranded, make_plan

# CP-SAT deterministic time for both solves (docs/tools.md: how it was chosen) and the
# wall-clock safety net, which a normal run never reaches.
DET_LIMIT = 10.0
SAFETY_TIME_LIMIT = 600.0

if TYPE_CHECKING:
    from ortools.sat.python.cp_model import IntVar

    _Vars = dict[int, IntVar]


def _dag(m: Mission) -> list[list[int]]:
    ts = m.targets
    follow = [[j for j, b in enumerate(ts) if j != i and can_follow(m, a, b)]
              for i, a in enumerate(ts)]
    return follow


def solve_ref(m: Mission, time_limit: float = SAFETY_TIME_LIMIT, workers: int = 1,
              det_limit: float = DET_LIMIT) -> Plan:
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
    z = [model.new_bool_var(f"z{k}") for k in range(nt)]
    serve: list[list[IntVar]] = [[] for _ in range(nt)]  # per target: x[u, t] vars
    cost_terms = []
    # per uav: (first arcs {k: var}, pair arcs {(a, b): var}, x {k: var}); None when stranded
    uav_vars: list[tuple[_Vars, dict[tuple[int, int], IntVar], _Vars] | None] = []
    for ui, u in enumerate(m.uavs):
        if is_stranded(m, u):
            uav_vars.append(None)
            continue
        home = dist_pt(u, dep)
        # Targets u can ever serve: reachable as first target, with fuel for
        # position -> t -> depot (triangle inequality: any route through t needs that).
        ok = [k for k, t in enumerate(ts)
              if u.fuel >= dist_pt(u, t) + m.hover_fuel + dist_pt(t, dep)]
        okset = set(ok)
        first = {k: model.new_bool_var(f"f{ui}_{k}") for k in ok if can_start(m, u, ts[k])}
        idle = model.new_bool_var(f"idle{ui}")
        pair = {}
        for a in ok:
            for b in follow[a]:
                if b in okset:
                    pair[(a, b)] = model.new_bool_var(f"p{ui}_{a}_{b}")
        last = {k: model.new_bool_var(f"l{ui}_{k}") for k in ok}
        x = {k: model.new_bool_var(f"x{ui}_{k}") for k in ok}
        model.add_exactly_one(list(first.values()) + [idle])
        inn: dict[int, list[IntVar]] = {k: [] for k in ok}
        out: dict[int, list[IntVar]] = {k: [] for k in ok}
        for (a, b), v in pair.items():
            out[a].append(v)
            inn[b].append(v)
        for k in ok:
            fk = [first[k]] if k in first else []
            model.add(sum(fk + inn[k]) == x[k])
            model.add(sum(out[k] + [last[k]]) == x[k])
            serve[k].append(x[k])
        legs = ([(dist_pt(u, ts[k]), v) for k, v in first.items()]
                + [(dist_pt(ts[a], ts[b]), v) for (a, b), v in pair.items()]
                + [(dist_pt(ts[k], dep), v) for k, v in last.items()]
                + [(home, idle)])
        dist = sum(c * v for c, v in legs if c)
        model.add(dist + m.hover_fuel * sum(x.values()) <= u.fuel)
        cost_terms += [(c, v) for c, v in legs if c]
        uav_vars.append((first, pair, x))
    for k, t in enumerate(ts):
        model.add(sum(serve[k]) == t.need * z[k])

    def make_solver(det: float, wall: float) -> cp_model.CpSolver:
        sol = cp_model.CpSolver()
        sol.parameters.num_workers = workers
        sol.parameters.max_deterministic_time = det
        sol.parameters.max_time_in_seconds = wall
        return sol

    solver = make_solver(det_limit, time_limit)
    model.maximize(sum(z))
    st1 = solver.solve(model)
    det_used = solver.deterministic_time
    feasible = st1 in (cp_model.OPTIMAL, cp_model.FEASIBLE)
    optimal1 = st1 == cp_model.OPTIMAL
    cov_ub = int(round(solver.best_objective_bound)) if feasible else nt
    assignment: dict[int, list[int]] = {}
    lower = None
    optimal = False
    if feasible:
        best = int(round(solver.objective_value))
        for k in range(nt):
            model.add_hint(z[k], solver.value(z[k]))
        model.add(sum(z) == best)
        model.minimize(sum(c * v for c, v in cost_terms))
        # The second solve gets what the first left of det_limit, and at least a
        # tenth of it (deterministic either way).
        left = max(0.1 * det_limit, det_limit - det_used)
        wall_left = max(1.0, time_limit - (time.perf_counter() - t0))
        solver2 = make_solver(left, wall_left)
        st2 = solver2.solve(model)
        det_used += solver2.deterministic_time
        if st2 in (cp_model.OPTIMAL, cp_model.FEASIBLE):
            solver = solver2
            optimal = optimal1 and st2 == cp_model.OPTIMAL
            lower = int(round(solver2.best_objective_bound))
        else:
            # Keep the first solve's plan; its cost is not minimised.
            optimal = False
        for ui, u in enumerate(m.uavs):
            vars_u = uav_vars[ui]
            if vars_u is None:
                continue
            first, pair, x = vars_u
            cur = next((k for k, v in first.items() if solver.value(v)), None)
            seq = []
            while cur is not None:
                seq.append(ts[cur].id)
                cur = next((b for (a, b), v in pair.items() if a == cur and solver.value(v)), None)
            assignment[u.id] = seq
    elapsed = time.perf_counter() - t0
    us = int(elapsed * 1e6)
    p = make_plan(m, "ref", assignment, None)
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


def fuel_free_bound(m: Mission) -> dict[str, Any]:
    """Min-cost flow lower bound of a complete plan, fuel ignored (see module doc)."""
    from ortools.graph.python import min_cost_flow

    t0 = time.perf_counter()
    ts = m.targets
    us = [u for u in m.uavs if not is_stranded(m, u)]
    nu, nt = len(us), len(ts)
    # nodes: uavs [0, nu), target in [nu, nu+nt), target out [nu+nt, nu+2nt), depot
    depot = nu + 2 * nt
    smcf = min_cost_flow.SimpleMinCostFlow()
    for i, u in enumerate(us):
        smcf.add_arc_with_capacity_and_unit_cost(i, depot, 1, dist_pt(u, m.depot))
        for k, t in enumerate(ts):
            if can_start(m, u, t):
                smcf.add_arc_with_capacity_and_unit_cost(i, nu + k, 1, dist_pt(u, t))
    for a, ta in enumerate(ts):
        smcf.add_arc_with_capacity_and_unit_cost(nu + nt + a, depot, ta.need, dist_pt(ta, m.depot))
        for b, tb in enumerate(ts):
            if a != b and can_follow(m, ta, tb):
                smcf.add_arc_with_capacity_and_unit_cost(nu + nt + a, nu + b,
                                                         min(ta.need, tb.need), dist_pt(ta, tb))
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
