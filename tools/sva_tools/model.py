"""The problem of SPEC section 1 and the shared rules of section 2, in plain Python.

Everything here is recomputed from the SPEC text, never taken from the C core: the
checker, the reference solver, IH and the generator all build on these functions.
"""
from __future__ import annotations

from collections.abc import Sequence
from dataclasses import dataclass, field
from typing import Any

# Bounds of the core's default profile (core/include/sva/sva_config.h). The host tools
# reject what the default build of the C CLI rejects, naming the same limit.
SVA_COORD_MIN = -32768
SVA_COORD_MAX = 32767
SVA_MAX_UAVS = 64
SVA_MAX_TARGETS = 256
SVA_MAX_TICK = 1_000_000_000
SVA_MAX_TICKS_PER_CELL = 1000
SVA_MAX_FUEL = 1_000_000_000
SVA_MAX_HOVER_FUEL = 1_000_000
SVA_MAX_ID = 2_147_483_647
SVA_MAX_TP_SOURCES = 24
SVA_MAX_TP_SINKS = 48
SVA_MAX_CHANGE_PENALTY = 1_000_000

DEFAULT_TICKS_PER_CELL = 1
DEFAULT_HOVER_FUEL = 0
DEFAULT_OVERLAP_PERCENT = 70


@dataclass(frozen=True)
class Uav:
    id: int
    x: int
    y: int
    fuel: int
    ready_at: int = 0


@dataclass(frozen=True)
class Target:
    id: int
    x: int
    y: int
    start: int
    end: int
    need: int


@dataclass
class Mission:
    name: str
    depot: tuple[int, int]
    uavs: list[Uav]
    targets: list[Target]
    ticks_per_cell: int = DEFAULT_TICKS_PER_CELL
    hover_fuel: int = DEFAULT_HOVER_FUEL
    overlap_percent: int = DEFAULT_OVERLAP_PERCENT
    change_penalty: int = 0   # live missions only (SPEC 12.4); written when not 0
    takeoff_ticks: int = 0    # live missions only (SPEC 12.2); written when not 0

    def target_by_id(self) -> dict[int, Target]:
        return {t.id: t for t in self.targets}

    def to_json(self) -> dict[str, Any]:
        out = {
            "name": self.name,
            "depot": {"x": self.depot[0], "y": self.depot[1]},
            "ticks_per_cell": self.ticks_per_cell,
            "hover_fuel": self.hover_fuel,
            "overlap_percent": self.overlap_percent,
            "uavs": [{"id": u.id, "x": u.x, "y": u.y, "fuel": u.fuel,
                      "ready_at": u.ready_at} for u in self.uavs],
            "targets": [{"id": t.id, "x": t.x, "y": t.y, "start": t.start,
                         "end": t.end, "need": t.need} for t in self.targets],
        }
        if self.change_penalty:
            out["change_penalty"] = self.change_penalty
        if self.takeoff_ticks:
            out["takeoff_ticks"] = self.takeoff_ticks
        return out


@dataclass
class Route:
    uav: int
    targets: list[int]
    distance: int
    fuel_used: int


@dataclass
class Plan:
    mission: str
    algorithm: str
    status: str
    covered: int
    uncovered: list[int]
    cost: int
    routes: list[Route]
    stats: dict[str, Any] | None = None
    stranded: list[int] = field(default_factory=list)

    def to_json(self) -> dict[str, Any]:
        out = {
            "mission": self.mission,
            "algorithm": self.algorithm,
            "status": self.status,
            "covered": self.covered,
            "uncovered": list(self.uncovered),
            "cost": self.cost,
            "routes": [{"uav": r.uav, "targets": list(r.targets), "distance": r.distance,
                        "fuel_used": r.fuel_used} for r in self.routes],
        }
        if self.stats is not None:
            out["stats"] = self.stats
        if self.stranded:
            out["stranded"] = list(self.stranded)
        return out


# --- SPEC section 1 -----------------------------------------------------------------

def manhattan(ax: int, ay: int, bx: int, by: int) -> int:
    return abs(ax - bx) + abs(ay - by)


def dist_pt(a: Uav | Target | tuple[int, int], b: Uav | Target | tuple[int, int]) -> int:
    """Manhattan distance between two objects with x and y (or (x, y) tuples)."""
    ax, ay = (a if isinstance(a, tuple) else (a.x, a.y))
    bx, by = (b if isinstance(b, tuple) else (b.x, b.y))
    return abs(ax - bx) + abs(ay - by)


def is_stranded(m: Mission, u: Uav) -> bool:
    """SPEC 1: a UAV whose fuel cannot even bring it home is reported, not planned."""
    return u.fuel < dist_pt(u, m.depot)


def can_start(m: Mission, u: Uav, t: Target) -> bool:
    """SPEC 1: t may be u's first target."""
    return u.ready_at + dist_pt(u, t) * m.ticks_per_cell <= t.start


def can_follow(m: Mission, a: Target, b: Target) -> bool:
    """SPEC 1: b may be served right after a by the same UAV."""
    return a.end + dist_pt(a, b) * m.ticks_per_cell <= b.start


def route_distance(m: Mission, u: Uav, targets: Sequence[Target]) -> int:
    """SPEC 1: legs from the UAV's position through its targets back to the depot."""
    pos = (u.x, u.y)
    total = 0
    for t in targets:
        total += dist_pt(pos, t)
        pos = (t.x, t.y)
    return total + dist_pt(pos, m.depot)


def route_fuel(m: Mission, u: Uav, targets: Sequence[Target]) -> int:
    return route_distance(m, u, targets) + m.hover_fuel * len(targets)


def route_feasible(m: Mission, u: Uav, targets: Sequence[Target]) -> bool:
    if not targets:
        return not is_stranded(m, u)
    if not can_start(m, u, targets[0]):
        return False
    for a, b in zip(targets, targets[1:]):
        if not can_follow(m, a, b):
            return False
    return route_fuel(m, u, targets) <= u.fuel


def window_overlap(a: Target, b: Target) -> tuple[int, int]:
    """SPEC 2's overlap measure: (|A n B|, min(|A|, |B|)), with |[s, e]| = e - s."""
    inter = max(0, min(a.end, b.end) - max(a.start, b.start))
    return inter, min(a.end - a.start, b.end - b.start)


def sorted_targets(m: Mission) -> list[Target]:
    return sorted(m.targets, key=lambda t: (t.start, t.end, t.id))


def clusters(m: Mission) -> list[list[Target]]:
    """SPEC 2 clustering: sort by (start, end, id); join the current cluster iff
    100 * |A n B| >= overlap_percent * min(|A|, |B|) with its last member."""
    out: list[list[Target]] = []
    for t in sorted_targets(m):
        if out:
            inter, shorter = window_overlap(out[-1][-1], t)
            if 100 * inter >= m.overlap_percent * shorter:
                out[-1].append(t)
                continue
        out.append([t])
    return out


def intersection_ratio(m: Mission) -> float:
    """A mission's window intersection ratio (docs/tools.md): the mean, over consecutive
    targets in (start, end, id) order, of |A n B| / min(|A|, |B|). 1.0 with < 2 targets."""
    ts = sorted_targets(m)
    if len(ts) < 2:
        return 1.0
    vals = []
    for a, b in zip(ts, ts[1:]):
        inter, shorter = window_overlap(a, b)
        vals.append(inter / shorter)
    return sum(vals) / len(vals)


def make_plan(m: Mission, algorithm: str, assignment: dict[int, list[int]],
              stats: dict[str, Any] | None = None) -> Plan:
    """Builds a SPEC 3 plan from {uav id: [target ids in visit order]}; counts, cost,
    stranded list and uncovered list are derived here (SPEC 1 rules)."""
    tmap = m.target_by_id()
    served: dict[int, int] = {t.id: 0 for t in m.targets}
    routes: list[Route] = []
    stranded: list[int] = []
    for u in m.uavs:
        ids = list(assignment.get(u.id, []))
        if is_stranded(m, u):
            stranded.append(u.id)
            routes.append(Route(u.id, [], 0, 0))
            continue
        ts = [tmap[i] for i in ids]
        for i in ids:
            served[i] += 1
        d = route_distance(m, u, ts)
        routes.append(Route(u.id, ids, d, d + m.hover_fuel * len(ts)))
    covered = sum(1 for t in m.targets if served[t.id] == t.need)
    uncovered = [t.id for t in m.targets if served[t.id] != t.need]
    return Plan(mission=m.name, algorithm=algorithm,
                status="complete" if covered == len(m.targets) else "partial",
                covered=covered, uncovered=uncovered,
                cost=sum(r.distance for r in routes), routes=routes, stats=stats,
                stranded=stranded)
