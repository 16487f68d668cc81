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

from .. import schema
from ..validate import validate_file


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
