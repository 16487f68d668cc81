"""Random missions and live-mission scenarios: the generator behind `sva-tools gen`."""
from __future__ import annotations

import math
import random
from collections.abc import Sequence
from typing import Any

from . import io, model

RATIOS = {"low": (0.0, 0.3), "mid": (0.3, 0.7), "high": (0.7, 1.0)}


def in_category(ratio: float, category: str) -> bool:
    lo, hi = RATIOS[category]
    return lo <= ratio < hi or (category == "high" and ratio <= 1.0 and ratio >= lo)


def generate(targets: int, uavs: int, *, width: tuple[int, int] = (20, 40), ratio: str = "any",
             max_coord: int = 20, need: tuple[int, int] = (2, 2), fuel: int = 150, hover: int = 0,
             ticks_per_cell: int = 1, overlap_percent: int = 70,
             depot: tuple[int, int] | None = None, seed: int = 0, index: int = 0,
             name: str | None = None) -> model.Mission:
    """One mission. Deterministic in (all parameters, seed, index)."""
    if targets < 0 or uavs < 0 or max_coord < 0 or width[0] < 1:
        raise ValueError("targets, uavs and max_coord must be >= 0 and width >= 1")
    rng = random.Random(f"sva-gen:{seed}:{index}")
    dx, dy = depot if depot is not None else (0, 0)
    # Every target is reachable from the depot at tick 0: windows start after the
    # longest possible flight from the depot to a grid point.
    far = max(abs(dx - cx) + abs(dy - cy) for cx in (0, max_coord) for cy in (0, max_coord))
    lead = far * ticks_per_cell
    for _attempt in range(1000):
        widths = [rng.randint(width[0], width[1]) for _ in range(targets)]
        starts = []
        if ratio == "any":
            horizon = max(1, targets * (width[0] + width[1]) // 2)
            starts = [lead + rng.randrange(horizon) for _ in range(targets)]
        else:
            lo, hi = RATIOS[ratio]
            s = lead + rng.randrange(max(1, widths[0] if targets else 1))
            for i in range(targets):
                if i > 0:
                    short = min(widths[i - 1], widths[i])
                    a = math.ceil(lo * short)
                    b = short if ratio == "high" else math.ceil(hi * short) - 1
                    ov = rng.randint(a, max(a, b))
                    if ov == 0:
                        s = starts[-1] + widths[i - 1] + rng.randint(0, widths[i - 1])
                    else:
                        s = starts[-1] + widths[i - 1] - ov
                starts.append(s)
        ts = [model.Target(i + 1, rng.randint(0, max_coord), rng.randint(0, max_coord),
                       starts[i], starts[i] + widths[i], rng.randint(need[0], need[1]))
              for i in range(targets)]
        us = [model.Uav(i + 1, dx, dy, fuel, 0) for i in range(uavs)]
        m = model.Mission(name or f"gen_{targets}t{uavs}u_{ratio}_s{seed}_{index}", (dx, dy), us, ts,
                      ticks_per_cell, hover, overlap_percent)
        if ratio == "any" or targets < 2 or in_category(model.intersection_ratio(m), ratio):
            io.mission_from_json(m.to_json())  # the generator never writes a bad mission
            return m
    raise RuntimeError(f"could not hit intersection category {ratio!r} in 1000 attempts")


# The default kinds. Their draws are fixed: every scenario generated from them stays byte
# for byte what it was, so new kinds are opt-in (KINDS) and never join this tuple.
EVENT_KINDS = ("uav_lost", "uav_back", "fuel", "target_added", "target_cancelled",
               "target_changed")
# Every kind gen can draw: the defaults, then the opt-in ones.
KINDS = EVENT_KINDS + ("position",)


def kinds_error(kinds: Sequence[str]) -> str | None:
    """Why `kinds` is not a list of event kinds gen can draw (None: it is)."""
    allowed = ", ".join(KINDS)
    if not kinds:
        return f"name at least one event kind (allowed: {allowed})"
    seen = set()
    for k in kinds:
        if k not in KINDS:
            return f"{k!r} is not an event kind gen draws: each kind must be one of {allowed}"
        if k in seen:
            return f"event kind {k!r} named twice: name each kind at most once (allowed: {allowed})"
        seen.add(k)
    return None


def _target_json(t: model.Target) -> dict[str, Any]:
    return {"id": t.id, "x": t.x, "y": t.y, "start": t.start, "end": t.end, "need": t.need}


def generate_events(m: model.Mission, count: int, *, kinds: Sequence[str] = EVENT_KINDS,
                    max_coord: int = 20, width: tuple[int, int] = (20, 40), need: tuple[int, int] = (2, 2),
                    seed: int = 0,
                    index: int = 0) -> tuple[model.Mission, list[dict[str, Any]]]:
    """`count` events at random ticks in [1, the mission's last window end), drawn from
    `kinds`, valid when applied in order (SPEC 12.3): a UAV is lost only while in
    service and comes back only after it was lost (at a later tick); fuel readings go to
    UAVs in service; targets are cancelled or changed only before their window starts
    (so never done, lost or under way) and never after a cancellation; a pop-up or a
    changed window starts after the event. Fuel readings and fuel on return are at least
    the longest flight home from the grid, so no UAV is stranded by them.

    A position report (only when `kinds` names "position") goes to a UAV in service, on
    a cell of the grid [0, max_coord]^2 it could have flown to since its last known cell
    (where it started, came back or was last seen): at most (elapsed ticks) //
    ticks_per_cell cells from there. Half the time, when one is in reach, it is the cell
    of a target whose window is open (the UAV on station, or blown onto it); otherwise
    any such cell, uniformly. Its fuel is at least the longest flight home, and at most
    the UAV's last known fuel less the cells from its last known cell (when that is
    above the floor).

    Targets (the mission's too: they are moved when needed, so it returns the mission)
    stand on distinct cells, none at the depot, and a UAV comes back on no target's cell:
    a UAV waiting at one target or at home never stands on another one's cell.
    Deterministic in (mission, parameters, seed, index)."""
    err = kinds_error(tuple(kinds))
    if err:
        raise ValueError(f"kinds: {err}")
    rng = random.Random(f"sva-gen-events:{seed}:{index}")
    dx, dy = m.depot
    far = max(abs(dx - cx) + abs(dy - cy) for cx in (0, max_coord) for cy in (0, max_coord))
    lead = far * m.ticks_per_cell
    full_fuel = max([u.fuel for u in m.uavs] + [2 * far])
    used = {m.depot}

    def fresh_cell() -> tuple[int, int]:
        for _ in range(10000):
            c = (rng.randint(0, max_coord), rng.randint(0, max_coord))
            if c not in used:
                used.add(c)
                return c
        raise ValueError(f"no free cell left on the {max_coord + 1}-cell-wide grid")

    targets: list[model.Target] = []
    for t in m.targets:
        x, y = (t.x, t.y) if (t.x, t.y) not in used else fresh_cell()
        used.add((x, y))
        targets.append(model.Target(t.id, x, y, t.start, t.end, t.need))
    m = model.Mission(m.name, m.depot, list(m.uavs), targets, m.ticks_per_cell, m.hover_fuel,
                  m.overlap_percent)
    horizon = max([t.end for t in targets] + [2])
    times = sorted(rng.randint(1, horizon - 1) for _ in range(count))
    in_service = {u.id: True for u in m.uavs}
    # Per UAV: its last known cell, the tick from which it may have left it, and its last
    # known fuel. Kept for every kind but read only by position reports, so the draws of
    # the other kinds do not depend on it.
    fix = {u.id: ((u.x, u.y), u.ready_at, u.fuel) for u in m.uavs}
    lost_at: dict[int, int] = {}
    current = {t.id: t for t in targets}
    cancelled = set()
    next_id = max([t.id for t in targets] + [0]) + 1
    need_hi = max(1, min(need[1], len(m.uavs)))
    need_lo = min(need[0], need_hi)

    def window(at: int) -> tuple[int, int]:
        start = at + rng.randint(max(1, lead // 2), lead + width[1])
        return start, start + rng.randint(width[0], width[1])

    def position(known: tuple[tuple[int, int], int, int], at: int,
                 open_targets: list[model.Target]) -> tuple[tuple[int, int], int]:
        """A cell the UAV could be on at `at` and a fuel reading there (see above)."""
        (fx, fy), since, fuel = known
        reach = min(max(0, at - since) // m.ticks_per_cell, 2 * max_coord)

        def dist(x: int, y: int) -> int:
            return abs(x - fx) + abs(y - fy)

        cells = [(x, y) for x in range(max(0, fx - reach), min(max_coord, fx + reach) + 1)
                 for y in range(max(0, fy - reach), min(max_coord, fy + reach) + 1)
                 if dist(x, y) <= reach] or [(fx, fy)]
        stations = [(t.x, t.y) for t in open_targets if dist(t.x, t.y) <= reach]
        cell = rng.choice(stations) if stations and rng.random() < 0.5 else rng.choice(cells)
        return cell, rng.randint(far, max(far, fuel - dist(*cell)))

    events: list[dict[str, Any]] = []
    for at in times:
        up = [u for u, ok in in_service.items() if ok]
        back = [u for u, t in lost_at.items() if t < at]
        ahead = [t for t in current.values() if t.start > at and t.id not in cancelled]
        can = {"uav_lost": bool(up), "uav_back": bool(back), "fuel": bool(up),
               "target_added": len(current) < model.SVA_MAX_TARGETS,
               "target_cancelled": bool(ahead), "target_changed": bool(ahead),
               "position": bool(up)}
        choice = [k for k in kinds if can[k]]
        if not choice:
            continue
        kind = rng.choice(choice)
        if kind == "uav_lost":
            u = rng.choice(up)
            in_service[u] = False
            lost_at[u] = at
            events.append({"at": at, "type": kind, "uav": u})
        elif kind == "uav_back":
            u = rng.choice(back)
            del lost_at[u]
            in_service[u] = True
            x, y = fresh_cell()
            events.append({"at": at, "type": kind, "uav": u, "x": x, "y": y,
                           "fuel": rng.randint(2 * far, max(2 * far, full_fuel))})
            fix[u] = ((x, y), at, events[-1]["fuel"])
        elif kind == "fuel":
            events.append({"at": at, "type": kind, "uav": rng.choice(up),
                           "fuel": rng.randint(far, max(far, full_fuel * 3 // 4))})
            cell, since, _ = fix[events[-1]["uav"]]
            fix[events[-1]["uav"]] = (cell, since, events[-1]["fuel"])
        elif kind == "position":
            u = rng.choice(up)
            (x, y), f = position(fix[u], at, [t for t in current.values()
                                              if t.id not in cancelled and t.start <= at < t.end])
            events.append({"at": at, "type": kind, "uav": u, "x": x, "y": y, "fuel": f})
            fix[u] = ((x, y), at, f)
        elif kind == "target_added":
            x, y = fresh_cell()
            start, end = window(at)
            t = model.Target(next_id, x, y, start, end, rng.randint(need_lo, need_hi))
            next_id += 1
            current[t.id] = t
            events.append({"at": at, "type": kind, "target": _target_json(t)})
        elif kind == "target_cancelled":
            t = rng.choice(ahead)
            cancelled.add(t.id)
            events.append({"at": at, "type": kind, "target": t.id})
        elif kind == "target_changed":
            old = rng.choice(ahead)
            x, y = fresh_cell()
            start, end = window(at)
            t = model.Target(old.id, x, y, start, end, rng.randint(need_lo, need_hi))
            current[t.id] = t
            events.append({"at": at, "type": kind, "target": _target_json(t)})
    return m, events


def generate_scenario(targets: int, uavs: int, events: int, *, kinds: Sequence[str] = EVENT_KINDS,
                      change_penalty: int | None = None, seed: int = 0, index: int = 0,
                      **kw: Any) -> dict[str, Any]:
    """A live-mission scenario: generate()'s mission with generate_events()' events."""
    m = generate(targets, uavs, seed=seed, index=index, **kw)
    m, evs = generate_events(m, events, kinds=kinds, max_coord=kw.get("max_coord", 20),
                             width=kw.get("width", (20, 40)), need=kw.get("need", (2, 2)),
                             seed=seed, index=index)
    io.mission_from_json(m.to_json())
    doc: dict[str, Any] = {"mission": m.to_json(), "events": evs}
    if change_penalty is not None:
        doc["change_penalty"] = change_penalty
    return doc
