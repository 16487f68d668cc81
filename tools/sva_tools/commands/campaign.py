"""`sva-tools campaign SPEC.yaml`: a regression campaign on a Dask cluster (docs/campaigns.md).

The spec (YAML) names generator settings, how many missions or live scenarios, the
algorithms and whether the exact reference (ref) solves them. Every task (one planner
on one mission, ref on one mission, one flight of a live scenario) runs on a Dask
worker: an embedded LocalCluster by default (--workers N processes, one thread each),
or the cluster of --scheduler tcp://HOST:PORT. Results go to OUT/results/*.parquet,
keyed by the mission's content hash, the tool, its settings and its version: a task
already stored is not submitted again, so an interrupted or extended campaign resumes
where it stopped. Then OUT/metrics.parquet (coverage, cost, gap to ref, solve time per
planner result) and OUT/report.html (tables and plots, self-contained).
A damaged part file (empty, truncated, not Parquet, another schema) is named in a
warning and skipped; while one is there nothing is computed (its tasks are not known
apart from new ones) and the summary and report show what is readable; --repair moves
it to OUT/damaged/ and computes every task without a readable result.
Exit status: 0 when every task has a stored result, 1 when some failed or damaged parts
left tasks without one, 2 on a bad spec or option, or a scheduler that cannot be reached.
"""
from __future__ import annotations

import argparse
import os
import sys
from pathlib import Path

from ..campaign import REPO, CampaignError, run
from ..text import shown


def add_parser(sub) -> None:
    ap = sub.add_parser("campaign", help="regression campaign on a Dask cluster (docs/campaigns.md)",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("spec", help="campaign spec, YAML (docs/campaigns.md)")
    ap.add_argument("--scheduler", metavar="tcp://HOST:PORT",
                    help="a running Dask scheduler (default: an embedded LocalCluster)")
    ap.add_argument("--workers", type=int, metavar="N",
                    help="LocalCluster worker processes (default 2 or the CPU count if lower)")
    ap.add_argument("--out", metavar="DIR", help="result folder (default build/campaigns/NAME)")
    ap.add_argument("--flush-rows", type=int, default=64, metavar="N",
                    help="results per Parquet file (default 64; also written every 2 s): at most "
                         "this many finished results are lost when the client dies")
    ap.add_argument("--no-progress", action="store_true", help="no progress bar")
    ap.add_argument("--no-report", action="store_true", help="skip OUT/report.html")
    ap.add_argument("--repair", action="store_true",
                    help="move damaged part files (named in warnings) to OUT/damaged/ and compute their tasks again")
    ap.set_defaults(func=main)


def _warn(message: str) -> None:
    print(f"sva-tools: warning: campaign: {shown(message)}", file=sys.stderr)


def _damaged(path: Path, reason: str) -> None:
    _warn(f"{path}: damaged part ({reason}), skipped; --repair moves it to damaged/ and computes its tasks again")


def main(args) -> int:
    from ..campaign import report
    from ..campaign.spec import SpecError, load, shown_value
    if args.workers is not None and args.workers < 1:
        print("sva-tools: error: campaign: --workers: must be >= 1, got "
              f"{args.workers}", file=sys.stderr)
        return 2
    if args.workers is not None and args.scheduler:
        print("sva-tools: error: campaign: --workers is for the embedded LocalCluster; "
              "with --scheduler the cluster's own workers run the tasks", file=sys.stderr)
        return 2
    if args.flush_rows < 1:
        print(f"sva-tools: error: campaign: --flush-rows: must be >= 1, got {args.flush_rows}", file=sys.stderr)
        return 2
    try:
        spec = load(args.spec)
    except SpecError as e:
        print(f"sva-tools: error: campaign: {shown(args.spec)}: {shown(e)}", file=sys.stderr)
        return 2
    campaigns = os.path.join(REPO, "build", "campaigns")
    out = args.out or os.path.join(campaigns, spec["name"])
    if not args.out and os.path.dirname(os.path.normpath(out)) != campaigns:  # the schema's name rule, kept
        print(f"sva-tools: error: campaign: {shown(args.spec)}: name: must name a folder in {shown(campaigns)}, "
              f"got {shown(shown_value(spec['name']))}", file=sys.stderr)
        return 2
    try:
        stats = run(spec, out, args.scheduler, args.workers, progress=not args.no_progress,
                    flush_rows=args.flush_rows, columns=[], repair=args.repair, on_damaged=_damaged)
    except SpecError as e:
        print(f"sva-tools: error: campaign: {shown(args.spec)}: {shown(e)}", file=sys.stderr)
        return 2
    except CampaignError as e:
        print(f"sva-tools: error: campaign: {shown(e)}", file=sys.stderr)
        return 2
    store = stats["store"]
    for old, new in stats["set_aside"]:
        _warn(f"{old}: moved to {new}; its tasks were computed again")
    # The figures need neither the missions nor (kind plan) the plans: the report reads
    # only the columns it needs, as one Arrow table, and groups this run's tasks.
    records, gs, stored = report.build(spec, store, stats["task_list"])
    report.write_metrics(records, out)
    print(report.summary(spec, stats, gs))
    if not args.no_report:
        path = report.write_html(spec, stats, gs, out, stored)
        print(f"report: {path}")
    for f in stats["failed"][:10]:
        print(f"failed: {shown(f)}", file=sys.stderr)
    damaged = bool(store.damaged)
    if damaged and args.repair:  # found only when the report read more columns than the keys
        for old, new in store.set_aside():
            _warn(f"{old}: moved to {new}; run again to compute its tasks")
    elif damaged:
        _warn(f"{len(store.damaged)} damaged part file(s) in {store.dir} skipped, {stats['held']} task(s) "
              "not computed; run again with --repair")
    return 1 if stats["failed"] or stats["held"] or damaged else 0
