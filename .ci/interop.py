#!/usr/bin/env python3
"""Notebook interop check for a sweep dataset: polars and pyarrow both read every part file,
the column types are the documented ones, no unflagged NaN, and the footer metadata is there.

    python3 .ci/interop.py outputs/smoke
"""

import math
import sys
from pathlib import Path

import polars as pl
import pyarrow.parquet as pq

dataset = Path(sys.argv[1])
parts = sorted(dataset.glob("part-*.parquet"))
assert parts, f"no part files in {dataset}"
assert all(p.name.startswith("part-") for p in dataset.iterdir()), "dataset holds non-part files"

expect = {
    "case_id": pl.String, "M": pl.Float64, "L": pl.Float64, "H_c": pl.Float64, "H_min": pl.Float64,
    "status": pl.String, "reason": pl.String, "valid": pl.Boolean, "grid": pl.Int64, "wall_s": pl.Float64,
    "contact": pl.String, "D": pl.Float64, "model_used": pl.String, "level": pl.Int64,
    "error_estimate": pl.Float64, "warm_start": pl.String, "half_grid_estimate": pl.Boolean,
    "far_field": pl.Boolean, "H_c_pmax_err": pl.Float64, "H_min_cl": pl.Float64, "H_min_cl_err": pl.Float64,
    "P_max_err": pl.Float64,
}
df = pl.scan_parquet(dataset).collect()  # the directory layout, as a notebook opens it
for col, ty in expect.items():
    assert df.schema[col] == ty, f"{col}: {df.schema[col]} != {ty}"
assert df["case_id"].n_unique() == df.height, "duplicate case ids"
for col, ty in df.schema.items():
    if ty == pl.Float64:
        bad = df.filter(pl.col(col).is_nan() & pl.col("valid"))
        assert bad.height == 0, f"unflagged NaN in {col}"

rows = 0
for p in parts:
    f = pq.ParquetFile(p)
    meta = {k.decode(): v.decode() for k, v in (f.metadata.metadata or {}).items()}
    for key in ("ehlmap_version", "git_commit", "spec", "created", "shard"):
        assert key in meta, f"{p.name}: footer lacks {key}"
    t = f.read()
    rows += t.num_rows
    assert t.schema.field("H_c").type == "double"
assert rows == df.height, f"pyarrow read {rows} rows, polars {df.height}"

conv = df.filter(pl.col("status") == "converged")
assert conv.height > 0 and all(h > 0 and math.isfinite(h) for h in conv["H_c"]), "no usable H_c"
print(f"interop ok: {len(parts)} part file(s), {df.height} rows, {conv.height} converged; "
      f"polars {pl.__version__}, pyarrow {pq.__name__.split('.')[0]} read the same rows and footers")
