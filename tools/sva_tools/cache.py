"""Result cache of `bench` (--cache DIR): the slow host solvers (ih, ref, peer) run once
per mission and setting, so a re-run of the report (e.g. after the C `flow` planner
changed) only re-runs the C planners.

One JSON file per result: DIR/<solver>/<key>.json, where key is the SHA-256 of the
canonical JSON (sorted keys, no spaces) of the key fields:
- mission: SHA-256 of the mission's canonical SPEC 3 JSON (its content, name included);
- solver: "ih", "ref" or "peer";
- settings: the solver's settings (ref: det_limit, workers, time_limit; peer:
  solution_limit, time_limit, hard_all_or_none; ih: none);
- version: sva_tools.__version__, the OR-tools version, and the SHA-256 of the
  sva_tools sources the solver runs (its module, model.py, and solvers.py for ih), so
  an edit to the solver's code misses instead of returning a stale plan.
The file stores the key fields again (checked on every hit), the result (plan as SPEC 3
JSON, or the error), and when and under what load it was measured: UTC time, the
load average (1, 5, 15 min) just before the solve, CPU count. A hit returns the plan
as stored, stats.solve_us included: a cached row keeps the solve time measured when it
was computed. Writes go to a temporary file renamed into place (no torn entries).
"""
from __future__ import annotations

import datetime
import hashlib
import json
import os
import tempfile
from importlib import metadata
from pathlib import Path
from typing import Any

from . import __version__, io, model, schema

CACHED_SOLVERS = ("ih", "ref", "peer")
_SOURCES = {"ih": ("ih.py", "solvers.py", "model.py"),
            "ref": ("ref.py", "model.py"),
            "peer": ("peer.py", "model.py")}
_PKG = Path(__file__).resolve().parent
_code: dict[str, str] = {}


def canonical(doc: Any) -> str:
    return json.dumps(doc, sort_keys=True, separators=(",", ":"), ensure_ascii=True)


def sha256(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def mission_hash(m: model.Mission) -> str:
    return sha256(canonical(m.to_json()))


def code_hash(solver: str) -> str:
    """SHA-256 over the sources the solver runs (file names and bytes)."""
    if solver not in _code:
        h = hashlib.sha256()
        for name in _SOURCES[solver]:
            h.update(name.encode("utf-8") + b"\0")
            h.update((_PKG / name).read_bytes())
        _code[solver] = h.hexdigest()
    return _code[solver]


def version(solver: str) -> dict[str, Any]:
    try:
        ortools = metadata.version("ortools")
    except metadata.PackageNotFoundError:  # pragma: no cover - ortools is pinned
        ortools = "none"
    return {"sva_tools": __version__, "ortools": ortools, "code": code_hash(solver)}


def key_fields(m: model.Mission, solver: str, settings: dict[str, Any]) -> dict[str, Any]:
    if solver not in CACHED_SOLVERS:
        raise ValueError(f"solver {solver!r} is not cached (only {', '.join(CACHED_SOLVERS)})")
    return {"mission": mission_hash(m), "solver": solver,
            "settings": dict(settings), "version": version(solver)}


class Cache:
    def __init__(self, root: str):
        self.root = Path(root)
        self.hits = 0
        self.misses = 0

    def path(self, fields: dict[str, Any]) -> Path:
        solver: str = fields["solver"]
        return self.root / solver / f"{sha256(canonical(fields))}.json"

    def get(self, m: model.Mission, solver: str, settings: dict[str, Any]) -> dict[str, Any] | None:
        """The stored entry {"result": {...}, "measured": {...}} or None on a miss.
        result: {"plan": Plan|None, "us": int|None, "error": str|None}."""
        fields = key_fields(m, solver, settings)
        p = self.path(fields)
        try:
            with open(p, encoding="utf-8") as f:
                doc = json.load(f)
        except (OSError, ValueError):
            self.misses += 1
            return None
        # A stored entry answers only for exactly these key fields, and only when it is
        # whole (docs/schema/cache-entry.schema.json).
        if schema.first_error(doc, "cache-entry") is not None or \
                doc.get("key") != json.loads(canonical(fields)):
            self.misses += 1
            return None
        res = doc.get("result") or {}
        try:
            plan = io.plan_from_json(res["plan"]) if res.get("plan") is not None else None
        except (io.InputError, KeyError):
            self.misses += 1
            return None
        self.hits += 1
        return {"result": {"plan": plan, "us": res.get("us"), "error": res.get("error")},
                "measured": doc.get("measured", {})}

    def put(self, m: model.Mission, solver: str, settings: dict[str, Any], result: dict[str, Any],
            measured: dict[str, Any]) -> Path:
        fields = key_fields(m, solver, settings)
        p = self.path(fields)
        p.parent.mkdir(parents=True, exist_ok=True)
        plan = result.get("plan")
        doc = {"key": json.loads(canonical(fields)), "mission_name": m.name,
               "result": {"plan": plan.to_json() if plan is not None else None,
                          "us": result.get("us"), "error": result.get("error")},
               "measured": measured}
        fd, tmp = tempfile.mkstemp(prefix=".tmp-", suffix=".json", dir=p.parent)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                json.dump(doc, f, indent=1, sort_keys=True)
                f.write("\n")
            os.replace(tmp, p)
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise
        return p


def measurement(load: tuple[float, float, float] | None = None) -> dict[str, Any]:
    """When and under what load a result is measured (stored with it)."""
    la = load if load is not None else os.getloadavg()
    return {"utc": datetime.datetime.now(datetime.timezone.utc).strftime("%Y-%m-%dT%H:%M:%SZ"),
            "loadavg": [round(x, 2) for x in la], "cpus": os.cpu_count()}
