"""A campaign spec (YAML, docs/campaigns.md): read, validated against spec.schema.json
with one-line errors naming the field, the rule and the limit, and expanded into tasks.

Missions are generated here, on the client, by sva_tools.gen (the same missions as
`sva-tools gen` writes), so every task's key (tasks.task_key: the mission's content
hash, the tool, its settings and version) is known before anything is submitted.
"""
from __future__ import annotations

import functools
import json
from pathlib import Path
from typing import Any, Dict, List, Optional

from jsonschema import Draft202012Validator

from .. import gen
from ..schema import field_path, json_type
from . import tasks as T

SCHEMA = Path(__file__).resolve().parent / "spec.schema.json"
DEFAULT_REF = {"det_limit": 10.0, "time_limit": 600.0, "max_targets": 40}
DEFAULT_EVENTS = 10


class SpecError(ValueError):
    pass


@functools.lru_cache(maxsize=None)
def schema() -> dict:
    with open(SCHEMA, encoding="utf-8") as f:
        return json.load(f)


def _leaf(err):
    """The most telling error of a oneOf/anyOf: one from the branch whose type matched."""
    while err.validator in ("oneOf", "anyOf") and err.context:
        typed = [e for e in err.context if e.validator != "type"]
        if not typed:
            return err
        err = min(typed, key=lambda e: len(list(e.absolute_path)))
    return err


def _message(err) -> str:
    top = err
    err = _leaf(err)
    where = field_path("spec", list(err.absolute_path))
    kw, v, sch = err.validator, err.instance, err.schema if isinstance(err.schema, dict) else {}
    if kw == "type":
        return f"{where}: must be {' or '.join(err.validator_value) if isinstance(err.validator_value, list) else err.validator_value}, got {json_type(v)}"
    if kw in ("oneOf", "anyOf"):
        kinds = sorted({e.validator_value for e in top.context if e.validator == "type"})
        return f"{where}: must be {' or '.join(map(str, kinds))}, got {json_type(v)}"
    if kw == "additionalProperties":
        extra = next(k for k in v if k not in sch.get("properties", {}))
        return f"{where}: unknown key {json.dumps(extra)} (known: {', '.join(sch.get('properties', {}))})"
    if kw == "required":
        missing = next(k for k in err.validator_value if k not in v)
        return f"{where}: missing key {json.dumps(missing)}"
    if kw in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        op = {"minimum": ">=", "maximum": "<=", "exclusiveMinimum": ">", "exclusiveMaximum": "<"}[kw]
        name = sch.get(f"x-sva-{kw}-name")
        limit = f"{err.validator_value} ({name})" if name else str(err.validator_value)
        return f"{where}: must be {op} {limit}, got {json.dumps(v)}"
    if kw == "enum":
        return f"{where}: must be one of {', '.join(json.dumps(x) for x in err.validator_value)}, got {json.dumps(v)}"
    if kw in ("minItems", "maxItems"):
        word = "at least" if kw == "minItems" else "at most"
        return f"{where}: must have {word} {err.validator_value} entries, got {len(v)}"
    if kw == "uniqueItems":
        return f"{where}: entries must be unique, got {json.dumps(v)}"
    if kw == "pattern":
        return f"{where}: must match {err.validator_value}, got {json.dumps(v)}"
    return f"{where}: {err.message}"


def validate(doc: Any) -> dict:
    """The spec with defaults filled in; raises SpecError with the first error."""
    errs = sorted(Draft202012Validator(schema()).iter_errors(doc),
                  key=lambda e: [str(p) for p in e.absolute_path])
    if errs:
        raise SpecError(_message(errs[0]))
    spec = json.loads(json.dumps(doc))
    if spec["kind"] == "plan" and "penalties" in spec:
        raise SpecError("penalties: only for kind \"live\" (a live scenario's change_penalty), got kind \"plan\"")
    for i, s in enumerate(spec["sets"]):
        if spec["kind"] == "plan" and ("events" in s or "ref_count" in s):
            key = "events" if "events" in s else "ref_count"
            raise SpecError(f"sets[{i}].{key}: only for kind \"live\", got kind \"plan\"")
        for r in ("width", "need"):
            if isinstance(s.get(r), list) and s[r][0] > s[r][1]:
                raise SpecError(f"sets[{i}].{r}: must be [LO, HI] with LO <= HI, got {json.dumps(s[r])}")
        n = s.get("count", spec.get("count", 1))
        if s.get("ref_count", 0) > n:
            raise SpecError(f"sets[{i}].ref_count: must be <= the set's count ({n}), got {s['ref_count']}")
    labels = [set_label(s) for s in spec["sets"]]
    for i, label in enumerate(labels):
        if label in labels[:i]:
            raise SpecError(f"sets[{i}]: label {label!r} already names sets[{labels.index(label)}]; "
                            "give one of them a distinct label")
    spec.setdefault("count", 1)
    spec.setdefault("seeds", {"first": 1})
    spec["seeds"].setdefault("count", 1)
    ref = spec.get("ref", False)
    spec["ref"] = dict(DEFAULT_REF, **ref) if isinstance(ref, dict) else (dict(DEFAULT_REF) if ref else None)
    if spec["kind"] == "live":
        spec.setdefault("penalties", [0])
    return spec


def load(path: str) -> dict:
    import yaml
    try:
        with open(path, encoding="utf-8") as f:
            doc = yaml.safe_load(f)
    except OSError as e:
        raise SpecError(f"cannot read: {e.strerror}") from None
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" at line {mark.line + 1}, column {mark.column + 1}" if mark else ""
        raise SpecError(f"not YAML{where}: {getattr(e, 'problem', None) or e}") from None
    if not isinstance(doc, dict):
        raise SpecError(f"spec: must be a mapping, got {json_type(doc)}")
    return validate(doc)


def _range(v, default):
    if v is None:
        return default
    return (v, v) if isinstance(v, int) else (v[0], v[1])


def gen_kwargs(s: dict) -> dict:
    kw = {"width": _range(s.get("width"), (20, 40)), "need": _range(s.get("need"), (2, 2))}
    for k in ("ratio", "max_coord", "fuel", "hover", "ticks_per_cell", "overlap_percent"):
        if k in s:
            kw[k] = s[k]
    return kw


def missions(spec: dict) -> int:
    """Missions (kind plan) or scenarios (kind live) the spec names."""
    return sum(s.get("count", spec["count"]) for s in spec["sets"]) * spec["seeds"]["count"]


def set_label(s: dict) -> str:
    return s.get("label") or f"{s['targets']}x{s['uavs']}"


def _base(spec: dict, run: str, s: dict, seed: int, index: int) -> dict:
    return {"campaign": spec["name"], "run": run, "set": set_label(s), "targets": s["targets"],
            "uavs": s["uavs"], "seed": seed, "index": index, "penalty": None}


def _task(base: dict, task: str, tool: str, mission_doc: dict, settings: dict,
          penalty: Optional[int] = None, coverable: Optional[int] = None) -> dict:
    version = T.tool_version(task)
    mh = T.mission_hash(mission_doc)
    key_settings = dict(settings, penalty=penalty) if task == "fly" else settings
    t = dict(base, task=task, tool=tool, settings=settings, version=version, mission_hash=mh,
             mission_name=(mission_doc.get("mission") or mission_doc).get("name"),
             mission=T.canonical(mission_doc), coverable=coverable,
             key=T.task_key(task, tool, mh, key_settings, version))
    if penalty is not None:
        t["penalty"] = penalty
    return t


def plan_settings(spec: dict) -> dict:
    return {k: spec[k] for k in ("flow_work", "repeat") if k in spec}


def ref_settings(spec: dict) -> dict:
    return {"det_limit": float(spec["ref"]["det_limit"]), "time_limit": float(spec["ref"]["time_limit"])}


def first_tasks(spec: dict, run: str) -> List[dict]:
    """Every task the spec names before any result is known: for kind plan, each
    mission's planner and ref tasks; for kind live, each scenario's flights (their
    replans' ref tasks follow from the flight logs: ref_tasks)."""
    out = []
    seeds = range(spec["seeds"]["first"], spec["seeds"]["first"] + spec["seeds"]["count"])
    for s in spec["sets"]:
        kw = gen_kwargs(s)
        for seed in seeds:
            for i in range(s.get("count", spec["count"])):
                base = _base(spec, run, s, seed, i)
                if spec["kind"] == "plan":
                    doc = gen.generate(s["targets"], s["uavs"], seed=seed, index=i, **kw).to_json()
                    settings = plan_settings(spec)
                    for algo in spec["algorithms"]:
                        out.append(_task(base, "plan", algo, doc, settings if algo == "flow" else {},
                                         coverable=s["targets"]))
                    if spec["ref"] and s["targets"] <= spec["ref"]["max_targets"]:
                        out.append(_task(base, "ref", "ref", doc, ref_settings(spec), coverable=s["targets"]))
                else:
                    doc = gen.generate_scenario(s["targets"], s["uavs"], s.get("events", DEFAULT_EVENTS),
                                                seed=seed, index=i, name=f"live_{i:04d}", **kw)
                    for algo in spec["algorithms"]:
                        for pen in spec["penalties"]:
                            out.append(_task(base, "fly", algo, doc, {}, penalty=pen))
    return out


def ref_tasks(spec: dict, run: str, flights: List[dict], logs: Dict[str, dict]) -> List[dict]:
    """ref on the residual missions (with a target) of the replans of each set's first
    ref_count scenarios (default: all) per seed, once per distinct residual mission."""
    if not spec["ref"]:
        return []
    by_set = {set_label(s): s for s in spec["sets"]}
    out, seen = [], set()
    for f in flights:
        s = by_set[f["set"]]
        if f["index"] >= s.get("ref_count", s.get("count", spec["count"])) or f["key"] not in logs:
            continue
        for doc in T.residuals(logs[f["key"]]):
            if len(doc["targets"]) > spec["ref"]["max_targets"]:
                continue
            t = _task(_base(spec, run, s, f["seed"], f["index"]), "ref", "ref", doc, ref_settings(spec),
                      coverable=len(doc["targets"]))
            if t["key"] not in seen:
                seen.add(t["key"])
                out.append(t)
    return out
