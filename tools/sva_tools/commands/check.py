"""`sva-tools check MISSION PLAN`: an independent SPEC section 1 validator.

Recomputes every figure of the plan from the mission (nothing comes from the C code)
and reports one message per violation. Exit 0: feasible and every figure right;
1: violations (one line each on stdout); 2: a file is not a valid SPEC 3 document.
"""
from __future__ import annotations

import argparse

from .. import io
from ..check import check_plan
from ..text import shown


def add_parser(sub) -> None:
    ap = sub.add_parser("check", help="validate a plan against SPEC section 1",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("mission")
    ap.add_argument("plan")
    ap.add_argument("-q", "--quiet", action="store_true", help="print nothing when the plan is right")
    ap.set_defaults(func=run)


def run(args) -> int:
    m = io.load_mission(args.mission)
    p = io.load_plan(args.plan)
    v = check_plan(m, p)
    for msg in v:
        print(f"{shown(args.plan)}: {shown(msg)}")
    if v:
        return 1
    if not args.quiet:
        print(f"{shown(args.plan)}: ok ({p.algorithm}, {p.status}, covered {p.covered}/{len(m.targets)}, "
              f"cost {p.cost})")
    return 0
