"""Running the C planner CLI (`sva plan`), found through $SVA_BIN or <repo>/build/bin/sva."""
from __future__ import annotations

import json
import os
import subprocess
import tempfile
from dataclasses import dataclass
from pathlib import Path
from typing import Any

from . import io, model

C_ALGORITHMS = ("sva", "ga", "hga", "bfa", "flow")
REPO = Path(__file__).resolve().parents[2]


class CliMissing(RuntimeError):
    pass


def sva_bin() -> Path:
    env = os.environ.get("SVA_BIN")
    p = Path(env) if env else REPO / "build" / "bin" / "sva"
    if not (p.is_file() and os.access(p, os.X_OK)):
        raise CliMissing(f"the C CLI is missing: {p} is not an executable file "
                         f"(build it with scripts/build.sh, or point SVA_BIN at it)")
    return p


@dataclass
class CResult:
    status: int               # exit status of `sva plan`
    plan: model.Plan | None    # when status is 0
    raw: dict[str, Any] | None
    stderr: str
    trace: list[dict[str, Any]] | None = None


def plan(mission_path: str, algo: str, trace: bool = False, timeout: float = 600) -> CResult:
    """`sva plan --algo ALGO MISSION` (with --trace FILE when trace is set)."""
    cmd = [str(sva_bin()), "plan", "--algo", algo]
    tdir = None
    tfile = None
    if trace:
        tdir = tempfile.TemporaryDirectory(prefix="sva-trace-")
        tfile = os.path.join(tdir.name, "trace.jsonl")
        cmd += ["--trace", tfile]
    cmd.append(str(mission_path))
    try:
        r = subprocess.run(cmd, capture_output=True, text=True, timeout=timeout)
        if r.returncode != 0:
            return CResult(r.returncode, None, None, r.stderr)
        raw = json.loads(r.stdout)
        p = io.plan_from_json(raw)
        recs = None
        if tfile is not None:
            recs = []
            if os.path.exists(tfile):
                recs = io.load_trace(tfile)
        return CResult(0, p, raw, r.stderr, recs)
    finally:
        if tdir is not None:
            tdir.cleanup()


_PROBE_MISSION = {"name": "probe", "depot": {"x": 0, "y": 0},
                  "uavs": [{"id": 1, "x": 0, "y": 0, "fuel": 10}],
                  "targets": [{"id": 1, "x": 1, "y": 1, "start": 5, "end": 6, "need": 1}]}
_known: dict[str, str | None] = {}


def algorithm_available(algo: str) -> str | None:
    """None when `sva plan --algo ALGO` plans (a one-target probe mission), else the
    CLI's answer (e.g. an algorithm this build of the C CLI does not know yet)."""
    if algo not in _known:
        with tempfile.TemporaryDirectory(prefix="sva-probe-") as d:
            path = os.path.join(d, "probe.json")
            io.write_json(_PROBE_MISSION, path)
            r = plan(path, algo, timeout=60)
        lines = r.stderr.strip().splitlines()
        _known[algo] = None if r.status == 0 else (
            f"`sva plan --algo {algo}` exit {r.status}: {lines[-1] if lines else ''}")
    return _known[algo]


def plan_mission(m: model.Mission, algo: str, trace: bool = False, timeout: float = 600) -> CResult:
    with tempfile.TemporaryDirectory(prefix="sva-m-") as d:
        path = os.path.join(d, "mission.json")
        io.write_json(m.to_json(), path)
        return plan(path, algo, trace=trace, timeout=timeout)
