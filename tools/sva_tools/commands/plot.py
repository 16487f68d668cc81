"""`sva-tools plot MISSION PLAN [-o PNG]`: the plan as a picture.

Left: the grid map with the depot (black square), every target (circle: green when
covered, red when not; label "T<id> n<need> [start,end]") and each UAV's route (one
colour per UAV, from its position through its targets to the depot). Right: a Gantt
chart, one row per UAV (flight legs leaving as early as possible, waiting hatched,
serving solid) under one row per target window.

A plan that is not a plan of the mission (`sva-tools check` finds a violation) is
refused with the first violation, one line, exit status 2.
"""
from __future__ import annotations

import argparse

from .. import check, io
from ..plot import render
from ..text import shown


def add_parser(sub) -> None:
    ap = sub.add_parser("plot", help="PNG of a plan: map and Gantt chart",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mission")
    ap.add_argument("plan")
    ap.add_argument("-o", "--out", help="PNG path (default: PLAN with .png)")
    ap.set_defaults(func=run)


def run(args) -> int:
    m = io.load_mission(args.mission)
    p = io.load_plan(args.plan)
    violations = check.check_plan(m, p)
    if violations:
        raise io.InputError(f"not a plan of this mission (SPEC section 1): {violations[0]}",
                            args.plan)
    out = args.out or (args.plan[:-5] if args.plan.endswith(".json") else args.plan) + ".png"
    render(m, p, out)
    print(shown(out))
    return 0
