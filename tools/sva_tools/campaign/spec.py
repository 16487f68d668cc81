"""A campaign spec (YAML, docs/campaigns.md): read, validated against spec.schema.json
with one-line errors naming the field, the rule and the limit, and expanded into tasks.

The spec is untrusted (docs/security.md): the loader bounds the work before the schema
applies. The file is read up to the schema's x-sva-max-bytes, decoded as strict UTF-8,
and composed by PyYAML's safe loader with hooks that refuse anchors and aliases (no
billion laughs), duplicate keys, keys that are not strings, tags beyond JSON's types,
nesting past x-sva-max-depth, more than x-sva-max-nodes nodes and scalars longer than
x-sva-max-scalar-chars, each at the first offence, in document order. Then NaN and
infinities, the schema, the rules across fields and the spec's totals (missions,
generated targets): every refusal is one SpecError `PATH: RULE, got VALUE`.

Missions are generated here, on the client, by sva_tools.gen (the same missions as
`sva-tools gen` writes), so every task's key (tasks.task_key: the mission's content
hash, the tool, its settings and version) is known before anything is submitted.
"""
from __future__ import annotations

import functools
import json
import math
import os
import re
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable, NoReturn, TypeVar, cast

from jsonschema import Draft202012Validator, validators
from jsonschema.exceptions import ValidationError

from .. import gen
from ..schema import field_path, json_type
from . import tasks

if TYPE_CHECKING:
    from yaml import SafeLoader
    from yaml.nodes import Node

_T = TypeVar("_T")

SCHEMA = Path(__file__).resolve().parent / "spec.schema.json"
DEFAULT_REF = {"det_limit": 10.0, "time_limit": 600.0, "max_targets": 40}
DEFAULT_EVENTS = 10


class SpecError(ValueError):
    pass


@functools.cache
def schema() -> dict[str, Any]:
    with open(SCHEMA, encoding="utf-8") as f:
        doc: dict[str, Any] = json.load(f)
        return doc


def limit(name: str) -> int:
    """One of the schema's x-sva-max-* limits: bytes, depth, nodes, scalar-chars,
    missions, generated-targets."""
    return int(schema()[f"x-sva-max-{name}"])


def _is_int(_checker: object, value: Any) -> bool:
    # 5.0 is a real here, as in the mission files (sva_tools.schema): JSON Schema's own
    # "integer" would take it, and gen would then fail on it.
    return isinstance(value, int) and not isinstance(value, bool)


_Validator = validators.extend(  # type: ignore[no-untyped-call]  # extend() has no hints in its stubs
    Draft202012Validator,
    type_checker=Draft202012Validator.TYPE_CHECKER.redefine("integer", _is_int))


def shown_value(v: Any, width: int = 48) -> str:
    """A value as a refusal quotes it: YAML's spelling of NaN and infinities, JSON
    otherwise, cut to about `width` characters."""
    if isinstance(v, float) and not math.isfinite(v):
        return ".nan" if math.isnan(v) else (".inf" if v > 0 else "-.inf")
    try:
        text = json.dumps(v, ensure_ascii=False, allow_nan=False)
    except (TypeError, ValueError):
        text = repr(v)
    return text if len(text) <= width else text[:width] + "..."


def _leaf(err: ValidationError) -> ValidationError:
    """The most telling error of a oneOf/anyOf: one from the branch whose type matched."""
    while err.validator in ("oneOf", "anyOf") and err.context:
        # a type error below the branch's top (ref.det_limit: a string) is the branch's
        typed = [e for e in err.context if e.validator != "type" or len(e.relative_path)]
        if not typed:
            return err
        err = min(typed, key=lambda e: len(list(e.absolute_path)))
    return err


def _message(err: ValidationError) -> str:
    top = err
    err = _leaf(err)
    where = field_path("spec", list(err.absolute_path))
    kw, sch = err.validator, err.schema if isinstance(err.schema, dict) else {}
    # Set on every error the validator yields (Unset only on an error built by hand).
    v: Any = err.instance
    want: Any = err.validator_value
    if kw == "type":
        return f"{where}: must be {' or '.join(want) if isinstance(want, list) else want}, got {json_type(v)}"
    if kw in ("oneOf", "anyOf"):
        types: set[Any] = {e.validator_value for e in top.context if e.validator == "type"}
        kinds = sorted(types)
        return f"{where}: must be {' or '.join(map(str, kinds))}, got {json_type(v)}"
    if kw == "additionalProperties":
        extra = next(k for k in v if k not in sch.get("properties", {}))
        return f"{where}: unknown key {shown_value(extra)} (known: {', '.join(sch.get('properties', {}))})"
    if kw == "required":
        missing = next(k for k in want if k not in v)
        return f"{where}: missing key {json.dumps(missing)}"
    if kw in ("minimum", "maximum", "exclusiveMinimum", "exclusiveMaximum"):
        op = {"minimum": ">=", "maximum": "<=", "exclusiveMinimum": ">", "exclusiveMaximum": "<"}[kw]
        name = sch.get(f"x-sva-{kw}-name")
        limit = f"{want} ({name})" if name else str(want)
        return f"{where}: must be {op} {limit}, got {shown_value(v)}"
    if kw == "enum":
        return f"{where}: must be one of {', '.join(json.dumps(x) for x in want)}, got {shown_value(v)}"
    if kw in ("minItems", "maxItems"):
        word = "at least" if kw == "minItems" else "at most"
        return f"{where}: must have {word} {want} entries, got {len(v)}"
    if kw == "uniqueItems":
        return f"{where}: entries must be unique, got {shown_value(v)}"
    if kw == "pattern":
        rule = sch.get("x-sva-pattern-rule") or f"must match {want}"
        return f"{where}: {rule}, got {shown_value(v)}"
    return f"{where}: {err.message}"


def _first_not_finite(doc: Any) -> tuple[tuple[Any, ...], Any] | None:
    """(path, value) of the first NaN or infinity in document order, else None."""
    todo: list[tuple[tuple[Any, ...], Any]] = [((), doc)]
    while todo:
        parts, v = todo.pop()
        if isinstance(v, float) and not math.isfinite(v):
            return parts, v
        if isinstance(v, dict):
            todo.extend(((*parts, k), x) for k, x in reversed(list(v.items())))
        elif isinstance(v, list):
            todo.extend(((*parts, i), x) for i, x in reversed(list(enumerate(v))))
    return None


# The schema's name and label patterns, anchored at both ends: a pattern's "$" in Python
# (jsonschema) also matches before a final newline.
_NAME = re.compile(r"(?!\.)[A-Za-z0-9_.-]{1,64}")
_LABEL = re.compile(r"[A-Za-z0-9_.-]{1,32}")


def _totals(spec: dict[str, Any]) -> None:
    """The spec's totals: missions or scenarios, and targets the client generates (it
    holds every mission of its task list), within the schema's limits."""
    n = missions(spec)
    if n > limit("missions"):
        raise SpecError(f"spec: must name at most {limit('missions')} missions or scenarios in all "
                        f"(each set's count x seeds.count, summed), got {n}")
    targets = sum(s["targets"] * s.get("count", spec["count"]) for s in spec["sets"]) * spec["seeds"]["count"]
    if targets > limit("generated-targets"):
        raise SpecError(f"spec: must generate at most {limit('generated-targets')} targets in all "
                        f"(each set's targets x count x seeds.count, summed), got {targets}")
    if spec["kind"] == "live":
        for i, s in enumerate(spec["sets"]):
            # gen places every target and every new or moved target on a free cell
            cells = (s.get("max_coord", 20) + 1) ** 2
            need = s["targets"] + s.get("events", DEFAULT_EVENTS) + 1
            if cells < need:
                raise SpecError(f"sets[{i}].max_coord: kind live needs (max_coord + 1)^2 >= targets + events + 1 "
                                f"({need}) free cells, got {cells}")


def validate(doc: Any) -> dict[str, Any]:
    """The spec with defaults filled in; raises SpecError with the first error."""
    bad = _first_not_finite(doc)
    if bad is not None:
        raise SpecError(f"{field_path('spec', list(bad[0]))}: must be a finite number, got {shown_value(bad[1])}")
    errs = sorted(_Validator(schema()).iter_errors(doc),
                  key=lambda e: [str(p) for p in e.absolute_path])
    if errs:
        raise SpecError(_message(errs[0]))
    if not _NAME.fullmatch(doc["name"]):
        raise SpecError(f"name: {schema()['properties']['name']['x-sva-pattern-rule']}, got {shown_value(doc['name'])}")
    for i, s in enumerate(doc["sets"]):
        if "label" in s and not _LABEL.fullmatch(s["label"]):
            raise SpecError(f"sets[{i}].label: must match ^[A-Za-z0-9_.-]{{1,32}}$, got {shown_value(s['label'])}")
    spec: dict[str, Any] = json.loads(json.dumps(doc))
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
            raise SpecError(f"sets[{i}].label: must be unique (give one of them a distinct label), got "
                            f"{shown_value(label)} again (sets[{labels.index(label)}]'s)")
    spec.setdefault("count", 1)
    spec.setdefault("seeds", {"first": 1})
    spec["seeds"].setdefault("count", 1)
    ref = spec.get("ref", False)
    spec["ref"] = dict(DEFAULT_REF, **ref) if isinstance(ref, dict) else (dict(DEFAULT_REF) if ref else None)
    if spec["kind"] == "live":
        spec.setdefault("penalties", [0])
    _totals(spec)
    return spec


class _Refused(Exception):
    """A breach the loader finds: (path parts, rule, what it got)."""


def _mark(mark: Any) -> str:
    # a PyYAML Mark, of the Python or the C loader; the stubs allow None where the
    # composer always sets one
    return f"line {mark.line + 1}, column {mark.column + 1}"


# Tags a spec may hold: JSON's types (PyYAML resolves a plain scalar to one of these or
# to a timestamp; explicit tags name anything).
_SCALAR_TAGS = {f"tag:yaml.org,2002:{t}" for t in ("str", "int", "float", "bool", "null")}
_COLLECTION_TAGS = {"tag:yaml.org,2002:seq", "tag:yaml.org,2002:map"}


def _loader_class() -> type[SafeLoader]:
    import yaml
    from yaml.events import AliasEvent, CollectionStartEvent
    from yaml.nodes import ScalarNode

    class SpecLoader(yaml.SafeLoader):
        """PyYAML's safe loader; its composer refuses, at the first offence in document
        order, what a spec never needs and what makes loading costly: anchors and
        aliases (a billion laughs composes a few nodes and constructs exponentially
        many), deep nesting (the composer and constructor recurse), too many nodes,
        long scalars (Python's int() of a long digit string), duplicate keys, keys that
        are not strings, tags beyond JSON's types."""

        def __init__(self, text: str):
            super().__init__(text)
            self.where: list[Any] = []
            self.depth = 0
            self.nodes = 0
            self.keys: dict[int, dict[str, Any]] = {}

        def refuse(self, rule: str, got: str, parts: list[Any] | None = None) -> NoReturn:
            raise _Refused(list(self.where) if parts is None else parts, rule, got)

        # index: a sequence item's position, a mapping value's key node, None for a key
        def compose_node(self, parent: Node | None, index: Any) -> Node:
            event = self.peek_event()  # type: ignore[no-untyped-call]  # Parser.peek_event has no hints in its stubs
            is_key = parent is not None and index is None
            pushed = parent is not None and not is_key
            if pushed:
                self.where.append(index if isinstance(index, int) else index.value)
            if isinstance(event, AliasEvent):
                self.refuse("YAML aliases are not allowed", f"*{event.anchor} at {_mark(event.start_mark)}")
            if event.anchor is not None:
                self.refuse("YAML anchors are not allowed", f"&{event.anchor} at {_mark(event.start_mark)}")
            self.nodes += 1
            if self.nodes > limit("nodes"):
                self.refuse(f"must have at most {limit('nodes')} YAML nodes (x-sva-max-nodes)",
                            f"more at {_mark(event.start_mark)}", parts=[])
            if isinstance(event, CollectionStartEvent):
                self.depth += 1
                if self.depth > limit("depth"):
                    self.refuse(f"must be nested at most {limit('depth')} deep (x-sva-max-depth)",
                                f"deeper at {_mark(event.start_mark)}")
            # PyYAML's composer returns a node here; its stubs say Node | None
            node = cast("Node", super().compose_node(parent, index))
            if isinstance(event, CollectionStartEvent):
                self.depth -= 1
                self.keys.pop(id(node), None)
            self.check(node, parent, is_key)
            if pushed:
                self.where.pop()
            return node

        def check(self, node: Node, parent: Node | None, is_key: bool) -> None:
            if node.tag == "tag:yaml.org,2002:merge":
                self.refuse("YAML merge keys are not allowed", f"<< at {_mark(node.start_mark)}")
            if isinstance(node, ScalarNode):
                if len(node.value) > limit("scalar-chars"):
                    self.refuse(f"must be at most {limit('scalar-chars')} characters (x-sva-max-scalar-chars)",
                                f"{len(node.value)} at {_mark(node.start_mark)}")
                if node.tag not in _SCALAR_TAGS:
                    kind = node.tag.rsplit(":", 1)[-1] if node.tag.startswith("tag:yaml.org,2002:") else node.tag
                    self.refuse("must be a string, number, boolean or null (quote a string that looks like "
                                "another YAML type)", f"YAML type {kind} at {_mark(node.start_mark)}")
                try:  # an explicit tag on a scalar that is not one (`!!int abc`, `!!bool maybe`)
                    self.construct_object(node)
                except (ValueError, KeyError, TypeError, yaml.YAMLError):
                    kind = node.tag.rsplit(":", 1)[-1]
                    self.refuse(f"must be a YAML {kind}", f"{shown_value(node.value)} at {_mark(node.start_mark)}")
            elif node.tag not in _COLLECTION_TAGS:
                self.refuse("must be a list or a mapping", f"YAML type {node.tag} at {_mark(node.start_mark)}")
            if not is_key:
                return
            if not (isinstance(node, ScalarNode) and node.tag == "tag:yaml.org,2002:str"):
                got = "a list or mapping"
                if isinstance(node, ScalarNode):
                    got = node.value[:48] + "..." * (len(node.value) > 48)
                self.refuse("keys must be strings", f"{got} at {_mark(node.start_mark)}")
            seen = self.keys.setdefault(id(parent), {})
            if node.value in seen:
                self.refuse("keys must be unique", f"{shown_value(node.value)} again at {_mark(node.start_mark)} "
                            f"(first at {_mark(seen[node.value])})", parts=list(self.where) + [node.value])
            seen[node.value] = node.start_mark

    return SpecLoader


def parse(data: bytes, size: int | None = None) -> Any:
    """A spec document from the file's bytes (size: the file's, when more than data
    holds); SpecError names the first breach of the loader's limits and rules."""
    import yaml
    size = max(len(data), size or 0)
    if size > limit("bytes"):
        raise SpecError(f"spec: must be at most {limit('bytes')} bytes (x-sva-max-bytes), got {size}")
    try:
        text = data.decode("utf-8")
    except UnicodeDecodeError as e:
        line = data.count(b"\n", 0, e.start) + 1
        column = e.start - (data.rfind(b"\n", 0, e.start) + 1) + 1
        raise SpecError(f"spec: must be UTF-8 text, got byte 0x{data[e.start]:02x} at line {line}, column {column}") \
            from None
    loader: SafeLoader | None = None
    try:
        loader = _loader_class()(text)  # the reader refuses unprintable characters here
        node = loader.get_single_node()
        doc = None if node is None else loader.construct_document(node)
    except _Refused as e:
        parts, rule, got = e.args
        raise SpecError(f"{field_path('spec', parts)}: {rule}, got {got}") from None
    except yaml.reader.ReaderError as e:
        line = text.count("\n", 0, e.position) + 1
        column = e.position - (text.rfind("\n", 0, e.position) + 1) + 1
        char = e.character if isinstance(e.character, int) else ord(e.character)
        raise SpecError(f"spec: must be printable text, got character U+{char:04X} at line {line}, column {column}") \
            from None
    except yaml.YAMLError as e:
        mark = getattr(e, "problem_mark", None)
        where = f" at {_mark(mark)}" if mark else ""
        problem = getattr(e, "problem", None) or str(e).splitlines()[0]
        raise SpecError(f"spec: must be YAML, got {problem}{where}") from None
    finally:
        if loader is not None:
            loader.dispose()
    return doc


def load(path: str) -> dict[str, Any]:
    try:
        with open(path, "rb") as f:
            data = f.read(limit("bytes") + 1)  # never more: a pipe or a device has no size
            size = os.fstat(f.fileno()).st_size
    except OSError as e:
        raise SpecError(f"cannot read: {e.strerror}") from None
    doc = parse(data, size)
    if not isinstance(doc, dict):
        raise SpecError(f"spec: must be a mapping, got {json_type(doc)}")
    return validate(doc)


def _range(v: Any, default: tuple[int, int]) -> tuple[int, int]:
    if v is None:
        return default
    return (v, v) if isinstance(v, int) else (v[0], v[1])


def gen_kwargs(s: dict[str, Any]) -> dict[str, Any]:
    kw = {"width": _range(s.get("width"), (20, 40)), "need": _range(s.get("need"), (2, 2))}
    for k in ("ratio", "max_coord", "fuel", "hover", "ticks_per_cell", "overlap_percent"):
        if k in s:
            kw[k] = s[k]
    return kw


def missions(spec: dict[str, Any]) -> int:
    """Missions (kind plan) or scenarios (kind live) the spec names."""
    n: int = sum(s.get("count", spec["count"]) for s in spec["sets"]) * spec["seeds"]["count"]
    return n


def set_label(s: dict[str, Any]) -> str:
    return s.get("label") or f"{s['targets']}x{s['uavs']}"


def _base(spec: dict[str, Any], run: str, s: dict[str, Any], seed: int, index: int) -> dict[str, Any]:
    return {"campaign": spec["name"], "run": run, "set": set_label(s), "targets": s["targets"],
            "uavs": s["uavs"], "seed": seed, "index": index, "penalty": None}


def _task(base: dict[str, Any], task: str, tool: str, mission_doc: dict[str, Any], settings: dict[str, Any],
          penalty: int | None = None, coverable: int | None = None) -> dict[str, Any]:
    version = tasks.tool_version(task)
    mh = tasks.mission_hash(mission_doc)
    key_settings = dict(settings, penalty=penalty) if task == "fly" else settings
    t = dict(base, task=task, tool=tool, settings=settings, version=version, mission_hash=mh,
             mission_name=(mission_doc.get("mission") or mission_doc).get("name"),
             mission=tasks.canonical(mission_doc), coverable=coverable,
             key=tasks.task_key(task, tool, mh, key_settings, version))
    if penalty is not None:
        t["penalty"] = penalty
    return t


def plan_settings(spec: dict[str, Any]) -> dict[str, Any]:
    return {k: spec[k] for k in ("flow_work", "repeat") if k in spec}


def ref_settings(spec: dict[str, Any]) -> dict[str, Any]:
    return {"det_limit": float(spec["ref"]["det_limit"]), "time_limit": float(spec["ref"]["time_limit"])}


def _generated(n: int, seed: int, index: int, make: Callable[[], _T]) -> _T:
    """make()'s mission; SpecError when gen cannot make one from the set's settings (a
    grid too small for a live scenario's new cells, a ratio it cannot hit)."""
    from .. import io
    try:
        return make()
    except (ValueError, RuntimeError, io.InputError) as e:
        raise SpecError(f"sets[{n}]: must be settings gen can make missions from, got for seed {seed}, "
                        f"mission {index}: {e}") from None


def first_tasks(spec: dict[str, Any], run: str) -> list[dict[str, Any]]:
    """Every task the spec names before any result is known: for kind plan, each
    mission's planner and ref tasks; for kind live, each scenario's flights (their
    replans' ref tasks follow from the flight logs: ref_tasks)."""
    out: list[dict[str, Any]] = []
    seeds = range(spec["seeds"]["first"], spec["seeds"]["first"] + spec["seeds"]["count"])
    for n, s in enumerate(spec["sets"]):
        kw = gen_kwargs(s)
        for seed in seeds:
            for i in range(s.get("count", spec["count"])):
                base = _base(spec, run, s, seed, i)
                if spec["kind"] == "plan":
                    doc = _generated(n, seed, i, functools.partial(gen.generate, s["targets"], s["uavs"],
                                                                   seed=seed, index=i, **kw)).to_json()
                    settings = plan_settings(spec)
                    for algo in spec["algorithms"]:
                        out.append(_task(base, "plan", algo, doc, settings if algo == "flow" else {},
                                         coverable=s["targets"]))
                    if spec["ref"] and s["targets"] <= spec["ref"]["max_targets"]:
                        out.append(_task(base, "ref", "ref", doc, ref_settings(spec), coverable=s["targets"]))
                else:
                    doc = _generated(n, seed, i, functools.partial(
                        gen.generate_scenario, s["targets"], s["uavs"], s.get("events", DEFAULT_EVENTS),
                        seed=seed, index=i, name=f"live_{i:04d}", **kw))
                    for algo in spec["algorithms"]:
                        for pen in spec["penalties"]:
                            out.append(_task(base, "fly", algo, doc, {}, penalty=pen))
    return out


def ref_tasks(spec: dict[str, Any], run: str, flights: list[dict[str, Any]],
              logs: dict[str, dict[str, Any]]) -> list[dict[str, Any]]:
    """ref on the residual missions (with a target) of the replans of each set's first
    ref_count scenarios (default: all) per seed, once per distinct residual mission."""
    if not spec["ref"]:
        return []
    by_set = {set_label(s): s for s in spec["sets"]}
    out: list[dict[str, Any]] = []
    seen: set[str] = set()
    for f in flights:
        s = by_set[f["set"]]
        if f["index"] >= s.get("ref_count", s.get("count", spec["count"])) or f["key"] not in logs:
            continue
        for doc in tasks.residuals(logs[f["key"]]):
            if len(doc["targets"]) > spec["ref"]["max_targets"]:
                continue
            t = _task(_base(spec, run, s, f["seed"], f["index"]), "ref", "ref", doc, ref_settings(spec),
                      coverable=len(doc["targets"]))
            if t["key"] not in seen:
                seen.add(t["key"])
                out.append(t)
    return out
