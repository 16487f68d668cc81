"""IH, the SVA pipeline with an integer LP, and the checks of its traces (`sva-tools ih`)."""
from __future__ import annotations

import time
from dataclasses import dataclass, field
from typing import Any

from . import io, model, solvers


@dataclass
class TpRecord:
    """One transportation problem, in the shape of a `--trace` line."""
    source_uavs: list[int]
    supply: list[int]
    sink_targets: list[int]
    demand: list[int]
    cost: list[list[int | None]]
    flow: list[list[int]] = field(default_factory=list)
    kept: list[bool] = field(default_factory=list)
    cost_total: int = 0
    covered: int = 0


Group = tuple[tuple[tuple[int, int], tuple[int, ...]], list[int]]


def _groups(m: model.Mission, sinks: list[model.Target], ready: list[int], pos: list[tuple[int, int]],
            free_at: list[int], fuel_left: list[int]) -> list[Group]:
    """Source groups for one problem: ready UAVs keyed by (position, reachable sinks),
    ordered by their lowest UAV id, members in id order (as the core does).
    Returns [(key, [uav indices])]."""
    groups: dict[tuple[tuple[int, int], tuple[int, ...]], list[int]] = {}
    for ui in sorted(ready, key=lambda i: m.uavs[i].id):
        reach = []
        for j, t in enumerate(sinks):
            d = model.dist_pt(pos[ui], t)
            if (free_at[ui] + d * m.ticks_per_cell <= t.start
                    and fuel_left[ui] >= d + m.hover_fuel + model.dist_pt(t, m.depot)):
                reach.append(j)
        if reach:
            groups.setdefault((pos[ui], tuple(reach)), []).append(ui)
    first_id = lambda kv: m.uavs[kv[1][0]].id  # noqa: E731
    out = sorted(groups.items(), key=first_id)
    if len(out) > model.SVA_MAX_TP_SOURCES:
        # Mirrors the core's bound: keep the groups with the nearest reachable sink
        # (ties: lower UAV id), numbered in id order (DESIGN.md section 3).
        def near(kv: Group) -> tuple[int, int]:
            (p, reach), members = kv
            return (min(model.dist_pt(p, sinks[j]) for j in reach), m.uavs[members[0]].id)
        out = sorted(sorted(out, key=near)[:model.SVA_MAX_TP_SOURCES], key=first_id)
    return out


def plan_ih(m: model.Mission, records: list[TpRecord] | None = None) -> model.Plan:
    t0 = time.perf_counter()
    n = len(m.uavs)
    pos = [(u.x, u.y) for u in m.uavs]
    free_at = [u.ready_at for u in m.uavs]
    fuel_left = [u.fuel for u in m.uavs]
    routes: list[list[int]] = [[] for _ in range(n)]
    active = [i for i, u in enumerate(m.uavs) if not model.is_stranded(m, u)]
    nproblems = 0
    ncl = 0
    for cl in model.clusters(m):
        ncl += 1
        for c0 in range(0, len(cl), model.SVA_MAX_TP_SINKS):
            sinks = cl[c0:c0 + model.SVA_MAX_TP_SINKS]
            groups = _groups(m, sinks, active, pos, free_at, fuel_left)
            if not groups:
                continue
            supply = [len(g) for _, g in groups]
            demand = [t.need for t in sinks]
            cost = [[model.dist_pt(p, t) if j in reach else None for j, t in enumerate(sinks)]
                    for (p, reach), _ in groups]
            sol = solvers.solve_max_cover(supply, demand, cost)
            nproblems += 1
            if records is not None:
                records.append(TpRecord([m.uavs[g[0]].id for _, g in groups], supply,
                                        [t.id for t in sinks], demand, cost, sol.flow,
                                        sol.kept, sol.cost, sol.covered))
            # Commit: sinks in cluster order, each taking its group's UAVs in id order.
            for gi, (_, members) in enumerate(groups):
                it = iter(members)
                for j, t in enumerate(sinks):
                    for _ in range(sol.flow[gi][j]):
                        ui = next(it)
                        d = model.dist_pt(pos[ui], t)
                        routes[ui].append(t.id)
                        fuel_left[ui] -= d + m.hover_fuel
                        pos[ui] = (t.x, t.y)
                        free_at[ui] = t.end
    us = (time.perf_counter() - t0) * 1e6
    return model.make_plan(m, "ih", {m.uavs[i].id: routes[i] for i in range(n)},
                       {"solve_us": int(us), "clusters": ncl, "transport_problems": nproblems})


# --- checking the C tableau against the integer LP ----------------------------------

@dataclass
class TraceVerdict:
    problems: int = 0
    mismatches: list[str] = field(default_factory=list)   # ILP optimum != cost_total
    drop_worse: int = 0        # max-cover ILP covers more sinks than the tableau kept
    drop_worse_sinks: int = 0  # how many more, summed
    with_drops: int = 0        # problems where the tableau dropped a sink
    drop_costlier: int = 0     # same number kept, but max-cover keeps a cheaper set


def verify_record(rec: dict[str, Any], verdict: TraceVerdict, where: str = "") -> None:
    """Checks one `--trace` line: the integer LP optimum of the problem without the
    dropped sinks (equality demands, supply as upper bounds, given arcs only) equals
    cost_total; and counts whether cover-as-many-as-possible would keep more sinks."""
    verdict.problems += 1
    supply, demand = rec["supply"], rec["demand"]
    cost = rec["cost"]
    dropped = rec.get("dropped") or [False] * len(demand)
    keep = [j for j in range(len(demand)) if not dropped[j]]
    sub_cost = [[row[j] for j in keep] for row in cost]
    sub_dem = [demand[j] for j in keep]
    sol = solvers.solve_exact(supply, sub_dem, sub_cost)
    tag = f"{where}problem {verdict.problems} (sinks {rec.get('sink_targets')})"
    if sol is None:
        verdict.mismatches.append(f"{tag}: the kept sinks cannot be covered at all, "
                                  f"yet the tableau reports cost {rec['cost_total']}")
    elif sol.cost != rec["cost_total"]:
        verdict.mismatches.append(f"{tag}: integer LP optimum {sol.cost} != tableau "
                                  f"cost_total {rec['cost_total']}")
    flow = rec.get("flow")
    if flow is not None:
        # null where there is no arc, like cost
        bad_arc = any(f and c is None for crow, frow in zip(cost, flow) for c, f in zip(crow, frow))
        flow = [[f or 0 for f in frow] for frow in flow]
        total = sum(c * f for crow, frow in zip(cost, flow) for c, f in zip(crow, frow)
                    if c is not None)
        col = [sum(frow[j] for frow in flow) for j in range(len(demand))]
        rowsum = [sum(frow) for frow in flow]
        if (bad_arc or total != rec["cost_total"]
                or any(col[j] != (0 if dropped[j] else demand[j]) for j in range(len(demand)))
                or any(r > s for r, s in zip(rowsum, supply))):
            verdict.mismatches.append(f"{tag}: the traced flow is not a feasible flow of "
                                      f"cost {rec['cost_total']}")
    if any(dropped):
        verdict.with_drops += 1
    mc = solvers.solve_max_cover(supply, demand, cost)
    kept = len(keep)
    if mc.covered > kept:
        verdict.drop_worse += 1
        verdict.drop_worse_sinks += mc.covered - kept
    elif mc.covered == kept and sol is not None and mc.cost < sol.cost:
        verdict.drop_costlier += 1
    elif mc.covered < kept and sol is not None:
        verdict.mismatches.append(f"{tag}: max-cover LP covers {mc.covered} < {kept} kept sinks")


def read_trace(path: str) -> list[dict[str, Any]]:
    """The records of a `--trace` file, each checked against docs/schema/trace.schema.json
    (io.InputError naming the line otherwise)."""
    return io.load_trace(path)


@dataclass
class CompareVerdict:
    missions: int = 0
    same: int = 0          # identical routes
    tie_first: int = 0     # plans differ and the first differing problem was a tie
    tie: int = 0           # routes differ, same covered and cost
    differ: list[str] = field(default_factory=list)  # covered or cost differ
    trace: TraceVerdict = field(default_factory=TraceVerdict)


def compare_mission(m: model.Mission, verdict: CompareVerdict) -> None:
    from . import cbin
    r = cbin.plan_mission(m, "sva", trace=True)
    if r.status != 0 or r.plan is None:
        verdict.differ.append(f"{m.name}: sva plan exited {r.status}: {r.stderr.strip()}")
        return
    verdict.missions += 1
    for rec in r.trace or []:
        verify_record(rec, verdict.trace, f"{m.name}: ")
    recs: list[TpRecord] = []
    p = plan_ih(m, recs)
    a = [(x.uav, x.targets) for x in r.plan.routes]
    b = [(x.uav, x.targets) for x in p.routes]
    if a == b:
        verdict.same += 1
        return
    # Walk both pipelines in step: the first problem they solved differently. When it
    # is the same problem with a different flow of equal cost, the plans diverged
    # through a tie (later problems then start from other UAV positions and fuel).
    cause = "the problems differ before any flow does"
    for k, (c, i) in enumerate(zip(r.trace or [], recs)):
        same_problem = (c["supply"] == i.supply and c["sink_targets"] == i.sink_targets
                        and c["cost"] == i.cost)
        if not same_problem:
            cause = f"problem {k + 1} differs in its sources or sinks"
            break
        cflow = [[f or 0 for f in row] for row in c["flow"]]
        if cflow != i.flow:
            if c["cost_total"] == i.cost_total and c["covered"] == i.covered:
                cause = "tie"
                verdict.tie_first += 1
            else:
                cause = f"problem {k + 1}: different optimum"
            break
    if (r.plan.covered, r.plan.cost) == (p.covered, p.cost):
        verdict.tie += 1
    else:
        verdict.differ.append(f"{m.name}: sva covered {r.plan.covered} cost {r.plan.cost}, "
                              f"ih covered {p.covered} cost {p.cost}; first divergence: {cause}")
