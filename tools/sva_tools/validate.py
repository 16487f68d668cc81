"""Validation of a mission, plan, trace, bound or cache entry against docs/schema
(`sva-tools validate`)."""
from __future__ import annotations

from typing import Any

from . import io

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
