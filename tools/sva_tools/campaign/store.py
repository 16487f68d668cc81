"""The campaign's result store: Parquet files under OUT/results/ (docs/campaigns.md).

Each flush writes one file results/part-<run>-<seq>.parquet (a temporary file renamed
into place, so a file is whole or absent) with a CRC per page; rows are never rewritten.
A row's key is its task's key (tasks.task_key: mission content hash, tool, settings, tool
version); when the same key is stored twice (two clients on one folder), reading keeps
the first.

A part file is bytes on disk that a full disk, a copy or a hand can damage. A part that
cannot be read whole (empty, truncated, not Parquet, a page whose CRC fails) or that has
another schema is damaged: it is recorded in `damaged` with the reason, reported once
through `on_damaged`, and skipped by every read; `set_aside()` moves the damaged parts
to OUT/damaged/ so that their tasks, no longer stored, run again.
"""
from __future__ import annotations

import os
import time
from collections.abc import Iterable
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from typing import Any, Callable

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


class Damaged(Exception):
    """Why a part file cannot be used (str: the reason, one line)."""


def _schema_error(found: pa.Schema) -> str | None:
    """Why a part's schema is not the store's, else None."""
    for field in SCHEMA:
        i = found.get_field_index(field.name)
        if i < 0:
            return f'foreign schema: no column "{field.name}"'
        if found.field(i).type != field.type:
            return f'foreign schema: column "{field.name}" is {found.field(i).type}, not {field.type}'
    return None


def read_part(path: Path, schema: pa.Schema, check_schema: bool = True) -> pa.Table:
    """The given columns of one part file; Damaged when it cannot be read whole or (when
    check_schema) its schema is not the store's."""
    try:
        if path.stat().st_size == 0:
            raise Damaged("empty file")
        # ParquetFile: a third of read_table's cost on a small part file
        f = pq.ParquetFile(path, page_checksum_verification=True)
        why = _schema_error(f.schema_arrow) if check_schema else None
        if why:
            raise Damaged(why)
        t = f.read(columns=schema.names, use_threads=False)
        if t.num_rows != f.metadata.num_rows:
            raise Damaged(f"{t.num_rows} rows read of {f.metadata.num_rows}")
        return t.cast(schema)
    except (OSError, ValueError, pa.ArrowException) as e:
        text = " ".join(str(e).split()) or type(e).__name__
        raise Damaged(f"unreadable: {text[:120]}") from None


class Store:
    def __init__(self, out: str, run: str, flush_rows: int = 64, flush_s: float = 2.0,
                 on_damaged: Callable[[Path, str], None] | None = None):
        self.dir = Path(out) / "results"
        self.dir.mkdir(parents=True, exist_ok=True)
        self.run = run
        self.flush_rows, self.flush_s = flush_rows, flush_s
        self.pending: list[dict[str, Any]] = []
        self.seq = 0
        self.last = time.monotonic()
        self.written = 0
        self.damaged: dict[Path, str] = {}  # part file -> reason, in the order found
        self.on_damaged = on_damaged
        self.schema_ok: set[Path] = set()  # part files whose schema was checked (a fifth of a read's cost)

    def files(self) -> list[Path]:
        """The part files, damaged ones included, in name order."""
        return sorted(self.dir.glob("part-*.parquet"))

    def table(self, columns: list[str] | None = None) -> pa.Table:
        """Every stored row (the first of each key), files in name order; a damaged
        file is recorded, reported once and skipped."""
        schema = SCHEMA if columns is None else pa.schema([SCHEMA.field(c) for c in columns])

        def read(path: Path) -> tuple[pa.Table | None, str]:
            try:
                t = read_part(path, schema, path not in self.schema_ok)
                self.schema_ok.add(path)
                return t, ""
            except Damaged as e:
                return None, str(e)

        files = [p for p in self.files() if p not in self.damaged]
        with ThreadPoolExecutor(max_workers=min(4, os.cpu_count() or 1)) as pool:
            read_parts = list(pool.map(read, files))  # in file order
        parts = []
        for path, (t, why) in zip(files, read_parts):
            if t is None:
                self.damaged[path] = why
                if self.on_damaged is not None:
                    self.on_damaged(path, why)
            else:
                parts.append(t)
        if not parts:
            return schema.empty_table()
        t = pa.concat_tables(parts)
        if "key" not in t.column_names or pc.count_distinct(t["key"]).as_py() == len(t):
            return t
        # the first row of each key, in file order
        first = pa.table({"key": t["key"], "i": pa.array(np.arange(len(t), dtype=np.int64))}).group_by(
            "key", use_threads=False).aggregate([("i", "min")])["i_min"]
        return t.take(first.take(pc.sort_indices(first)))

    def set_aside(self) -> list[tuple[Path, Path]]:
        """Moves the damaged part files to OUT/damaged/ (kept for a look, out of every
        read); returns (from, to) of each. Their tasks are no longer stored: the next
        submission computes them again."""
        dest = self.dir.parent / "damaged"
        dest.mkdir(exist_ok=True)
        moved = []
        for path in list(self.damaged):
            target, n = dest / path.name, 1
            while target.exists():
                target, n = dest / f"{path.name}.{n}", n + 1
            os.replace(path, target)
            moved.append((path, target))
            del self.damaged[path]
        return moved

    def keys(self) -> set[str]:
        return set(self.table(["key"]).column("key").to_pylist())

    def rows(self, keys: Iterable[str] | None = None,
             columns: list[str] | None = None) -> dict[str, dict[str, Any]]:
        """key -> row (only the given columns, key always included)."""
        t = self.table(None if columns is None else ["key"] + [c for c in columns if c != "key"])
        wanted = set(keys) if keys is not None else None
        return {r["key"]: r for r in t.to_pylist() if wanted is None or r["key"] in wanted}

    def add(self, row: dict[str, Any]) -> None:
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
        pq.write_table(table, tmp, compression="zstd", write_page_checksum=True)
        os.replace(tmp, self.dir / name)
        self.seq += 1
        self.written += len(self.pending)
        self.pending = []
