#!/usr/bin/env python3
"""Foreign Parquet: a dataset re-saved from a notebook reads in ehlmap.

* pyarrow re-saves every part of DATASET with its default codec (snappy), polars with gzip and
  with lz4; `ehlmap fit` on each copy gives the same fit.json as on DATASET (datasets field
  aside), with --no-limit-solves;
* a Parquet file of another layout makes `ehlmap fit` exit 2 with "not an ehlmap dataset:
  missing column `case_id`", naming the file.

Usage: foreign_parquet.py EHLMAP DATASET [WORKDIR]. Exit 1 on a failure."""
import glob
import json
import os
import shutil
import subprocess
import sys
import tempfile

import polars as pl
import pyarrow as pa
import pyarrow.parquet as pq


def fit(ehlmap, dataset, out):
    r = subprocess.run([ehlmap, "fit", dataset, "--no-limit-solves", "--json", "--out", out],
                       capture_output=True, text=True)
    return r.returncode, r.stdout, r.stderr


def comparable(text):
    j = json.loads(text)
    j.pop("datasets", None)
    return j


def main(ehlmap, dataset, work):
    parts = sorted(glob.glob(os.path.join(dataset, "*.parquet")))
    if not parts:
        print(f"FAIL: {dataset} holds no Parquet file")
        return 1
    failures = []
    code, want, err = fit(ehlmap, dataset, os.path.join(work, "report-original"))
    if code != 0:
        print(f"FAIL: ehlmap fit {dataset}: exit {code}: {err}")
        return 1
    want = comparable(want)
    copies = {
        # pyarrow's default codec is snappy; the name a notebook might choose.
        "pyarrow-snappy": lambda src, dst: pq.write_table(pq.read_table(src), dst),
        "polars-gzip": lambda src, dst: pl.read_parquet(src).write_parquet(dst, compression="gzip"),
        "polars-lz4": lambda src, dst: pl.read_parquet(src).write_parquet(dst, compression="lz4"),
    }
    for tag, save in copies.items():
        d = os.path.join(work, f"smoke-{tag}")
        os.makedirs(d)
        for i, src in enumerate(parts):
            dst = os.path.join(d, f"resaved-{i}.parquet")
            save(src, dst)
        codecs = {pq.ParquetFile(f).metadata.row_group(0).column(0).compression
                  for f in glob.glob(os.path.join(d, "*.parquet"))}
        code, got, err = fit(ehlmap, d, os.path.join(work, f"report-{tag}"))
        if code != 0:
            failures.append(f"ehlmap fit on the {tag} copy ({sorted(codecs)}): exit {code}: "
                            f"{err.strip()}")
        elif comparable(got) != want:
            failures.append(f"ehlmap fit on the {tag} copy ({sorted(codecs)}) differs from the "
                            "original's fit.json")
        else:
            print(f"{tag} ({', '.join(sorted(codecs))}): ehlmap fit reads it, same fit.json")
    # A table of another layout.
    other = os.path.join(work, "other")
    os.makedirs(other)
    path = os.path.join(other, "table.parquet")
    pq.write_table(pa.table({"x": [1.0, 2.0], "label": ["a", "b"]}), path)
    code, _, err = fit(ehlmap, other, os.path.join(work, "report-other"))
    want_msg = f"{path}: not an ehlmap dataset: missing column `case_id`"
    if code != 2 or want_msg not in err:
        failures.append(f"ehlmap fit on a foreign table: exit {code}, stderr {err.strip()!r}, "
                        f"want exit 2 and {want_msg!r}")
    else:
        print(f"foreign table: exit 2, {err.strip()}")
    for f in failures:
        print("FAIL:", f)
    if failures:
        return 1
    print("foreign Parquet ok")
    return 0


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        sys.exit(__doc__)
    given = len(sys.argv) == 4
    work = sys.argv[3] if given else tempfile.mkdtemp(prefix="ehlmap-foreign-")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    code = main(sys.argv[1], sys.argv[2], work)
    if not given and code == 0:
        shutil.rmtree(work, ignore_errors=True)
    sys.exit(code)
