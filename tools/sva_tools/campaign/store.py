"""The campaign's result store: Parquet files under OUT/results/ (docs/campaigns.md).

Each flush writes one file results/part-<run>-<seq>.parquet (a temporary file renamed
into place, so a file is whole or absent); rows are never rewritten. A row's key is its
task's key (tasks.task_key: mission content hash, tool, settings, tool version); when
the same key is stored twice (two clients on one folder), reading keeps the first.
"""
from __future__ import annotations

import os
import time
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Dict, Iterable, List, Optional

import numpy as np
import pyarrow as pa
import pyarrow.compute as pc
import pyarrow.parquet as pq

from .tasks import ROW_FIELDS

SCHEMA = pa.schema([
    ("key", pa.string()), ("campaign", pa.string()), ("run", pa.string()), ("task", pa.string()),
    ("tool", pa.string()), ("set", pa.string()), ("targets", pa.int32()), ("uavs", pa.int32()),
    ("seed", pa.int64()), ("index", pa.int32()), ("penalty", pa.int64()),
    ("mission_hash", pa.string()), ("mission_name", pa.string()), ("version", pa.string()),
    ("settings", pa.string()), ("mission", pa.string()), ("result", pa.string()),
    ("covered", pa.int32()), ("coverable", pa.int32()), ("cost", pa.int64()), ("optimal", pa.bool_()),
    ("solve_us", pa.int64()), ("replan_us", pa.list_(pa.int64())), ("wall_s", pa.float64()),
    ("worker", pa.string()), ("host", pa.string()), ("pid", pa.int64()), ("utc", pa.string()),
    ("error", pa.string()),
])
assert tuple(SCHEMA.names) == ROW_FIELDS


class Store:
    def __init__(self, out: str, run: str, flush_rows: int = 64, flush_s: float = 2.0):
        self.dir = Path(out) / "results"
        self.dir.mkdir(parents=True, exist_ok=True)
        self.run = run
        self.flush_rows, self.flush_s = flush_rows, flush_s
        self.pending: List[dict] = []
        self.seq = 0
        self.last = time.monotonic()
        self.written = 0

    def files(self) -> List[Path]:
        return sorted(self.dir.glob("part-*.parquet"))

    def table(self, columns: Optional[List[str]] = None) -> pa.Table:
        """Every stored row (the first of each key), files in name order."""
        schema = SCHEMA if columns is None else pa.schema([SCHEMA.field(c) for c in columns])

        def read(path):  # ParquetFile: a third of read_table's cost on a small part file
            return pq.ParquetFile(path).read(columns=schema.names, use_threads=False).cast(schema)

        with ThreadPoolExecutor(max_workers=min(4, os.cpu_count() or 1)) as pool:
            parts = list(pool.map(read, self.files()))  # in file order
        if not parts:
            return schema.empty_table()
        t = pa.concat_tables(parts)
        if "key" not in t.column_names or pc.count_distinct(t["key"]).as_py() == len(t):
            return t
        # the first row of each key, in file order
        first = pa.table({"key": t["key"], "i": pa.array(np.arange(len(t), dtype=np.int64))}).group_by(
            "key", use_threads=False).aggregate([("i", "min")])["i_min"]
        return t.take(first.take(pc.sort_indices(first)))

    def keys(self) -> set:
        return set(self.table(["key"]).column("key").to_pylist())

    def rows(self, keys: Optional[Iterable[str]] = None, columns: Optional[List[str]] = None) -> Dict[str, dict]:
        """key -> row (only the given columns, key always included)."""
        t = self.table(None if columns is None else ["key"] + [c for c in columns if c != "key"])
        wanted = set(keys) if keys is not None else None
        return {r["key"]: r for r in t.to_pylist() if wanted is None or r["key"] in wanted}

    def add(self, row: dict) -> None:
        self.pending.append(row)
        if len(self.pending) >= self.flush_rows or time.monotonic() - self.last >= self.flush_s:
            self.flush()

    def flush(self) -> None:
        self.last = time.monotonic()
        if not self.pending:
            return
        table = pa.Table.from_pylist(self.pending, schema=SCHEMA)
        name = f"part-{self.run}-{self.seq:06d}.parquet"
        tmp = self.dir / f".tmp-{name}"
        pq.write_table(table, tmp, compression="zstd")
        os.replace(tmp, self.dir / name)
        self.seq += 1
        self.written += len(self.pending)
        self.pending = []
