"""`sva-tools gen`: the paper's random mission generator (section 5.1), seeded.

The paper's six parameters: number of targets, number of UAVs, time-window width,
window intersection ratio, largest coordinate, need per target; plus fuel, hover fuel
and ticks per cell. Same seed and parameters give the same missions, byte for byte.

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
from typing import Optional, Tuple

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
    ap.add_argument("-o", "--out", default="-",
                    help="output file ('-': stdout); with --count > 1 a directory")
    ap.set_defaults(func=run)


def run(args) -> int:
    kw = dict(width=args.width, ratio=args.ratio, max_coord=args.max_coord, need=args.need,
              fuel=args.fuel, hover=args.hover, ticks_per_cell=args.ticks_per_cell,
              overlap_percent=args.overlap_percent, seed=args.seed)
    try:
        if args.count == 1:
            m = generate(args.targets, args.uavs, name=args.name, **kw)
            io.write_json(m.to_json(), args.out)
            return 0
        if args.out == "-":
            print("sva-tools: error: --count > 1 needs --out DIRECTORY", file=sys.stderr)
            return 2
        os.makedirs(args.out, exist_ok=True)
        for i in range(args.count):
            name = f"{args.name}_{i:04d}" if args.name else None
            m = generate(args.targets, args.uavs, index=i, name=name, **kw)
            io.write_json(m.to_json(), os.path.join(args.out, f"{m.name}.json"))
        return 0
    except (ValueError, io.InputError) as e:
        print(f"sva-tools: error: gen: {shown(e)}", file=sys.stderr)
        return 2
