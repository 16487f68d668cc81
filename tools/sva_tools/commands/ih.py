"""`sva-tools ih`: the paper's intlinprog heuristic (IH, section 4.5).

The `sva` pipeline of SPEC 2 run in Python (clustering, ready UAVs, source groups,
commit and advance), with every transportation problem solved by an integer LP
(HiGHS): first as many of the cluster's targets covered in full as possible, then
least cost. Source groups are UAVs at one position that can serve the same set of
sinks (the C core's grouping: UAVs at one position may differ in fuel and ready time).

  ih MISSION [-o PLAN]             plan a mission ("algorithm": "ih")
  ih --verify-trace FILE...        re-solve every problem `sva plan --trace` wrote
  ih --compare MISSION|DIR...      run `sva plan --algo sva --trace` and this IH on
                                   each mission: traced optima, drop rule, whole plans
Exit 0 when every check passes, 1 when one fails, 2 on bad input.
"""
from __future__ import annotations

import argparse
import json
import os
import sys

from .. import io
from ..ih import CompareVerdict, TpRecord, TraceVerdict, compare_mission, plan_ih, read_trace, verify_record
from ..text import shown


def _mission_paths(items: list[str]) -> list[str]:
    out = []
    for it in items:
        if os.path.isdir(it):
            out += sorted(os.path.join(it, f) for f in os.listdir(it) if f.endswith(".json"))
        else:
            out.append(it)
    return out


def add_parser(sub) -> None:
    ap = sub.add_parser("ih", help="intlinprog heuristic: SVA pipeline with an integer LP",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("inputs", nargs="+", metavar="MISSION|TRACE")
    mode = ap.add_mutually_exclusive_group()
    mode.add_argument("--verify-trace", action="store_true",
                      help="inputs are --trace files of `sva plan`")
    mode.add_argument("--compare", action="store_true",
                      help="inputs are missions or directories: compare with the C sva")
    ap.add_argument("-o", "--out", default="-", help="plan output (default stdout)")
    ap.add_argument("--trace", help="also write IH's problems as JSON Lines")
    ap.set_defaults(func=run)


def _print_trace_verdict(v: TraceVerdict) -> None:
    for msg in v.mismatches:
        print(f"MISMATCH {msg}")
    print(f"problems checked: {v.problems}; integer LP optimum == tableau cost_total: "
          f"{v.problems - len(v.mismatches)}/{v.problems}")
    print(f"problems with dropped sinks: {v.with_drops}; where cover-as-many-as-possible "
          f"keeps more sinks than the tableau's drop rule: {v.drop_worse} "
          f"({v.drop_worse_sinks} sinks in all); where it keeps as many sinks but a cheaper "
          f"set: {v.drop_costlier}")


def run(args) -> int:
    if args.verify_trace:
        v = TraceVerdict()
        for path in args.inputs:
            for rec in read_trace(path):
                verify_record(rec, v, f"{path}: ")
        _print_trace_verdict(v)
        return 1 if v.mismatches else 0
    if args.compare:
        from .. import cbin
        cv = CompareVerdict()
        for path in _mission_paths(args.inputs):
            m = io.load_mission(path)
            try:
                compare_mission(m, cv)
            except cbin.CliMissing as e:
                print(f"sva-tools: error: {shown(e)}", file=sys.stderr)
                return 2
        _print_trace_verdict(cv.trace)
        print(f"missions: {cv.missions}; identical plans: {cv.same}; differ with the same "
              f"covered and cost: {cv.tie}; differ in covered or cost: {len(cv.differ)}; "
              f"differing plans whose first differing problem was a tie (same problem, "
              f"other flow of equal cost): {cv.tie_first}/{cv.missions - cv.same}")
        for msg in cv.differ:
            print(f"DIFFER {msg}")
        return 1 if cv.trace.mismatches else 0
    if len(args.inputs) != 1:
        print("sva-tools: error: ih plans one mission at a time", file=sys.stderr)
        return 2
    m = io.load_mission(args.inputs[0])
    recs: list[TpRecord] = []
    p = plan_ih(m, recs)
    if args.trace:
        with open(args.trace, "w", encoding="utf-8") as f:
            for r in recs:
                f.write(json.dumps({"algorithm": "ih", "source_uavs": r.source_uavs,
                                    "supply": r.supply, "sink_targets": r.sink_targets,
                                    "demand": r.demand, "dropped": [not k for k in r.kept],
                                    "cost": r.cost, "flow": r.flow, "cost_total": r.cost_total,
                                    "covered": r.covered, "pivots": 0}) + "\n")
    io.write_json(p.to_json(), args.out)
    return 0
