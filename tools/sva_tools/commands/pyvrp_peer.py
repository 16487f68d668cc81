"""`python -m sva_tools.commands.pyvrp_peer MISSION`: PyVRP as a peer on one mission (the
model: sva_tools.pyvrp_peer)."""
from __future__ import annotations

import argparse
import sys

from .. import io, pyvrp_peer
from ..pyvrp_peer import SEED, TIME_LIMIT, solve_pyvrp
from .common import fail


def main(argv: list[str]) -> int:
    ap = argparse.ArgumentParser(prog="pyvrp_peer", description=pyvrp_peer.__doc__,
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mission")
    ap.add_argument("--time-limit", type=float, default=TIME_LIMIT,
                    help=f"wall-clock search limit in seconds (default {TIME_LIMIT:g})")
    ap.add_argument("--seed", type=int, default=SEED, help=f"PyVRP's seed (default {SEED})")
    ap.add_argument("-o", "--out", default="-")
    args = ap.parse_args(argv)
    try:
        mission = io.load_mission(args.mission)
    except io.InputError as e:
        return fail(args.mission, e)
    try:
        plan = solve_pyvrp(mission, args.time_limit, args.seed)
    except ValueError as e:
        print(f"pyvrp_peer: error: {e}", file=sys.stderr)
        return 2
    io.write_json(plan.to_json(), args.out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
