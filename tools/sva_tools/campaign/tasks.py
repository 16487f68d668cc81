"""One campaign task, run on a Dask worker (or directly): plan a mission with a C
planner (`sva plan`), solve it with the exact reference (`ref`), or fly a live
scenario (`sva-tools sim`). A task is a plain dict built by the client
(sva_tools.campaign.spec); its result is one row of the campaign's Parquet store
(ROW_FIELDS).

A task carries the tool version the client keyed it with; the worker computes its own
and refuses the task when they differ (a worker on another build of the C CLI or of
the tools would store a result under the wrong key).
"""
from __future__ import annotations

import hashlib
import json
import os
import socket
import time
from collections.abc import Iterable
from pathlib import Path
from typing import Any

from .. import __version__

_PKG = Path(__file__).resolve().parents[1]
_hashes: dict[str, str] = {}

# Columns of a stored row, in order (docs/campaigns.md, "Parquet layout").
ROW_FIELDS = ("key", "campaign", "run", "task", "tool", "set", "targets", "uavs", "seed", "index",
              "penalty", "mission_hash", "mission_name", "version", "settings", "mission", "result",
              "covered", "coverable", "cost", "optimal", "solve_us", "replan_us", "wall_s",
              "worker", "host", "pid", "utc", "error")


def canonical(doc: Any) -> str:
    return json.dumps(doc, sort_keys=True, separators=(",", ":"), ensure_ascii=True)


def sha256(text: str) -> str:
    return hashlib.sha256(text.encode("utf-8")).hexdigest()


def _file_hash(path: Path) -> str:
    key = str(path)
    if key not in _hashes:
        _hashes[key] = hashlib.sha256(path.read_bytes()).hexdigest()
    return _hashes[key]


def _sources_hash(names: Iterable[str]) -> str:
    h = hashlib.sha256()
    for name in names:
        h.update(name.encode("utf-8") + b"\0")
        h.update((_PKG / name).read_bytes())
    return h.hexdigest()


def tool_version(task: str) -> dict[str, Any]:
    """The version a task's result depends on: sva_tools' version, and for `plan` the
    C CLI binary's SHA-256, for `ref` ref's sources and OR-tools (cache.version), for
    `fly` the simulator's sources and the C CLI binary."""
    from .. import cbin
    if task == "ref":
        from .. import cache
        return dict(cache.version("ref"))
    out = {"sva_tools": __version__, "sva": _file_hash(cbin.sva_bin())}
    if task == "fly":
        out["sim"] = _sources_hash(("sim.py", "model.py", "io.py", "cbin.py"))
    return out


def task_key(task: str, tool: str, mission_hash: str, settings: dict[str, Any], version: dict[str, Any]) -> str:
    return sha256(canonical({"task": task, "tool": tool, "mission": mission_hash,
                             "settings": settings, "version": version}))


def _plan_figures(plan: dict[str, Any]) -> dict[str, Any]:
    stats = plan.get("stats") or {}
    return {"covered": plan.get("covered"), "cost": plan.get("cost"),
            "optimal": bool(stats.get("optimal")) if "optimal" in stats else None,
            "solve_us": stats.get("solve_us")}


def _run_plan(task: dict[str, Any]) -> dict[str, Any]:
    import subprocess
    import tempfile

    from .. import cbin
    s = task["settings"]
    cmd = [str(cbin.sva_bin()), "plan", "--algo", task["tool"]]
    if s.get("flow_work") is not None:
        cmd += ["--flow-work", str(s["flow_work"])]
    if s.get("repeat") is not None:
        cmd += ["--repeat", str(s["repeat"])]
    with tempfile.TemporaryDirectory(prefix="sva-campaign-") as d:
        path = os.path.join(d, "mission.json")
        with open(path, "w", encoding="utf-8") as f:
            f.write(task["mission"])
        r = subprocess.run(cmd + [path], capture_output=True, text=True, timeout=s.get("timeout", 600))
    if r.returncode != 0:
        lines = [ln for ln in r.stderr.splitlines() if ln.strip()]
        return {"error": f"sva plan exit {r.returncode}: {lines[-1] if lines else ''}"}
    plan = json.loads(r.stdout)
    return dict(_plan_figures(plan), result=canonical(plan))


def _run_ref(task: dict[str, Any]) -> dict[str, Any]:
    from .. import io
    from ..ref import solve_ref
    s = task["settings"]
    m = io.mission_from_json(json.loads(task["mission"]))
    plan = solve_ref(m, s["time_limit"], 1, s["det_limit"]).to_json()
    return dict(_plan_figures(plan), result=canonical(plan))


def _run_fly(task: dict[str, Any]) -> dict[str, Any]:
    from .. import sim
    doc = json.loads(task["mission"])
    m, events, _ = sim.parse_scenario(doc)
    log = sim.simulate(m, events, task["penalty"], task["tool"])
    times = [r["solve_us"] for r in log["replans"] if r["solve_us"] is not None]
    return {"covered": log["summary"]["covered"], "coverable": log["summary"]["coverable"],
            "cost": None, "optimal": None, "solve_us": None, "replan_us": times,
            "result": canonical(log)}


RUNNERS = {"plan": _run_plan, "ref": _run_ref, "fly": _run_fly}


def run_task(task: dict[str, Any]) -> dict[str, Any]:
    """Runs one task and returns its stored row. Raises RuntimeError when this worker's
    tool version differs from the task's (the result must not be stored)."""
    mine = tool_version(task["task"])
    if mine != task["version"]:
        raise RuntimeError(f"task {task['key'][:12]} ({task['task']} {task['tool']}): this worker's "
                           f"version {canonical(mine)} differs from the client's {canonical(task['version'])}; "
                           "run the workers from the same build as the client")
    t0 = time.perf_counter()
    try:
        out = RUNNERS[task["task"]](task)
    except Exception as e:  # a tool's own failure is a result (deterministic): stored
        out = {"error": f"{type(e).__name__}: {e}"}
    wall = time.perf_counter() - t0
    worker = ""
    try:
        from distributed import get_worker
        worker = get_worker().address
    except (ImportError, ValueError):
        worker = "direct"
    row: dict[str, Any] = {k: None for k in ROW_FIELDS}
    row.update({k: task.get(k) for k in ("key", "campaign", "run", "task", "tool", "set", "targets",
                                        "uavs", "seed", "index", "penalty", "mission_hash",
                                        "mission_name", "mission")})
    row.update({"version": canonical(task["version"]), "settings": canonical(task["settings"]),
                "coverable": task.get("coverable")})
    row.update(out)
    row.update({"wall_s": wall, "worker": worker, "host": socket.gethostname(), "pid": os.getpid(),
                "utc": time.strftime("%Y-%m-%dT%H:%M:%SZ", time.gmtime())})
    return row


def mission_hash(doc: dict[str, Any]) -> str:
    return sha256(canonical(doc))


def residual_for_ref(mission: dict[str, Any]) -> dict[str, Any]:
    """A live replan's residual mission as ref solves it: without change_penalty, named by
    its content, so equal residuals of different flights are one task."""
    doc = {k: v for k, v in mission.items() if k not in ("change_penalty", "name")}
    doc["name"] = "residual_" + sha256(canonical(doc))[:16]
    return doc


def residuals(log: dict[str, Any]) -> list[dict[str, Any]]:
    """The residual missions of a flight log's replans that have a target."""
    return [residual_for_ref(r["mission"]) for r in log["replans"] if r["mission"]["targets"]]
