"""A tiny brute force of SPEC 1, written for the tests only: every ordered subset of
targets for every UAV, all combinations; the lexicographic best (max covered, then
min cost) among plans that never half-serve a target."""
import itertools

from sva_tools import model


def sequences(m, u):
    ts = m.targets
    out = [()]
    for k in range(1, len(ts) + 1):
        for perm in itertools.permutations(ts, k):
            if model.route_feasible(m, u, list(perm)):
                out.append(perm)
    return out


def optimum(m):
    """(covered, cost) of the SPEC 1 optimum."""
    per_uav = []
    for u in m.uavs:
        if model.is_stranded(m, u):
            per_uav.append([None])
        else:
            per_uav.append(sequences(m, u))
    best = None
    for combo in itertools.product(*per_uav):
        served = {t.id: 0 for t in m.targets}
        cost = 0
        for u, seq in zip(m.uavs, combo):
            if seq is None:
                continue
            for t in seq:
                served[t.id] += 1
            cost += model.route_distance(m, u, list(seq))
        if any(0 < served[t.id] != t.need for t in m.targets):
            continue
        covered = sum(1 for t in m.targets if served[t.id] == t.need)
        key = (-covered, cost)
        if best is None or key < best:
            best = key
    return -best[0], best[1]
