"""PyVRP (0.14) as a peer: a prize-collecting VRP with time windows, need-1 missions only.

Usage: python -m sva_tools.commands.pyvrp_peer MISSION [--time-limit S] [--seed N] [-o PLAN]

Model (SPEC 1, modelled as exactly as a plain VRP allows):
- One optional client per target with prize P = (sum of the UAVs' fuel) + hover_fuel + 1.
  A used vehicle's distance less its way home (the fixed cost below) lies in [0, its
  fuel], so no difference in distance can outweigh one more covered target, and PyVRP's
  objective (distance + fixed costs + uncollected prizes) is SPEC 1's lexicographic
  (covered, cost) exactly: at equal coverage the covered targets' hover fuel and the
  fleet's ways home are constants.
- Service starts exactly at the window's start (tw_early = tw_late = start) and lasts
  end - start; waiting before a window is free (no duration cost) and burns no fuel.
- Durations: Manhattan distance times ticks_per_cell. Distances: Manhattan distance, plus
  hover_fuel on every edge into a client; max_distance = the UAV's fuel, so a route's
  distance in the model is exactly its fuel_used (flying and hovering, return included).
- One vehicle type per distinct (position, fuel, ready_at) with as many vehicles as UAVs
  share it (identical UAVs are interchangeable, so this is the model of one type per UAV):
  it starts at its own position (a depot of the model) no earlier than ready_at and ends
  at the mission's depot, with no shift limit. Its fixed cost is minus its distance home:
  a UAV away from the depot that serves nothing flies home in the plan but costs nothing
  in PyVRP, so this makes the objective the plan's cost less a constant.
- Stranded UAVs (SPEC 1) are left out, and so are targets no UAV can serve (not reachable
  by their start, or not with the fuel to come home), as for the OR-tools peer.
- need > 1 is refused (ValueError): a plain VRP cannot say "all or none of a target's
  copies". Copies with tw_early = tw_late = start would be synchronised and never served
  twice by one UAV, but each copy would earn its prize alone, so partial service would be
  rewarded and the objective would no longer be SPEC 1's. Compare on need-1 sets only.

The search stops at --time-limit seconds of wall clock (pyvrp.stop.MaxRuntime; default 1)
with a fixed --seed: the result depends on the machine's load. stats.solve_us is the wall
time of the whole call, model building included. The plan is built from PyVRP's best
solution with model.make_plan and must still pass `sva-tools check`; stats.feasible is
PyVRP's own verdict (an infeasible best solution is returned as it is, so that the checker
refuses it and the failure is counted, never hidden).
"""
from __future__ import annotations

import time
from dataclasses import dataclass
from typing import Any

from .model import Mission, Plan, Target, Uav, can_start, dist_pt, is_stranded, make_plan

TIME_LIMIT = 1.0
SEED = 1


def servable(m: Mission, u: Uav, t: Target) -> bool:
    """u can reach t by its start and come home with its fuel (t as the only target)."""
    return (can_start(m, u, t)
            and dist_pt(u, t) + m.hover_fuel + dist_pt(t, m.depot) <= u.fuel)


@dataclass
class PeerModel:
    """The PyVRP model of a need-1 mission and how to read its solutions back."""
    model: Any                                     # pyvrp.Model
    targets: list[Target]                        # client k is targets[k]
    groups: dict[tuple[int, int, int, int], list[Uav]]   # vehicle type k: list(groups)[k]


def build_model(m: Mission) -> PeerModel:
    """The model of the module's docstring. Raises ValueError when a target needs more
    than one UAV."""
    from pyvrp import Model

    big = [t.id for t in m.targets if t.need != 1]
    if big:
        raise ValueError(f"pyvrp peer: targets {big[:5]} need more than one UAV; "
                         "PyVRP models need-1 missions only")
    vehicles = [u for u in m.uavs if not is_stranded(m, u)]
    targets = [t for t in m.targets if any(servable(m, u, t) for u in vehicles)]
    groups: dict[tuple[int, int, int, int], list[Uav]] = {}
    for u in vehicles:
        groups.setdefault((u.x, u.y, u.fuel, u.ready_at), []).append(u)
    model = Model()
    points: list[tuple[int, int]] = []
    locations = []
    is_client: list[bool] = []

    def location(x: int, y: int, client: bool) -> Any:
        points.append((x, y))
        is_client.append(client)
        loc = model.add_location(x, y)
        locations.append(loc)
        return loc

    home = model.add_depot(location(m.depot[0], m.depot[1], False))
    starts: dict[tuple[int, int], Any] = {m.depot: home}
    for (x, y, _, _) in groups:
        if (x, y) not in starts:
            starts[(x, y)] = model.add_depot(location(x, y, False))
    for (x, y, fuel, ready), uavs in groups.items():
        # A UAV away from the depot that serves nothing still flies home (SPEC 1) while
        # an unused vehicle costs nothing in PyVRP: the fixed cost -(its way home) makes
        # the objective the plan's cost less a constant (the fleet's ways home).
        model.add_vehicle_type(num_available=len(uavs), start_depot=starts[(x, y)],
                               end_depot=home, tw_early=ready, max_distance=fuel,
                               fixed_cost=-dist_pt((x, y), m.depot),
                               unit_distance_cost=1, unit_duration_cost=0)
    prize = sum(u.fuel for u in vehicles) + m.hover_fuel + 1
    for t in targets:
        model.add_client(location(t.x, t.y, True), service_duration=t.end - t.start,
                         tw_early=t.start, tw_late=t.start, prize=prize, required=False)
    tpc = m.ticks_per_cell
    for i, a in enumerate(locations):
        for j, b in enumerate(locations):
            if i != j:
                d = dist_pt(points[i], points[j])
                model.add_edge(a, b, distance=d + (m.hover_fuel if is_client[j] else 0),
                               duration=d * tpc)
    return PeerModel(model, targets, groups)


def solution_of(pm: PeerModel, plan: Plan) -> Any:
    """The pyvrp.Solution of a project plan (every served target must be a client of the
    model): the model check, an optimal plan must be feasible in the model."""
    from pyvrp import Route, Solution

    data = pm.model.data()
    client = {t.id: k for k, t in enumerate(pm.targets)}
    vtype = {u.id: k for k, uavs in enumerate(pm.groups.values()) for u in uavs}
    routes = [Route(data, [client[tid] for tid in r.targets], vtype[r.uav])
              for r in plan.routes if r.targets]
    return Solution(data, routes)


def solve_pyvrp(m: Mission, time_limit: float = TIME_LIMIT, seed: int = SEED) -> Plan:
    """PyVRP's best plan within time_limit seconds (wall clock). Raises ValueError when a
    target needs more than one UAV."""
    from pyvrp.stop import MaxRuntime

    t0 = time.perf_counter()
    pm = build_model(m)
    base = {"time_limit_s": time_limit, "seed": seed,
            "left_out_targets": len(m.targets) - len(pm.targets)}
    if not pm.groups or not pm.targets:
        return make_plan(m, "pyvrp", {}, dict(base, solve_us=int((time.perf_counter() - t0) * 1e6),
                                               feasible=True, stopped_by="trivial"))
    result = pm.model.solve(stop=MaxRuntime(time_limit), seed=seed, display=False,
                            collect_stats=False)
    best = result.best
    elapsed = time.perf_counter() - t0
    groups = list(pm.groups.values())
    taken = [0] * len(groups)
    assignment: dict[int, list[int]] = {}
    for route in best.routes():
        k = route.vehicle_type()
        uav = groups[k][taken[k]]
        taken[k] += 1
        # A scheduled activity's idx is the client's own index (clients in the order added).
        assignment[uav.id] = [pm.targets[a.idx].id for a in route if a.is_client()]
    stats = dict(base, solve_us=int(elapsed * 1e6), feasible=bool(best.is_feasible()),
                 objective=int(result.cost()) if best.is_feasible() else None,
                 iterations=int(result.num_iterations), stopped_by="time_limit")
    return make_plan(m, "pyvrp", assignment, stats)
