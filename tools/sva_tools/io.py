"""SPEC section 3 files in, SPEC section 4 errors out.

Missions and plans are parsed strictly: unknown or duplicate keys, wrong types and
values outside their bound are errors (InputError) naming the field, the rule and the
limit, e.g. "targets[3].need: must be >= 1, got 0". Commands turn an InputError into
one line `sva-tools: error: FILE: MESSAGE` and exit status 2.
"""
from __future__ import annotations

import json
import os
import sys
from typing import Any, Dict, List, Optional

from . import model as M


class InputError(Exception):
    """A mission or plan file breaks SPEC section 3/4. str() is the one-line message;
    `path` names the file when it came from load_mission/load_plan."""

    def __init__(self, message: str, path: Optional[str] = None):
        super().__init__(message)
        self.path = path


def _no_duplicates(pairs):
    out = {}
    for k, v in pairs:
        if k in out:
            raise InputError(f"{k}: duplicate key")
        out[k] = v
    return out


def read_json(path: str) -> Any:
    try:
        with open(path, "r", encoding="utf-8") as f:
            text = f.read()
    except OSError as e:
        raise InputError(f"cannot read file: {e.strerror}") from None
    except UnicodeDecodeError:
        raise InputError("file is not UTF-8 text") from None
    try:
        return json.loads(text, object_pairs_hook=_no_duplicates)
    except json.JSONDecodeError as e:
        raise InputError(f"not valid JSON: {e.msg} at line {e.lineno} column {e.colno}") from None
    except RecursionError:
        raise InputError("not valid JSON: nested too deeply") from None


def _is_int(v: Any) -> bool:
    return isinstance(v, int) and not isinstance(v, bool)


def _obj(v: Any, where: str, required: List[str], optional: List[str]) -> Dict[str, Any]:
    if not isinstance(v, dict):
        raise InputError(f"{where or 'file'}: must be a JSON object")
    for k in v:
        if k not in required and k not in optional:
            raise InputError(f"{_join(where, k)}: unknown key")
    for k in required:
        if k not in v:
            raise InputError(f"{_join(where, k)}: missing key")
    return v


def _join(where: str, key: str) -> str:
    return f"{where}.{key}" if where else key


def _int(v: Any, where: str, lo: Optional[int] = None, hi: Optional[int] = None,
         lo_name: str = "", hi_name: str = "") -> int:
    if not _is_int(v):
        raise InputError(f"{where}: must be an integer, got {json.dumps(v)}")
    if lo is not None and v < lo:
        lim = f"{lo_name} ({lo})" if lo_name else str(lo)
        raise InputError(f"{where}: must be >= {lim}, got {v}")
    if hi is not None and v > hi:
        lim = f"{hi_name} ({hi})" if hi_name else str(hi)
        raise InputError(f"{where}: must be <= {lim}, got {v}")
    return v


def _list(v: Any, where: str, max_len: Optional[int] = None, max_name: str = "") -> list:
    if not isinstance(v, list):
        raise InputError(f"{where}: must be a JSON array")
    if max_len is not None and len(v) > max_len:
        raise InputError(f"{where}: {len(v)} entries exceed {max_name} ({max_len})")
    return v


def _coord(v: Any, where: str) -> int:
    return _int(v, where, M.SVA_COORD_MIN, M.SVA_COORD_MAX, "SVA_COORD_MIN", "SVA_COORD_MAX")


def mission_from_json(doc: Any) -> M.Mission:
    """Validates a SPEC 3 mission (every SPEC 4 rule, default-profile bounds)."""
    d = _obj(doc, "", ["name", "depot", "uavs", "targets"],
             ["ticks_per_cell", "hover_fuel", "overlap_percent", "change_penalty"])
    if not isinstance(d["name"], str):
        raise InputError("name: must be a string")
    dep = _obj(d["depot"], "depot", ["x", "y"], [])
    depot = (_coord(dep["x"], "depot.x"), _coord(dep["y"], "depot.y"))
    tpc = _int(d.get("ticks_per_cell", M.DEFAULT_TICKS_PER_CELL), "ticks_per_cell",
               1, M.SVA_MAX_TICKS_PER_CELL, "", "SVA_MAX_TICKS_PER_CELL")
    hover = _int(d.get("hover_fuel", M.DEFAULT_HOVER_FUEL), "hover_fuel",
                 0, M.SVA_MAX_HOVER_FUEL, "", "SVA_MAX_HOVER_FUEL")
    ovl = _int(d.get("overlap_percent", M.DEFAULT_OVERLAP_PERCENT), "overlap_percent", 0, 100)
    # SPEC 5.4: a live mission's price of a changed visit; planning ignores it.
    penalty = _int(d.get("change_penalty", 0), "change_penalty", 0, M.SVA_MAX_CHANGE_PENALTY,
                   "", "SVA_MAX_CHANGE_PENALTY")
    uavs = []
    seen: Dict[int, int] = {}
    for i, u in enumerate(_list(d["uavs"], "uavs", M.SVA_MAX_UAVS, "SVA_MAX_UAVS")):
        w = f"uavs[{i}]"
        u = _obj(u, w, ["id", "x", "y", "fuel"], ["ready_at"])
        uid = _int(u["id"], w + ".id", 1, M.SVA_MAX_ID, "", "SVA_MAX_ID")
        if uid in seen:
            raise InputError(f"{w}.id: duplicate id {uid} (same as uavs[{seen[uid]}])")
        seen[uid] = i
        uavs.append(M.Uav(uid, _coord(u["x"], w + ".x"), _coord(u["y"], w + ".y"),
                          _int(u["fuel"], w + ".fuel", 0, M.SVA_MAX_FUEL, "", "SVA_MAX_FUEL"),
                          _int(u.get("ready_at", 0), w + ".ready_at", 0, M.SVA_MAX_TICK,
                               "", "SVA_MAX_TICK")))
    targets = []
    seen = {}
    for i, t in enumerate(_list(d["targets"], "targets", M.SVA_MAX_TARGETS, "SVA_MAX_TARGETS")):
        w = f"targets[{i}]"
        t = _obj(t, w, ["id", "x", "y", "start", "end", "need"], [])
        tid = _int(t["id"], w + ".id", 1, M.SVA_MAX_ID, "", "SVA_MAX_ID")
        if tid in seen:
            raise InputError(f"{w}.id: duplicate id {tid} (same as targets[{seen[tid]}])")
        seen[tid] = i
        x, y = _coord(t["x"], w + ".x"), _coord(t["y"], w + ".y")
        start = _int(t["start"], w + ".start", 0, M.SVA_MAX_TICK - 1, "", "SVA_MAX_TICK - 1")
        end = _int(t["end"], w + ".end", 1, M.SVA_MAX_TICK, "", "SVA_MAX_TICK")
        if end <= start:
            raise InputError(f"{w}.end: must be > start ({start}), got {end}")
        need = _int(t["need"], w + ".need", 1, M.SVA_MAX_UAVS, "", "SVA_MAX_UAVS")
        targets.append(M.Target(tid, x, y, start, end, need))
    return M.Mission(d["name"], depot, uavs, targets, tpc, hover, ovl, penalty)


def plan_from_json(doc: Any) -> M.Plan:
    """Validates the shape of a SPEC 3 plan (types and keys; not its figures: that is
    the checker's job)."""
    d = _obj(doc, "", ["mission", "algorithm", "status", "covered", "uncovered", "cost",
                       "routes"], ["stats", "stranded"])
    for k in ("mission", "algorithm"):
        if not isinstance(d[k], str):
            raise InputError(f"{k}: must be a string")
    if d["status"] not in ("complete", "partial"):
        raise InputError(f"status: must be \"complete\" or \"partial\", got {json.dumps(d['status'])}")
    covered = _int(d["covered"], "covered", 0)
    uncovered = [_int(v, f"uncovered[{i}]") for i, v in enumerate(_list(d["uncovered"], "uncovered"))]
    cost = _int(d["cost"], "cost", 0)
    routes = []
    for i, r in enumerate(_list(d["routes"], "routes")):
        w = f"routes[{i}]"
        r = _obj(r, w, ["uav", "targets", "distance", "fuel_used"], [])
        ts = [_int(v, f"{w}.targets[{j}]") for j, v in enumerate(_list(r["targets"], w + ".targets"))]
        routes.append(M.Route(_int(r["uav"], w + ".uav"), ts, _int(r["distance"], w + ".distance", 0),
                              _int(r["fuel_used"], w + ".fuel_used", 0)))
    stats = d.get("stats")
    if stats is not None and not isinstance(stats, dict):
        raise InputError("stats: must be a JSON object")
    stranded = [_int(v, f"stranded[{i}]") for i, v in enumerate(_list(d.get("stranded", []), "stranded"))]
    return M.Plan(d["mission"], d["algorithm"], d["status"], covered, uncovered, cost, routes,
                  stats, stranded)


def _load(path: str, parse):
    try:
        return parse(read_json(path))
    except InputError as e:
        e.path = path
        raise


def load_mission(path: str) -> M.Mission:
    """The mission in `path`; InputError (with .path) on any SPEC 3/4 breach. The
    `sva-tools` entry point turns an uncaught one into the SPEC 4 message, exit 2."""
    return _load(path, mission_from_json)


def load_plan(path: str) -> M.Plan:
    return _load(path, plan_from_json)


def write_json(doc: Any, path: Optional[str]) -> None:
    """Writes doc to path ('-' or None: stdout), atomically for files."""
    text = json.dumps(doc, indent=2) + "\n"
    if path in (None, "-"):
        sys.stdout.write(text)
        return
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


def fail(path: str, err: InputError) -> int:
    print(f"sva-tools: error: {path}: {err}", file=sys.stderr)
    return 2
