"""The independent SPEC checker of a plan against its mission (`sva-tools check`)."""
from __future__ import annotations

from collections import Counter

from . import model


def check_plan(m: model.Mission, p: model.Plan) -> list[str]:
    """Returns the list of violations of SPEC 1 and 3 (empty when the plan is right)."""
    v: list[str] = []
    tmap = m.target_by_id()
    if p.mission != m.name:
        v.append(f"mission: plan is for {p.mission!r}, mission is {m.name!r}")

    # Every UAV exactly once, in mission order.
    want = [u.id for u in m.uavs]
    got = [r.uav for r in p.routes]
    if got != want:
        known = set(want)
        for uid, n in Counter(got).items():
            if uid not in known:
                v.append(f"routes: uav {uid} is not in the mission")
            elif n > 1:
                v.append(f"routes: uav {uid} has {n} routes, must have exactly 1")
        missing = [uid for uid in want if uid not in set(got)]
        if missing:
            v.append(f"routes: no route for uav(s) {missing}")
        if not missing and len(got) == len(want) and sorted(got) == sorted(want):
            v.append(f"routes: not in mission order (expected uav ids {want}, got {got})")

    uav_by_id = {u.id: u for u in m.uavs}
    served: Counter[int] = Counter()
    stranded_listed = list(p.stranded)
    for uid, n in Counter(stranded_listed).items():
        if n > 1:
            v.append(f"stranded: uav {uid} listed {n} times")
        if uid not in uav_by_id:
            v.append(f"stranded: uav {uid} is not in the mission")
    stranded_set = set(stranded_listed)
    seen_route = set()
    for r in p.routes:
        u = uav_by_id.get(r.uav)
        if u is None or r.uav in seen_route:
            continue
        seen_route.add(r.uav)
        w = f"uav {u.id}"
        cant_return = model.is_stranded(m, u)
        if cant_return:
            if u.id not in stranded_set:
                v.append(f"{w}: fuel {u.fuel} cannot bring it home "
                         f"({model.dist_pt(u, m.depot)} cells), so it must be listed in stranded")
            if r.targets or r.distance != 0 or r.fuel_used != 0:
                v.append(f"{w}: stranded, so its route must be empty with distance 0 and "
                         f"fuel_used 0 (got {len(r.targets)} targets, distance {r.distance}, "
                         f"fuel_used {r.fuel_used})")
            continue
        if u.id in stranded_set:
            v.append(f"{w}: listed in stranded but its fuel {u.fuel} brings it home "
                     f"({model.dist_pt(u, m.depot)} cells)")
        ts = []
        bad_id = False
        for tid in r.targets:
            t = tmap.get(tid)
            if t is None:
                v.append(f"{w}: target {tid} is not in the mission")
                bad_id = True
            else:
                ts.append(t)
        for tid, n in Counter(r.targets).items():
            if n > 1:
                v.append(f"{w}: serves target {tid} {n} times (needs distinct UAVs)")
        for tid in {t.id for t in ts}:
            served[tid] += 1
        if bad_id:
            continue
        if ts:
            t0 = ts[0]
            arrive = u.ready_at + model.dist_pt(u, t0) * m.ticks_per_cell
            if arrive > t0.start:
                v.append(f"{w}: reaches target {t0.id} at tick {arrive}, after its start {t0.start}"
                         f" (ready_at {u.ready_at}, {model.dist_pt(u, t0)} cells)")
            for a, b in zip(ts, ts[1:]):
                arrive = a.end + model.dist_pt(a, b) * m.ticks_per_cell
                if arrive > b.start:
                    v.append(f"{w}: leaves target {a.id} at its end {a.end} and reaches target "
                             f"{b.id} at tick {arrive}, after its start {b.start}")
        dist = model.route_distance(m, u, ts)
        fuel = dist + m.hover_fuel * len(ts)
        if r.distance != dist:
            v.append(f"{w}: distance is {r.distance}, recomputed {dist}")
        if r.fuel_used != fuel:
            v.append(f"{w}: fuel_used is {r.fuel_used}, recomputed {fuel}")
        if fuel > u.fuel:
            v.append(f"{w}: route needs {fuel} fuel (return leg and hover included), "
                     f"has {u.fuel}")

    covered = 0
    uncovered = []
    for t in m.targets:
        n = served[t.id]
        if n == t.need:
            covered += 1
            continue
        uncovered.append(t.id)
        if n > t.need:
            v.append(f"target {t.id}: served by {n} UAVs, needs exactly {t.need}")
        elif n > 0:
            v.append(f"target {t.id}: {n} UAV(s) sent to a target left uncovered "
                     f"(needs {t.need})")
    if p.covered != covered:
        v.append(f"covered: is {p.covered}, recomputed {covered}")
    if Counter(p.uncovered) != Counter(uncovered):
        v.append(f"uncovered: is {sorted(p.uncovered)}, recomputed {sorted(uncovered)}")
    status = "complete" if covered == len(m.targets) else "partial"
    if p.status != status:
        v.append(f"status: is {p.status!r}, recomputed {status!r}")
    cost = sum(r.distance for r in p.routes)
    if p.cost != cost:
        v.append(f"cost: is {p.cost}, sum of route distances is {cost}")
    return v
