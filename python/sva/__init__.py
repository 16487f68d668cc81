"""sva: the on-board mission planner's C core from Python (docs/python.md).

    import sva
    plan = sva.plan(mission, algo="flow")   # mission: a dict in SPEC section 3's format

`plan` returns the plan as a dict, exactly what `sva plan --algo ALGO` prints, parsed;
`replan` does the same for `sva replan`'s live file (SPEC section 12.5). A mission the
core rejects raises MissionError with the message `sva` prints after "sva: error: ".
"""
from __future__ import annotations

import json
import os
import tempfile
from collections.abc import Mapping
from typing import Any, Union

from . import _native

__all__ = [
    "ALGORITHMS",
    "Error",
    "MissionError",
    "PlanError",
    "core_version",
    "plan",
    "plan_text",
    "replan",
    "replan_text",
]

__version__ = "0.4.0"

#: The core's algorithms (SPEC section 2), as `--algo` names them.
ALGORITHMS: tuple[str, ...] = ("sva", "ga", "hga", "bfa", "flow")

Document = Union[Mapping[str, Any], str, bytes]


class Error(Exception):
    """A mission or live file the planner did not plan; str(error) is the CLI's message."""

    def __init__(self, message: str) -> None:
        super().__init__(message)
        self.message = message


class MissionError(Error, ValueError):
    """Bad input (the CLI's exit 2): the document breaks a rule of SPEC sections 3, 4 or 12.

    `message` is exactly what `sva` prints after "sva: error: ", e.g.
    ``targets[1].need: must be >= 1, got 0``.
    """


class PlanError(Error):
    """The planner failed on a valid mission (the CLI's exit 1), e.g. past bfa's limits:
    ``targets: 25 entries exceed SVA_BFA_MAX_TARGETS (12)``."""


def _document(doc: Document) -> bytes:
    if isinstance(doc, bytes):
        return doc
    if isinstance(doc, str):
        return doc.encode("utf-8")
    # allow_nan=False: JSON has no NaN or infinity (SPEC section 3)
    return json.dumps(doc, ensure_ascii=False, allow_nan=False).encode("utf-8")


def _result(code: int, text: str) -> str:
    if code == _native.OK:
        return text
    if code == _native.BAD_INPUT:
        raise MissionError(text)
    if code == _native.BAD_ARGUMENT:
        raise ValueError(text)
    raise PlanError(text)


def _budget(flow_work: int | None) -> int:
    if flow_work is None:
        return 0
    if isinstance(flow_work, bool) or not isinstance(flow_work, int):
        raise TypeError(f"flow_work: must be an integer, got {type(flow_work).__name__}")
    # 0 means "the default budget" to the C side; the C side checks the range
    return flow_work if flow_work != 0 else -1


def plan_text(mission: Document, algo: str = "sva", *, flow_work: int | None = None,
              source: str = "<mission>") -> str:
    """The plan JSON text, byte for byte what `sva plan --algo ALGO` prints for the same
    document (`stats.solve_us` aside, a time). `mission` is a dict, or JSON text; `source`
    names the document in errors of the document itself (invalid JSON, empty)."""
    return _result(*_native.plan(_document(mission), source, algo, _budget(flow_work)))


def plan(mission: Document, algo: str = "sva", *, flow_work: int | None = None) -> dict[str, Any]:
    """Plans `mission` (SPEC section 3) with `algo` and returns the plan as a dict.

    Raises MissionError on a rejected mission, PlanError when the planner fails
    (an algorithm's limit), ValueError on an unknown algorithm or a flow_work out of
    [1000, SVA_FLOW_MAX_WORK]."""
    result: dict[str, Any] = json.loads(plan_text(mission, algo, flow_work=flow_work))
    return result


def replan_text(live: Document, algo: str = "sva", *, flow_work: int | None = None,
                source: str = "<live>") -> str:
    """The last replan of the live document `live` (SPEC section 12.5) as JSON text, as
    `sva replan --algo ALGO` prints it; `source` names the document in errors, as the
    file name does for the CLI."""
    data = _document(live)
    # The JSON layer reads live files from a path: a private temporary file, named in
    # errors by `source`.
    handle, path = tempfile.mkstemp(prefix="sva-live-", suffix=".json")
    try:
        with os.fdopen(handle, "wb") as file:
            file.write(data)
        code, text = _native.replan(path, algo, _budget(flow_work))
        return _result(code, text if code == _native.OK else text.replace(path, source))
    finally:
        os.unlink(path)


def replan(live: Document, algo: str = "sva", *, flow_work: int | None = None,
           source: str = "<live>") -> dict[str, Any]:
    """Replays the live mission `live` (mission, plan in force, events, now; SPEC section
    12.5) as `sva replan` does and returns its last replan as a dict. Errors as plan()."""
    text = replan_text(live, algo, flow_work=flow_work, source=source)
    result: dict[str, Any] = json.loads(text)
    return result


def core_version() -> str:
    """MAJOR.MINOR.PATCH of the C core inside this package."""
    return _native.core_version()
