"""Regression campaigns on a Dask cluster: tasks, their stored results, metrics and the
report (`sva-tools campaign`, docs/campaigns.md)."""
from __future__ import annotations

import datetime
import json
import os
import sys
import time
import uuid
from pathlib import Path
from typing import TYPE_CHECKING, Any, Callable

if TYPE_CHECKING:
    from distributed import Client

    from .store import Store

# The Dask, Parquet and schema modules are imported when a campaign runs, not when the
# `sva-tools` parser is built for another subcommand.

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__)))))


def new_run_id() -> str:
    now = datetime.datetime.now(datetime.timezone.utc)
    return now.strftime("%Y%m%dT%H%M%S") + "-" + uuid.uuid4().hex[:8]


class CampaignError(RuntimeError):
    pass


class _Cluster:
    """The Dask client, connected (and the LocalCluster started) only when a task is to
    be submitted: a campaign whose results are all stored starts no cluster."""

    def __init__(self, scheduler: str | None, workers: int | None, client: Client | None = None) -> None:
        self.scheduler, self.workers = scheduler, workers
        self.client: Any = client  # a distributed.Client: few of its methods have type hints
        self.cluster: Any = None  # the LocalCluster this run starts, if any
        self.own = client is None

    def get(self) -> Any:
        if self.client is None:
            from distributed import Client, LocalCluster
            if self.scheduler:
                try:
                    self.client = Client(self.scheduler, timeout="30s")  # type: ignore[no-untyped-call]  # distributed: no hints
                except (OSError, TimeoutError) as e:
                    raise CampaignError(f"--scheduler {self.scheduler}: cannot connect within 30 s "
                                        f"({type(e).__name__}: {e})") from None
            else:
                n = self.workers or min(2, os.cpu_count() or 1)
                # On loopback; no dashboard, and the scheduler's HTTP server (health
                # checks) on a free port rather than 8787, which may be taken.
                self.cluster = LocalCluster(  # type: ignore[no-untyped-call]  # distributed: no hints
                    n_workers=n, threads_per_worker=1, processes=True, host="127.0.0.1",
                    dashboard_address=None, scheduler_kwargs={"dashboard_address": "127.0.0.1:0"})
                self.client = Client(self.cluster)  # type: ignore[no-untyped-call]  # distributed: no hints
        return self.client

    def n_workers(self) -> int:
        return len(self.client.nthreads()) if self.client is not None else 0

    def close(self) -> None:
        if self.own and self.client is not None:
            self.client.close()
            if self.cluster is not None:
                self.cluster.close()


def _execute(cl: _Cluster, tasks: list[dict[str, Any]], store: Store, stored: set[str], stats: dict[str, Any],
             progress: bool, label: str, compute: bool = True) -> None:
    from distributed import as_completed

    from .tasks import run_task
    new = [t for t in tasks if t["key"] not in stored]
    todo = list({t["key"]: t for t in new}.values())  # a mission two sets share runs once
    stats["tasks"] += len(tasks)
    stats["stored"] += len(tasks) - len(new)
    if not todo:
        return
    if not compute:
        stats["held"] += len(todo)
        return
    client = cl.get()
    stats["workers"] = max(stats["workers"], cl.n_workers())
    t0 = time.perf_counter()
    futures = [client.submit(run_task, t, key=f"sva-{t['task']}-{t['key']}") for t in todo]
    bar = None
    if progress:
        from tqdm import tqdm
        bar = tqdm(total=len(futures), desc=label, unit="task", file=sys.stderr, dynamic_ncols=True)
    try:
        for fut in as_completed(futures):  # type: ignore[no-untyped-call]  # distributed: no hints
            try:
                row = fut.result()
            except Exception as e:  # noqa: BLE001 - a worker's refusal or a lost task: not stored
                stats["failed"].append(f"{fut.key}: {type(e).__name__}: {e}")
            else:
                store.add(row)
                stored.add(row["key"])
                stats["computed"] += 1
            if bar is not None:
                bar.update(1)
            fut.release()
    finally:
        store.flush()
        stats["compute_s"] += time.perf_counter() - t0
        if bar is not None:
            bar.close()


def run(spec: dict[str, Any], out: str, scheduler: str | None = None, workers: int | None = None,
        progress: bool = True, client: Client | None = None, flush_rows: int = 64,
        columns: list[str] | None = None, repair: bool = False,
        on_damaged: Callable[[Path, str], None] | None = None) -> dict[str, Any]:
    """Runs the campaign; returns {"run", "tasks", "stored", "computed", "failed", "wall_s",
    "compute_s" (first submission to last result, cluster start excluded), "workers",
    "held" (tasks not computed because of damaged parts), "set_aside" ((from, to) of the
    damaged parts repair moved), "rows" (key -> stored row, the given columns or all, of
    every task of the spec; absent for columns=[]), "task_list" (this run's tasks),
    "store" (the Store)}.
    A damaged part file is reported through on_damaged(path, reason) and skipped; while
    one is in the folder no task is computed (a task of that part is not told apart from
    a new one), unless repair: then the damaged parts are set aside (Store.set_aside) and
    every task without a readable result is computed. Raises spec.SpecError, before
    anything is written, when gen cannot make the spec's missions."""
    from .spec import first_tasks, ref_tasks
    from .store import Store
    run_id = new_run_id()
    t0 = time.perf_counter()
    first = first_tasks(spec, run_id)
    store = Store(out, run_id, flush_rows=flush_rows, on_damaged=on_damaged)
    stored = store.keys()
    stats: dict[str, Any] = {"run": run_id, "tasks": 0, "stored": 0, "computed": 0, "failed": [], "workers": 0,
                             "compute_s": 0.0, "held": 0, "set_aside": []}
    if repair and store.damaged:
        stats["set_aside"] = store.set_aside()
    compute = not store.damaged
    cl = _Cluster(scheduler, workers, client)
    try:
        _execute(cl, first, store, stored, stats, progress, spec["name"], compute)
        all_tasks = list(first)
        if spec["kind"] == "live":
            flights = [t for t in first if t["task"] == "fly"]
            rows = store.rows(t["key"] for t in flights)
            logs = {k: json.loads(r["result"]) for k, r in rows.items() if r["result"]}
            refs = ref_tasks(spec, run_id, flights, logs)
            _execute(cl, refs, store, stored, stats, progress, spec["name"] + " ref", compute)
            all_tasks += refs
        stats["wall_s"] = time.perf_counter() - t0
    finally:
        cl.close()
    if columns is None or columns:
        stats["rows"] = store.rows((t["key"] for t in all_tasks), columns)
    stats["task_list"] = all_tasks
    stats["store"] = store
    return stats
