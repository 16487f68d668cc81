"""Basic SPEC section 1/3 invariants of a plan JSON against its mission JSON.

A stand-in until the independent checker (`sva-tools check`) lands on main: routes one
per UAV in mission order, legs and distances recomputed, fuel, time windows, coverage
exactly `need` distinct UAVs, uncovered targets not served, cost, status."""


def check_plan(mission: dict, plan: dict) -> list[str]:
    errs = []
    depot = (mission["depot"]["x"], mission["depot"]["y"])
    tpc = mission.get("ticks_per_cell", 1)
    hover = mission.get("hover_fuel", 0)
    targets = {t["id"]: t for t in mission["targets"]}
    uavs = mission["uavs"]

    def dist(a, b):
        return abs(a[0] - b[0]) + abs(a[1] - b[1])

    if plan["mission"] != mission["name"]:
        errs.append("mission name differs")
    if [r["uav"] for r in plan["routes"]] != [u["id"] for u in uavs]:
        errs.append("routes are not one per UAV in mission order")
        return errs
    served = {tid: set() for tid in targets}
    stranded = set(plan.get("stranded", []))
    total = 0
    for u, r in zip(uavs, plan["routes"]):
        pos, t_free, d = (u["x"], u["y"]), u.get("ready_at", 0), 0
        for tid in r["targets"]:
            if tid not in targets:
                errs.append(f"uav {u['id']}: unknown target {tid}")
                continue
            t = targets[tid]
            leg = dist(pos, (t["x"], t["y"]))
            if t_free + leg * tpc > t["start"]:
                errs.append(f"uav {u['id']}: reaches target {tid} after its start")
            if u["id"] in served[tid]:
                errs.append(f"uav {u['id']}: serves target {tid} twice")
            served[tid].add(u["id"])
            d += leg
            pos, t_free = (t["x"], t["y"]), t["end"]
        if r["targets"] or pos != depot:
            d += dist(pos, depot)
        if u["id"] in stranded:
            if r["targets"]:
                errs.append(f"uav {u['id']}: stranded but given targets")
            d = r["distance"]
        if r["distance"] != d:
            errs.append(f"uav {u['id']}: distance {r['distance']}, recomputed {d}")
        if not u["id"] in stranded:
            fuel = d + hover * len(r["targets"])
            if r["fuel_used"] != fuel:
                errs.append(f"uav {u['id']}: fuel_used {r['fuel_used']}, recomputed {fuel}")
            if fuel > u["fuel"]:
                errs.append(f"uav {u['id']}: needs {fuel} fuel, has {u['fuel']}")
        total += r["distance"]
    covered = [tid for tid, s in served.items() if len(s) == targets[tid]["need"]]
    for tid, s in served.items():
        if s and len(s) != targets[tid]["need"]:
            errs.append(f"target {tid}: served by {len(s)} UAVs, needs {targets[tid]['need']}")
    want_uncovered = [t["id"] for t in mission["targets"] if t["id"] not in covered]
    if plan["uncovered"] != want_uncovered:
        errs.append(f"uncovered {plan['uncovered']}, recomputed {want_uncovered}")
    if plan["covered"] != len(covered):
        errs.append(f"covered {plan['covered']}, recomputed {len(covered)}")
    if plan["cost"] != total:
        errs.append(f"cost {plan['cost']}, sum of distances {total}")
    want_status = "complete" if not want_uncovered else "partial"
    if plan["status"] != want_status:
        errs.append(f"status {plan['status']}, expected {want_status}")
    return errs
