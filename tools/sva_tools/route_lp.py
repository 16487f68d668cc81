"""The route master's LP bound, by column generation: a lower bound on the cost of every
plan covering at least c targets, computed apart from the core (its own model, COIN-OR
CLP for the LP), to show how much any bound from this relaxation can certify.

The master, over the routes r of each group g of alike UAVs (lambda_r >= 0) and the
targets t (0 <= y_t <= 1):
    min  sum_r cost_r lambda_r
    s.t. sum_{r visits t} lambda_r - need_t y_t = 0     (pi_t)
         sum_t y_t + s >= c                              (mu >= 0)
         sum_{r of g} lambda_r = |g|                     (sigma_g)
the empty route (the flight home) one of each group's, and a slack s >= 0 at the cost
of every UAV's fuel plus one per unit, more than any plan costs, so that the master is
feasible from the empty routes on. A plan covering c targets or more is an integer
point of it (its routes; y_t = 1 on the targets it covers; s = 0), so the LP optimum
bounds its cost from below. Pricing
is exact: a route serves targets in window order (SPEC 1: a.end + leg <= b.start), so
every path of the time DAG is elementary, and the labels (reduced cost, fuel used) at a
target are kept Pareto-best without a cap. At every pricing the Lagrangian value
    z_LP + sum_g |g| min(0, least reduced cost of a route of g)
is a valid bound, so the bound holds when the column generation stops early too; it is
the LP optimum once no route prices out.
"""
from __future__ import annotations

import math
import time
from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Optional

from .model import Mission, Target, Uav, can_follow, can_start, dist_pt, is_stranded, route_distance, sorted_targets

# A label: (reduced cost so far, fuel used, path as nested (target id, previous) pairs).
_Path = Optional[tuple[int, "_Path"]]
_Label = tuple[float, int, _Path]
EPS = 1e-6


@dataclass
class RouteLpBound:
    bound: int | None       # ceil of the best valid bound found (None: none yet)
    lp_value: float         # the last restricted master's LP value
    converged: bool         # no route prices out: bound is the LP optimum's ceil
    stopped_by: str         # "priced out", "time limit", "no new route" or "LP status N" (no optimum)
    iterations: int
    columns: int
    seconds: float
    history: list[float] = field(default_factory=list)  # the Lagrangian value per pricing


def _price(m: Mission, u: Uav, order: list[Target], follow: dict[int, list[Target]],
           pi: dict[int, float], sigma: float, keep: int) -> tuple[list[list[int]], float]:
    """Up to `keep` routes of u with negative reduced cost (least first), as target ids,
    and the least reduced cost over routes with a target (inf when none)."""
    home = {t.id: dist_pt(t, m.depot) for t in order}
    labels: dict[int, list[_Label]] = {t.id: [] for t in order}

    def add(tid: int, cost: float, fuel: int, path: _Path) -> None:
        ls = labels[tid]
        for c, f, _ in ls:
            if c <= cost + EPS and f <= fuel:
                return
        ls[:] = [lab for lab in ls if not (cost <= lab[0] + EPS and fuel <= lab[1])]
        ls.append((cost, fuel, path))

    for t in order:
        if can_start(m, u, t):
            fuel = dist_pt(u, t) + m.hover_fuel
            if fuel + home[t.id] <= u.fuel:
                add(t.id, dist_pt(u, t) - pi[t.id], fuel, (t.id, None))
    ends: list[tuple[float, _Path]] = []
    for a in order:  # window order: every arc into a comes from an earlier target
        for c, f, path in labels[a.id]:
            ends.append((c + home[a.id] - sigma, path))
            for b in follow[a.id]:
                leg = dist_pt(a, b)
                fuel = f + leg + m.hover_fuel
                if fuel + home[b.id] <= u.fuel:
                    add(b.id, c + leg - pi[b.id], fuel, (b.id, path))
    ends.sort(key=lambda e: e[0])
    routes = []
    for rc, end in ends[:keep]:
        if rc >= -EPS:
            break
        ids: list[int] = []
        node = end
        while node is not None:
            ids.append(node[0])
            node = node[1]
        routes.append(ids[::-1])
    return routes, (ends[0][0] if ends else math.inf)


def route_lp_bound(m: Mission, covered: int, start_routes: Sequence[tuple[int, list[int]]] = (),
                   time_limit: float = 600.0, keep: int = 20) -> RouteLpBound:
    """The master's bound on plans covering at least `covered` targets; start_routes
    ((UAV id, target ids), e.g. a plan's) are its first columns besides the empty
    routes, keep the most routes each pricing adds per group of UAVs."""
    from ortools.linear_solver import pywraplp  # imported here: keeps start-up fast

    t0 = time.perf_counter()
    order = sorted_targets(m)
    follow = {a.id: [b for b in order if b.id != a.id and can_follow(m, a, b)] for a in order}
    by_id = {t.id: t for t in m.targets}
    groups: dict[tuple[int, int, int, int], list[Uav]] = {}
    for u in m.uavs:
        if not is_stranded(m, u):
            groups.setdefault((u.x, u.y, u.ready_at, u.fuel), []).append(u)
    group_of = {u.id: key for key, us in groups.items() for u in us}

    solver = pywraplp.Solver.CreateSolver("CLP")
    inf = solver.infinity()
    visit = {t.id: solver.Constraint(0.0, 0.0) for t in m.targets}
    cover = solver.Constraint(float(covered), inf)
    fleet = {key: solver.Constraint(float(len(us)), float(len(us))) for key, us in groups.items()}
    objective = solver.Objective()
    objective.SetMinimization()
    slack = solver.NumVar(0.0, inf, "s")
    objective.SetCoefficient(slack, float(sum(u.fuel for u in m.uavs) + 1))
    cover.SetCoefficient(slack, 1.0)
    for t in m.targets:
        y = solver.NumVar(0.0, 1.0, f"y{t.id}")
        visit[t.id].SetCoefficient(y, -float(t.need))
        cover.SetCoefficient(y, 1.0)
    seen: set[tuple[tuple[int, int, int, int], tuple[int, ...]]] = set()

    def add_route(key: tuple[int, int, int, int], path: list[int]) -> bool:
        if (key, tuple(path)) in seen:
            return False
        seen.add((key, tuple(path)))
        cost = route_distance(m, groups[key][0], [by_id[tid] for tid in path])
        lam = solver.NumVar(0.0, inf, f"r{len(seen)}")
        objective.SetCoefficient(lam, float(cost))
        fleet[key].SetCoefficient(lam, 1.0)
        for tid in path:
            visit[tid].SetCoefficient(lam, 1.0)
        return True

    for key in groups:
        add_route(key, [])
    for uid, path in start_routes:
        if uid in group_of:
            add_route(group_of[uid], path)
    best = -math.inf
    lp_value = math.nan
    history: list[float] = []
    converged = False
    iterations = 0
    added = 1
    stopped_by = "time limit"
    while added > 0 and not converged and time.perf_counter() - t0 < time_limit:
        iterations += 1
        status = solver.Solve()
        if status != pywraplp.Solver.OPTIMAL:
            # An LP the last basis does not solve: once more from scratch.
            fresh = pywraplp.MPSolverParameters()
            fresh.SetIntegerParam(fresh.INCREMENTALITY, fresh.INCREMENTALITY_OFF)
            status = solver.Solve(fresh)
        if status != pywraplp.Solver.OPTIMAL:
            stopped_by = f"LP status {status}"  # the bound so far holds
            break
        lp_value = objective.Value()
        pi = {tid: c.dual_value() for tid, c in visit.items()}
        sigma = {key: row.dual_value() for key, row in fleet.items()}  # before columns go in
        value = lp_value
        added = 0
        converged = True
        for key, us in groups.items():
            routes, least = _price(m, us[0], order, follow, pi, sigma[key], keep)
            value += len(us) * min(0.0, least)
            converged = converged and least >= -EPS
            added += sum(add_route(key, r) for r in routes)
        history.append(value)
        best = max(best, value)
    if not converged and added == 0 and stopped_by == "time limit":
        stopped_by = "no new route"  # the routes priced out were in the master (rounding)
    stopped_by = "priced out" if converged else stopped_by
    bound = None if best == -math.inf else max(0, math.ceil(best - EPS))
    return RouteLpBound(bound, lp_value, converged, stopped_by, iterations, len(seen), time.perf_counter() - t0,
                        history)
