"""`sva-tools validate FILE... [--kind KIND]`: check files against their JSON Schema
(docs/schema/) and the rules a schema cannot express (docs/SPEC.md sections 3 and 4).

Kinds: mission, plan, trace (JSON Lines, one record a line), bound (`ref --bound`
output), cache-entry (`bench --cache`). Without --kind: a `.jsonl` file is a trace; an
object with "routes" is a plan, with "complete_possible" a bound, with "key" and
"result" a cache entry; anything else a mission. A live mission, scenario or flight log
(told apart by their top-level keys) is refused without --kind, naming what it is and
the command that takes it.

Prints `ok: FILE: KIND ...` per valid file; the first error of the first invalid file
is one line `sva-tools: error: FILE: FIELD: RULE` and exit status 2.
"""
from __future__ import annotations

import argparse
from typing import Any

from . import io, schema


TAKER = "sva-tools validate takes a mission, plan, trace, bound or cache entry (SPEC 9)"


def guess_kind(path: str, doc: Any) -> str:
    if path.endswith(".jsonl"):
        return "trace"
    if isinstance(doc, dict):
        if "routes" in doc:
            return "plan"
        if "complete_possible" in doc:
            return "bound"
        if "key" in doc and "result" in doc:
            return "cache-entry"
    return "mission"


def validate_file(path: str, kind: str = "") -> str:
    """The `ok` line for a valid file; io.InputError (with .path) otherwise."""
    if kind == "trace" or (not kind and path.endswith(".jsonl")):
        recs = io.load_trace(path)
        return f"ok: {path}: trace, {len(recs)} records"
    try:
        doc = io.read_json(path)
        if not kind:
            io.wrong_kind(doc, guess_kind(path, doc), TAKER)
        kind = kind or guess_kind(path, doc)
        io.check(doc, kind)
    except io.InputError as e:
        e.path = path
        raise
    if kind == "mission":
        return f"ok: {path}: mission {doc['name']}: {len(doc['uavs'])} UAVs, {len(doc['targets'])} targets"
    if kind == "plan":
        return f"ok: {path}: plan of {doc['mission']} by {doc['algorithm']}, {doc['status']}"
    return f"ok: {path}: {kind}"


def add_parser(sub) -> None:
    ap = sub.add_parser("validate", help="check files against their JSON Schema (docs/schema)",
                        description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("files", nargs="+", metavar="FILE")
    ap.add_argument("--kind", choices=schema.KINDS, default="",
                    help="the file format (default: from the name and the content)")
    ap.set_defaults(func=run)


def run(args) -> int:
    for path in args.files:
        print(validate_file(path, args.kind))
    return 0
