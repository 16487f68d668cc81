"""`sva-tools gen`: the paper's random mission generator (section 5.1), seeded.

The paper's six parameters: number of targets, number of UAVs, time-window width,
window intersection ratio, largest coordinate, need per target; plus fuel, hover fuel
and ticks per cell. Same seed and parameters give the same missions, byte for byte.

With --events N it writes a live-mission scenario instead (docs/live.md):
{"mission", "events", "change_penalty"}, with N events at random ticks inside the
mission's horizon drawn from --kinds (default the six: uav_lost, uav_back, fuel,
target_added, target_cancelled, target_changed; `position` is drawn only when named).
Every event is valid when applied in order (see generate_events).

Intersection ratio of a mission (model.intersection_ratio): targets sorted by
(start, end, id); the mean over consecutive pairs of |A n B| / min(|A|, |B|), SPEC 2's
overlap measure. Categories: low [0, 0.3), mid [0.3, 0.7), high [0.7, 1.0].
"""
from __future__ import annotations

import argparse
import math
import os
import random
import sys
from typing import Dict, List, Optional, Sequence, Tuple

from . import io
from . import model as M
from .text import shown

RATIOS = {"low": (0.0, 0.3), "mid": (0.3, 0.7), "high": (0.7, 1.0)}


def parse_range(text: str) -> Tuple[int, int]:
    """'7' -> (7, 7); '5:9' -> (5, 9)."""
    try:
        if ":" in text:
            a, b = text.split(":", 1)
            lo, hi = int(a), int(b)
        else:
            lo = hi = int(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected N or LO:HI, got {text!r}") from None
    if lo > hi:
        raise argparse.ArgumentTypeError(f"range {text!r}: LO must be <= HI")
    return lo, hi


def in_category(ratio: float, category: str) -> bool:
    lo, hi = RATIOS[category]
    return lo <= ratio < hi or (category == "high" and ratio <= 1.0 and ratio >= lo)


def generate(targets: int, uavs: int, *, width=(20, 40), ratio: str = "any",
             max_coord: int = 20, need=(2, 2), fuel: int = 150, hover: int = 0,
             ticks_per_cell: int = 1, overlap_percent: int = 70,
             depot: Optional[Tuple[int, int]] = None, seed: int = 0, index: int = 0,
             name: Optional[str] = None) -> M.Mission:
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
        ts = [M.Target(i + 1, rng.randint(0, max_coord), rng.randint(0, max_coord),
                       starts[i], starts[i] + widths[i], rng.randint(need[0], need[1]))
              for i in range(targets)]
        us = [M.Uav(i + 1, dx, dy, fuel, 0) for i in range(uavs)]
        m = M.Mission(name or f"gen_{targets}t{uavs}u_{ratio}_s{seed}_{index}", (dx, dy), us, ts,
                      ticks_per_cell, hover, overlap_percent)
        if ratio == "any" or targets < 2 or in_category(M.intersection_ratio(m), ratio):
            io.mission_from_json(m.to_json())  # the generator never writes a bad mission
            return m
    raise RuntimeError(f"could not hit intersection category {ratio!r} in 1000 attempts")


# The default kinds. Their draws are fixed: every scenario generated from them stays byte
# for byte what it was, so new kinds are opt-in (KINDS) and never join this tuple.
EVENT_KINDS = ("uav_lost", "uav_back", "fuel", "target_added", "target_cancelled",
               "target_changed")
# Every kind gen can draw: the defaults, then the opt-in ones.
KINDS = EVENT_KINDS + ("position",)


def kinds_error(kinds: Sequence[str]) -> Optional[str]:
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


def parse_kinds(text: str) -> Tuple[str, ...]:
    """--kinds: comma-separated kinds (argparse prefixes its errors with the option)."""
    kinds = tuple(k.strip() for k in text.split(",") if k.strip())
    err = kinds_error(kinds)
    if err:
        raise argparse.ArgumentTypeError(err)
    return kinds


def _target_json(t: M.Target) -> dict:
    return {"id": t.id, "x": t.x, "y": t.y, "start": t.start, "end": t.end, "need": t.need}


def generate_events(m: M.Mission, count: int, *, kinds: Sequence[str] = EVENT_KINDS,
                    max_coord: int = 20, width=(20, 40), need=(2, 2), seed: int = 0,
                    index: int = 0) -> Tuple[M.Mission, List[dict]]:
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

    def fresh_cell() -> Tuple[int, int]:
        for _ in range(10000):
            c = (rng.randint(0, max_coord), rng.randint(0, max_coord))
            if c not in used:
                used.add(c)
                return c
        raise ValueError(f"no free cell left on the {max_coord + 1}-cell-wide grid")

    targets: List[M.Target] = []
    for t in m.targets:
        x, y = (t.x, t.y) if (t.x, t.y) not in used else fresh_cell()
        used.add((x, y))
        targets.append(M.Target(t.id, x, y, t.start, t.end, t.need))
    m = M.Mission(m.name, m.depot, list(m.uavs), targets, m.ticks_per_cell, m.hover_fuel,
                  m.overlap_percent)
    horizon = max([t.end for t in targets] + [2])
    times = sorted(rng.randint(1, horizon - 1) for _ in range(count))
    in_service = {u.id: True for u in m.uavs}
    # Per UAV: its last known cell, the tick from which it may have left it, and its last
    # known fuel. Kept for every kind but read only by position reports, so the draws of
    # the other kinds do not depend on it.
    fix = {u.id: ((u.x, u.y), u.ready_at, u.fuel) for u in m.uavs}
    lost_at: Dict[int, int] = {}
    current = {t.id: t for t in targets}
    cancelled = set()
    next_id = max([t.id for t in targets] + [0]) + 1
    need_hi = max(1, min(need[1], len(m.uavs)))
    need_lo = min(need[0], need_hi)

    def window(at: int) -> Tuple[int, int]:
        start = at + rng.randint(max(1, lead // 2), lead + width[1])
        return start, start + rng.randint(width[0], width[1])

    def position(known, at: int, open_targets: List[M.Target]) -> Tuple[Tuple[int, int], int]:
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

    events: List[dict] = []
    for at in times:
        up = [u for u, ok in in_service.items() if ok]
        back = [u for u, t in lost_at.items() if t < at]
        ahead = [t for t in current.values() if t.start > at and t.id not in cancelled]
        can = {"uav_lost": bool(up), "uav_back": bool(back), "fuel": bool(up),
               "target_added": len(current) < M.SVA_MAX_TARGETS,
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
            t = M.Target(next_id, x, y, start, end, rng.randint(need_lo, need_hi))
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
            t = M.Target(old.id, x, y, start, end, rng.randint(need_lo, need_hi))
            current[t.id] = t
            events.append({"at": at, "type": kind, "target": _target_json(t)})
    return m, events


def generate_scenario(targets: int, uavs: int, events: int, *, kinds=EVENT_KINDS,
                      change_penalty: Optional[int] = None, seed: int = 0, index: int = 0,
                      **kw) -> dict:
    """A live-mission scenario: generate()'s mission with generate_events()' events."""
    m = generate(targets, uavs, seed=seed, index=index, **kw)
    m, evs = generate_events(m, events, kinds=kinds, max_coord=kw.get("max_coord", 20),
                             width=kw.get("width", (20, 40)), need=kw.get("need", (2, 2)),
                             seed=seed, index=index)
    io.mission_from_json(m.to_json())
    doc = {"mission": m.to_json(), "events": evs}
    if change_penalty is not None:
        doc["change_penalty"] = change_penalty
    return doc


def add_parser(sub) -> None:
    ap = sub.add_parser("gen", help="generate random missions (paper section 5.1)",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--targets", type=int, default=10, help="number of targets (default 10)")
    ap.add_argument("--uavs", type=int, default=5, help="number of UAVs, all at the depot (default 5)")
    ap.add_argument("--width", type=parse_range, default=(20, 40),
                    help="time-window width in ticks, N or LO:HI (default 20:40)")
    ap.add_argument("--ratio", choices=["any", "low", "mid", "high"], default="any",
                    help="window intersection category (default any: starts uniform over "
                         "targets * mean width ticks)")
    ap.add_argument("--max-coord", type=int, default=20, help="coordinates in [0, N] (default 20)")
    ap.add_argument("--need", type=parse_range, default=(2, 2), help="UAVs per target, N or LO:HI (default 2)")
    ap.add_argument("--fuel", type=int, default=150, help="fuel of every UAV (default 150)")
    ap.add_argument("--hover", type=int, default=0, help="hover_fuel per served window (default 0)")
    ap.add_argument("--ticks-per-cell", type=int, default=1)
    ap.add_argument("--overlap-percent", type=int, default=70)
    ap.add_argument("--seed", type=int, default=1)
    ap.add_argument("--count", type=int, default=1, help="missions to write (default 1)")
    ap.add_argument("--name", help="mission name (with --count > 1: prefix)")
    ap.add_argument("--events", type=int, metavar="N",
                    help="write a live-mission scenario with N random events (docs/live.md)")
    ap.add_argument("--kinds", type=parse_kinds, default=EVENT_KINDS,
                    help="with --events: comma-separated event kinds to draw from, each "
                         f"one of {','.join(KINDS)} (default: {','.join(EVENT_KINDS)}; "
                         "position only when named)")
    ap.add_argument("--change-penalty", type=int, metavar="P",
                    help="with --events: the scenario's change_penalty (default: none)")
    ap.add_argument("-o", "--out", default="-",
                    help="output file ('-': stdout); with --count > 1 a directory")
    ap.set_defaults(func=run)


def run(args) -> int:
    kw = dict(width=args.width, ratio=args.ratio, max_coord=args.max_coord, need=args.need,
              fuel=args.fuel, hover=args.hover, ticks_per_cell=args.ticks_per_cell,
              overlap_percent=args.overlap_percent, seed=args.seed)
    if args.events is not None and args.events < 0:
        print("sva-tools: error: gen: --events must be >= 0", file=sys.stderr)
        return 2

    def one(index: int, name: Optional[str]):
        if args.events is None:
            m = generate(args.targets, args.uavs, index=index, name=name, **kw)
            return m.name, m.to_json()
        doc = generate_scenario(args.targets, args.uavs, args.events, kinds=args.kinds,
                                change_penalty=args.change_penalty, index=index, name=name,
                                **kw)
        return doc["mission"]["name"], doc

    try:
        if args.count == 1:
            io.write_json(one(0, args.name)[1], args.out)
            return 0
        if args.out == "-":
            print("sva-tools: error: --count > 1 needs --out DIRECTORY", file=sys.stderr)
            return 2
        os.makedirs(args.out, exist_ok=True)
        for i in range(args.count):
            name = f"{args.name}_{i:04d}" if args.name else None
            mname, doc = one(i, name)
            io.write_json(doc, os.path.join(args.out, f"{mname}.json"))
        return 0
    except (ValueError, io.InputError) as e:
        print(f"sva-tools: error: gen: {shown(e)}", file=sys.stderr)
        return 2
