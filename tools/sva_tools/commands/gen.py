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
import os
import sys

from .. import io
from ..gen import EVENT_KINDS, KINDS, generate, generate_scenario, kinds_error
from ..text import shown


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

    def one(index: int, name: str | None):
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


def parse_range(text: str) -> tuple[int, int]:
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


def parse_kinds(text: str) -> tuple[str, ...]:
    """--kinds: comma-separated kinds (argparse prefixes its errors with the option)."""
    kinds = tuple(k.strip() for k in text.split(",") if k.strip())
    err = kinds_error(kinds)
    if err:
        raise argparse.ArgumentTypeError(err)
    return kinds
