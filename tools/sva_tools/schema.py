"""The JSON Schemas of sva's files (docs/schema/, docs/SPEC.md section 3) and the rules
a schema cannot express, as one-line SPEC section 4 messages.

Kinds: mission, plan, trace (one record of a JSON Lines trace), bound (`ref --bound`),
cache-entry (`bench --cache`). `first_error(doc, kind)` returns the message of the first
error in the order the C CLI reports them: shape errors (unknown keys, then missing
keys, wrong types, integers beyond int32, the name) before value rules, each in
document order (SPEC key order, list index); then rules that need more than one field
(duplicate ids, end > start) and the default profile's bounds (list lengths, need), or
another profile's within `profile_bounds(uavs, targets)`.
Messages match the CLI's word for word, e.g. `targets[1].need: must be >= 1, got 0`,
`uavs[0]: unknown key "speed"`, `uavs: 65 entries exceed SVA_MAX_UAVS (64)`.

Integers are JSON numbers written without a fraction or exponent: 5.0 is a real here
(JSON Schema's own "integer" would take it), as it is for the CLI.
"""
from __future__ import annotations

import contextlib
import functools
import json
from collections.abc import Iterator, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

from jsonschema import Draft202012Validator, validators
from referencing import Registry, Resource

from .frame import ISO_RULE, t0_rule
from .model import SVA_MAX_TARGETS, SVA_MAX_UAVS

if TYPE_CHECKING:
    from typing import TypeGuard

# The repository's docs/schema; an installed package carries a copy (schema_files/).
SCHEMA_DIR = Path(__file__).resolve().parents[2] / "docs" / "schema"
if not (SCHEMA_DIR / "mission.schema.json").is_file():
    SCHEMA_DIR = Path(__file__).resolve().parent / "schema_files"
KINDS = ("mission", "plan", "trace", "bound", "cache-entry")
# How messages name the document itself (the CLI calls a mission's root "mission").
# SVA_MAX_UAVS and SVA_MAX_TARGETS as the mission rules check them (profile_bounds).
_BOUNDS = {"SVA_MAX_UAVS": SVA_MAX_UAVS, "SVA_MAX_TARGETS": SVA_MAX_TARGETS}


@contextlib.contextmanager
def profile_bounds(uavs: int, targets: int) -> Iterator[None]:
    """Within it, missions are checked against SVA_MAX_UAVS = uavs and SVA_MAX_TARGETS =
    targets: another bound profile's (core/profiles/), as a CLI built with it checks them."""
    saved = dict(_BOUNDS)
    _BOUNDS.update(SVA_MAX_UAVS=uavs, SVA_MAX_TARGETS=targets)
    try:
        yield
    finally:
        _BOUNDS.update(saved)


ROOT_NAMES = {"mission": "mission", "plan": "plan", "trace": "record", "bound": "bound",
              "cache-entry": "entry"}

# Document order of keys (SPEC section 3 order): one ranking serves every object.
_KEY_ORDER = ("name", "mission", "frame", "lat", "lon", "alt_m", "cell_m", "tick_s", "t0",
              "algorithm", "status", "covered", "uncovered", "cost",
              "depot", "ticks_per_cell", "hover_fuel", "overlap_percent", "change_penalty",
              "takeoff_ticks",
              "uavs", "id", "uav",
              "x", "y", "fuel", "ready_at", "targets", "start", "end", "need", "distance",
              "fuel_used", "routes", "stranded", "stats")
_KEY_RANK = {k: i for i, k in enumerate(_KEY_ORDER)}
_AFTER_FIELDS = 1000  # rules over a whole list element come after its fields
_SHAPE, _VALUE = 0, 1


def _is_int(_checker: Any, value: Any) -> bool:
    return isinstance(value, int) and not isinstance(value, bool)


# types-jsonschema leaves validators.extend unannotated
_Validator = validators.extend(  # type: ignore[no-untyped-call]
    Draft202012Validator,
    type_checker=Draft202012Validator.TYPE_CHECKER.redefine("integer", _is_int))


@functools.cache
def schemas() -> dict[str, dict[str, Any]]:
    """Every schema of docs/schema by kind."""
    out = {}
    for kind in KINDS:
        with open(SCHEMA_DIR / f"{kind}.schema.json", encoding="utf-8") as f:
            out[kind] = json.load(f)
    return out


@functools.cache
def _registry() -> Registry:
    return Registry().with_resources(
        (s["$id"], Resource.from_contents(s)) for s in schemas().values())


@functools.cache
def validator(kind: str, definition: str = "") -> Draft202012Validator:
    """The validator of a kind's schema, or of one of its $defs (e.g. plan's cli_stats:
    the stats exactly as `sva plan` writes them)."""
    if kind not in KINDS:
        raise ValueError(f"unknown kind {kind!r} (known: {', '.join(KINDS)})")
    s = schemas()[kind]
    if definition:
        if definition not in s.get("$defs", {}):
            raise ValueError(f"{kind} schema has no definition {definition!r}")
        s = {"$ref": f"{s['$id']}#/$defs/{definition}"}
    checker: Draft202012Validator = _Validator(s, registry=_registry())
    return checker


def version() -> int:
    """The schema version (SVA_SCHEMA_VERSION of sva.h); every schema carries it."""
    return int(schemas()["mission"]["x-sva-schema-version"])


def json_type(value: Any) -> str:
    """The CLI's name of a JSON value's type."""
    if isinstance(value, bool):
        return "boolean"
    if isinstance(value, int):
        return "integer"
    if isinstance(value, float):
        return "real"
    if isinstance(value, str):
        return "string"
    if isinstance(value, list):
        return "array"
    if isinstance(value, dict):
        return "object"
    return "null"


def field_path(root: str, parts: Sequence[str | int]) -> str:
    """`targets[1].need` from ["targets", 1, "need"]; the root's name when empty."""
    out = ""
    for p in parts:
        out += f"[{p}]" if isinstance(p, int) else (f".{p}" if out else str(p))
    return out or root


def _position(parts: Sequence[str | int]) -> Position:
    return tuple((p, "") if isinstance(p, int) else (_KEY_RANK.get(p, len(_KEY_RANK)), p)
                 for p in parts)


# Where an error is: per path part, (index, "") or (key rank, key).
Position = tuple[tuple[int, str], ...]
# One candidate error: (phase, position, order at that position, message).
Found = tuple[int, Position, int, str]


def _article(type_name: str) -> str:
    return "an" if type_name[0] in "aeiou" else "a"


def _described(err: Any, root: str, prefix: tuple[str | int, ...] = ()) -> Found | None:
    # err: a jsonschema ValidationError; Any, as its stub types each field as possibly unset
    # while the validator has set every one it reports.
    kw, sch, v = err.validator, err.schema, err.instance
    parts = list(prefix) + list(err.absolute_path)
    where = field_path(root, parts)
    pos = _position(parts)
    rule = sch.get("x-sva-rule") if isinstance(sch, dict) else None
    if kw == "type":
        want = err.validator_value
        want = want if isinstance(want, str) else " or ".join(want)
        article = "" if want == "null" else _article(want) + " "
        return (_SHAPE, pos, 2, f"{where}: must be {article}{want}, got {json_type(v)}")
    if kw == "additionalProperties":
        known = sch.get("properties", {})
        extra = next(k for k in v if k not in known)
        return (_SHAPE, pos, 0, f"{where}: unknown key {json.dumps(extra)}")
    if kw == "required":
        missing = next(k for k in err.validator_value if k not in v)
        return (_SHAPE, pos, 1, f"{where}: missing key {json.dumps(missing)}")
    if rule == "int32" and kw in ("minimum", "maximum"):
        return (_SHAPE, pos, 3, f"{where}: must be an integer in [-2147483648, 2147483647], got {v}")
    if rule == "name" and kw in ("minLength", "maxLength"):
        return (_SHAPE, pos, 3, f"{where}: must be a non-empty string of at most "
                                f"{schemas()['mission']['$defs']['name']['maxLength']} bytes, "
                                f"got {len(v.encode('utf-8'))}")
    if kw in ("minimum", "maximum"):
        name = sch.get(f"x-sva-{kw}-name")
        limit = f"{name} ({err.validator_value})" if name else str(err.validator_value)
        return (_VALUE, pos, 0, f"{where}: must be {'>=' if kw == 'minimum' else '<='} {limit}, got {v}")
    if kw == "enum":
        allowed = ", ".join(json.dumps(x) for x in err.validator_value)
        return (_VALUE, pos, 0, f"{where}: must be one of {allowed}, got {json.dumps(v)}")
    if kw == "const":
        return (_VALUE, pos, 0, f"{where}: must be {json.dumps(err.validator_value)}, got {json.dumps(v)}")
    if kw == "uniqueItems":
        first: dict[str, int] = {}
        for j, item in enumerate(v):
            key = json.dumps(item, sort_keys=True)
            if key in first:
                return (_VALUE, _position(parts + [j]), 0,
                        f"{field_path(root, parts + [j])}: duplicate {key} (first at index {first[key]})")
            first[key] = j
    if kw in ("minItems", "maxItems"):
        if isinstance(sch, dict) and "x-sva-message" in sch:
            return (_VALUE, pos, 0, f"{where}: {sch['x-sva-message']}, got {len(v)} entries")
        word = "at least" if kw == "minItems" else "at most"
        return (_VALUE, pos, 0, f"{where}: must have {word} {err.validator_value} entries, got {len(v)}")
    if kw in ("oneOf", "anyOf") and err.context:
        # "null or X": report why the value is not an X.
        inner = [_described(e, root, prefix) for e in err.context if e.validator != "type"
                 or e.validator_value != "null"]
        candidates = [f for f in inner if f is not None]
        if candidates:
            return min(candidates, key=lambda f: f[:3])
        return (_SHAPE, pos, 2, f"{where}: must be null or {_article(_first_type(err))} "
                                f"{_first_type(err)}, got {json_type(v)}")
    if rule == "utc-time" and kw == "pattern":
        return (_VALUE, pos, 0, f"{where}: {ISO_RULE}, got {json.dumps(v)}")
    if kw == "pattern":
        return (_VALUE, pos, 0, f"{where}: must match {err.validator_value}, got {json.dumps(v)}")
    return (_VALUE, pos, 0, f"{where}: {err.message}")


def _first_type(err: Any) -> str:
    for e in err.context:
        if e.validator == "type" and e.validator_value != "null":
            return e.validator_value if isinstance(e.validator_value, str) else e.validator_value[0]
    return "value"


def _int(value: Any) -> TypeGuard[int]:
    return _is_int(None, value)


def _duplicate_ids(items: list[Any], list_name: str, found: list[Found]) -> None:
    first: dict[int, int] = {}
    for i, item in enumerate(items):
        if not isinstance(item, dict) or not _int(item.get("id")):
            continue
        uid = item["id"]
        if uid in first:
            found.append((_VALUE, _position([list_name, i]) + ((_AFTER_FIELDS + 1, ""),), 0,
                          f"{list_name}[{i}].id: duplicate id {uid} (first at index {first[uid]})"))
        else:
            first[uid] = i


def _frame_rules(doc: Any, found: list[Found]) -> None:
    """The frame's t0 (SPEC section 3): a date of the calendar, within the range (its
    form is the schema's pattern, which Python's `$` lets end in a newline)."""
    frame = doc.get("frame")
    if not isinstance(frame, dict) or not isinstance(frame.get("t0"), str):
        return
    rule = t0_rule(frame["t0"])
    if rule:
        found.append((_VALUE, _position(["frame", "t0"]), 0,
                      f"frame.t0: {rule}, got {json.dumps(frame['t0'])}"))


def _plan_rules(doc: Any, found: list[Found]) -> None:
    if isinstance(doc, dict):
        _frame_rules(doc, found)


def _mission_rules(doc: Any, found: list[Found]) -> None:
    """SPEC section 4 rules a schema cannot express; the default profile's bounds."""
    if not isinstance(doc, dict):
        return
    _frame_rules(doc, found)
    name = doc.get("name")
    limit = schemas()["mission"]["$defs"]["name"]["maxLength"]
    if isinstance(name, str) and len(name) <= limit < len(name.encode("utf-8")):
        found.append((_SHAPE, _position(["name"]), 3, f"name: must be a non-empty string of at "
                                                      f"most {limit} bytes, got {len(name.encode('utf-8'))}"))
    max_uavs = _BOUNDS["SVA_MAX_UAVS"]
    for key, bound, bound_name in (("uavs", max_uavs, "SVA_MAX_UAVS"),
                                   ("targets", _BOUNDS["SVA_MAX_TARGETS"], "SVA_MAX_TARGETS")):
        items = doc.get(key)
        if isinstance(items, list) and len(items) > bound:
            found.append((_SHAPE, _position([key]), 3,
                          f"{key}: {len(items)} entries exceed {bound_name} ({bound})"))
    uavs, targets = doc.get("uavs"), doc.get("targets")
    if isinstance(uavs, list):
        _duplicate_ids(uavs, "uavs", found)
    if isinstance(targets, list):
        for i, t in enumerate(targets):
            if not isinstance(t, dict):
                continue
            need = t.get("need")
            if _int(need) and need > max_uavs:
                found.append((_VALUE, _position(["targets", i, "need"]), 1,
                              f"targets[{i}].need: must be <= SVA_MAX_UAVS ({max_uavs}), got {need}"))
            start, end = t.get("start"), t.get("end")
            if _int(start) and _int(end) and end <= start:
                found.append((_VALUE, _position(["targets", i]) + ((_AFTER_FIELDS, ""),), 0,
                              f"targets[{i}].end: must be > start ({start}), got {end}"))
        _duplicate_ids(targets, "targets", found)


def _trace_rules(doc: Any, found: list[Found]) -> None:
    """A trace record's lists line up: one entry per source, one per sink."""
    if not isinstance(doc, dict):
        return
    lists: dict[str, Any] = {k: doc.get(k) for k in ("source_uavs", "supply", "sink_targets", "demand",
                                     "dropped", "cost", "flow")}
    if not all(isinstance(v, list) for v in lists.values()):
        return
    sources, sinks = len(lists["source_uavs"]), len(lists["sink_targets"])
    for k, want, per in (("supply", sources, "source"), ("cost", sources, "source"),
                         ("flow", sources, "source"), ("demand", sinks, "sink"),
                         ("dropped", sinks, "sink")):
        if len(lists[k]) != want:
            found.append((_VALUE, (), 0, f"{k}: must have one entry per {per} ({want}), "
                                         f"got {len(lists[k])}"))
    for k in ("cost", "flow"):
        for s, row in enumerate(lists[k]):
            if isinstance(row, list) and len(row) != sinks:
                found.append((_VALUE, (), 0, f"{k}[{s}]: must have one entry per sink "
                                             f"({sinks}), got {len(row)}"))
    for s, (crow, frow) in enumerate(zip(lists["cost"], lists["flow"])):
        if isinstance(crow, list) and isinstance(frow, list):
            for j, (c, f) in enumerate(zip(crow, frow)):
                if (c is None) != (f is None):
                    found.append((_VALUE, (), 0, f"flow[{s}][{j}]: must be null exactly where "
                                                 f"cost is, got {json.dumps(f)}"))


_RULES = {"mission": _mission_rules, "plan": _plan_rules, "trace": _trace_rules}


def errors(doc: Any, kind: str, definition: str = "", root: str = "") -> list[str]:
    """Every error of doc as a `kind` file (or as that schema's $defs `definition`,
    named `root` in messages), the CLI's first one first."""
    root = root or ROOT_NAMES[kind]
    prefix = (root,) if definition else ()  # a part of a document: name it from its root
    found = [f for f in (_described(e, root, prefix)
                         for e in validator(kind, definition).iter_errors(doc)) if f is not None]
    if kind in _RULES and not definition:
        _RULES[kind](doc, found)
    found.sort(key=lambda f: f[:3])
    out: list[str] = []
    for f in found:
        if f[3] not in out:
            out.append(f[3])
    return out


def first_error(doc: Any, kind: str) -> str | None:
    """The message of the first error of doc as a `kind` file, or None when it is valid."""
    errs = errors(doc, kind)
    return errs[0] if errs else None
