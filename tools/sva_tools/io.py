"""SPEC section 3 files in, SPEC section 4 errors out.

Files are read as strictly as the C CLI reads them (UTF-8, no duplicate keys, no NUL)
and checked against their JSON Schema (docs/schema, sva_tools.schema) plus the rules a
schema cannot express. Every breach is an InputError naming the field, the rule and the
limit in the CLI's words, e.g. "targets[3].need: must be >= 1, got 0". Commands turn an
InputError into one line `sva-tools: error: FILE: MESSAGE` (`FILE:LINE:COLUMN: ...` for
a syntax error) and exit status 2.
"""
from __future__ import annotations

import json
import math
import os
import sys
from typing import Any, Callable, NoReturn, TypeVar

from . import model, schema

_T = TypeVar("_T")


class InputError(Exception):
    """A mission or plan file breaks SPEC section 3/4. str() is the one-line message;
    `path` names the file when it came from load_mission/load_plan; `where` is the
    place in it (`LINE:COLUMN` of a syntax error, `LINE` of a JSON Lines record)."""

    def __init__(self, message: str, path: str | None = None, where: str = ""):
        super().__init__(message)
        self.path = path
        self.where = where


def _no_duplicates(pairs: list[tuple[str, Any]]) -> dict[str, Any]:
    out = {}
    for k, v in pairs:
        if k in out:
            raise _DuplicateKey(k)
        out[k] = v
    return out


class _DuplicateKey(Exception):
    pass


class _TooBig(Exception):
    pass


class _NotFinite(Exception):
    pass


def _constant(name: str) -> NoReturn:
    # NaN and Infinity are not JSON (RFC 8259); Python's reader takes them, jansson not.
    raise _NotFinite(f"invalid token {name}")


def _real(text: str) -> float:
    v = float(text)
    if math.isinf(v):
        raise _NotFinite(f"real number overflow {text}")
    return v


def _int64(digits: str) -> int:
    # jansson's json_int_t, as the CLI reads it: integers beyond int64 are a syntax error.
    v = int(digits)
    if not -2**63 <= v < 2**63:
        raise _TooBig(digits)
    return v


def _has_nul(doc: Any) -> bool:
    todo = [doc]
    while todo:
        v = todo.pop()
        if isinstance(v, str) and "\0" in v:
            return True
        if isinstance(v, dict):
            todo.extend(v.keys())
            todo.extend(v.values())
        elif isinstance(v, list):
            todo.extend(v)
    return False


def _line_col(text: str, offset: int) -> str:
    line = text.count("\n", 0, offset) + 1
    return f"{line}:{offset - (text.rfind(chr(10), 0, offset) + 1) + 1}"


def parse_json(data: bytes) -> Any:
    """One JSON document from bytes, as strictly as the CLI reads it: UTF-8, no
    duplicate keys, no NUL, nothing after the document. InputError names the place."""
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        partial = data[:e.start].decode("utf-8", errors="replace")
        raise InputError(f"invalid JSON: unable to decode byte 0x{data[e.start]:02x}",
                         where=_line_col(partial, len(partial))) from None
    if not text.strip():
        raise InputError("empty input")
    if "\0" in text:
        raise InputError("invalid JSON: NUL byte in input", where=_line_col(text, text.index("\0")))
    try:
        doc = json.loads(text, object_pairs_hook=_no_duplicates, parse_int=_int64,
                         parse_float=_real, parse_constant=_constant)
    except json.JSONDecodeError as e:
        raise InputError(f"invalid JSON: {e.msg}", where=f"{e.lineno}:{e.colno}") from None
    except _DuplicateKey as e:
        raise InputError(f"invalid JSON: duplicate object key {json.dumps(e.args[0])}") from None
    except _TooBig as e:
        raise InputError(f"invalid JSON: too big integer {e.args[0]}") from None
    except _NotFinite as e:
        raise InputError(f"invalid JSON: {e.args[0]}") from None
    except RecursionError:
        raise InputError("invalid JSON: nested too deeply") from None
    if _has_nul(doc):
        raise InputError("invalid JSON: \\u0000 is not allowed in a string")
    return doc


# The CLI's input cap (docs/SPEC.md section 4).
MAX_INPUT_BYTES = 16 * 1024 * 1024


def read_json(path: str) -> Any:
    try:
        with open(path, "rb") as f:
            data = f.read(MAX_INPUT_BYTES + 1)
    except OSError as e:
        raise InputError(f"cannot open: {e.strerror}") from None
    if len(data) > MAX_INPUT_BYTES:
        raise InputError(f"input exceeds {MAX_INPUT_BYTES} bytes")
    return parse_json(data)


def check(doc: Any, kind: str) -> None:
    """Raises InputError with the first error of doc as a `kind` file (docs/schema and
    the rules a schema cannot express, schema.first_error)."""
    message = schema.first_error(doc, kind)
    if message is not None:
        raise InputError(message)


def mission_from_json(doc: Any) -> model.Mission:
    """Validates a SPEC 3 mission (the schema, every SPEC 4 rule, default-profile bounds)."""
    check(doc, "mission")
    uavs = [model.Uav(u["id"], u["x"], u["y"], u["fuel"], u.get("ready_at", 0)) for u in doc["uavs"]]
    targets = [model.Target(t["id"], t["x"], t["y"], t["start"], t["end"], t["need"])
               for t in doc["targets"]]
    return model.Mission(doc["name"], (doc["depot"]["x"], doc["depot"]["y"]), uavs, targets,
                     doc.get("ticks_per_cell", model.DEFAULT_TICKS_PER_CELL),
                     doc.get("hover_fuel", model.DEFAULT_HOVER_FUEL),
                     doc.get("overlap_percent", model.DEFAULT_OVERLAP_PERCENT),
                     doc.get("change_penalty", 0), doc.get("takeoff_ticks", 0))


def plan_from_json(doc: Any) -> model.Plan:
    """Validates a SPEC 3 plan against its schema (keys, types, ranges; not its figures:
    that is the checker's job)."""
    check(doc, "plan")
    routes = [model.Route(r["uav"], list(r["targets"]), r["distance"], r["fuel_used"])
              for r in doc["routes"]]
    return model.Plan(doc["mission"], doc["algorithm"], doc["status"], doc["covered"],
                  list(doc["uncovered"]), doc["cost"], routes, doc.get("stats"),
                  list(doc.get("stranded", [])))


def load_trace(path: str) -> list[dict[str, Any]]:
    """The records of a JSON Lines trace (`sva plan --trace`), each checked against the
    trace schema; InputError names the line."""
    try:
        with open(path, "rb") as f:
            lines = f.read().split(b"\n")
    except OSError as e:
        raise InputError(f"cannot open: {e.strerror}", path) from None
    out = []
    for n, line in enumerate(lines, 1):
        if not line.strip():
            continue
        try:
            rec = parse_json(line)
            check(rec, "trace")
        except InputError as e:
            e.path = path
            e.where = f"{n}:{e.where}" if e.where else str(n)
            raise
        out.append(rec)
    return out


def _load(path: str, parse: Callable[[Any], _T]) -> _T:
    try:
        return parse(read_json(path))
    except InputError as e:
        e.path = path
        raise


def load_mission(path: str) -> model.Mission:
    """The mission in `path`; InputError (with .path) on any SPEC 3/4 breach. The
    `sva-tools` entry point turns an uncaught one into the SPEC 4 message, exit 2."""
    return _load(path, mission_from_json)


def load_plan(path: str) -> model.Plan:
    return _load(path, plan_from_json)


def write_json(doc: Any, path: str | None) -> None:
    """Writes doc to path ('-' or None: stdout), atomically for files."""
    text = json.dumps(doc, indent=2) + "\n"
    if path in (None, "-"):
        sys.stdout.write(text)
        return
    tmp = f"{path}.tmp{os.getpid()}"
    with open(tmp, "w", encoding="utf-8") as f:
        f.write(text)
    os.replace(tmp, path)


# Our file kinds, told apart by their top-level keys: what each is and which command takes
# it (the C CLI's port/json names them in the same words).
KIND_TEXT = {
    "mission": "a mission (name, depot, uavs, targets): sva plan takes it",
    "plan": "a plan (mission, algorithm, status, routes): sva-tools check MISSION PLAN takes it",
    "live mission": "a live mission (mission, plan, events, now): sva replan takes it",
    "scenario": "a scenario (mission, events, change_penalty): sva-tools sim takes it",
    "flight log": ("a flight log (scenario, uavs, targets, replans): sva-tools sim writes it, "
                   "and takes its scenario"),
}


def kind_of(doc: Any, expected: str = "") -> str:
    """The kind (a KIND_TEXT key) `doc` is by its top-level keys, "" when none. A
    {mission, events} document is both a scenario and a live mission: it is `expected`
    when that is one of the two, else a scenario."""
    if not isinstance(doc, dict):
        return ""
    if "scenario" in doc and "replans" in doc:
        return "flight log"
    if "routes" in doc:
        return "plan"
    if isinstance(doc.get("mission"), dict):
        if "change_penalty" in doc:
            return "scenario"
        if "plan" in doc or "now" in doc or "events" not in doc:
            return "live mission"
        return expected if expected in ("scenario", "live mission") else "scenario"
    if "mission" not in doc and any(k in doc for k in ("depot", "uavs", "targets")):
        return "mission"
    return ""


def wrong_kind(doc: Any, expected: str, taker: str) -> None:
    """Raises InputError "this is KIND (KEYS): COMMAND takes it; TAKER" when `doc` is
    another of our kinds than `expected` (taker: what the command takes, e.g. "sva-tools
    sim takes a scenario (mission, events, change_penalty; SPEC 12.5)")."""
    kind = kind_of(doc, expected)
    if kind and kind != expected:
        raise InputError(f"this is {KIND_TEXT[kind]}; {taker}")
