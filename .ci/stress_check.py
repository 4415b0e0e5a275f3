#!/usr/bin/env python3
"""Checks a stress-sweep dataset (sweeps/stress.toml) with pyarrow, the way a notebook reads it:

* the dataset is complete: distinct case ids number the footer's `cases_total`, none twice;
* every row has a status, one of the known names;
* no NaN or infinity in a numeric column of a row that is not flagged (flagged: status other than
  `converged`, or `valid` false); a converged valid row has H_c and H_min;
* no row with status `converged` and a film (H_c or H_min) <= 0: a film the grid does not resolve
  is not a converged answer, whatever `valid` says.

Usage: stress_check.py DATASET_DIR. Prints a summary and every offending row; exit 1 on any."""
import math
import sys
from collections import Counter

import pyarrow.compute as pc
import pyarrow.dataset as pads
import pyarrow.parquet as pq

# Every status a row may hold (src/store/results/row.rs, plus the solver's under-resolved).
KNOWN = {"converged", "diverged", "stalled", "max-iterations", "not-run", "invalid", "panic",
         "under-resolved"}
FILMS = ("H_c", "H_min")


def label(r):
    d = "" if r.get("D") is None else f", D = {r['D']}"
    return (f"{r['case_id']} {r['contact']} M = {r['M']:.6g}, L = {r['L']:g}{d} "
            f"(status {r['status']}, valid {r['valid']}, grid {r.get('grid')})")


def main(path):
    ds = pads.dataset(path, format="parquet")
    table = ds.to_table()
    rows = table.to_pylist()
    problems = []
    if not rows:
        problems.append(f"{path}: no rows")
    # Complete, no case twice.
    ids = Counter(r["case_id"] for r in rows)
    twice = [i for i, n in ids.items() if n > 1]
    if twice:
        problems.append(f"{len(twice)} case ids stored more than once, e.g. {twice[0]}")
    totals = set()
    for f in ds.files:
        meta = pq.read_metadata(f).metadata or {}
        totals.add(meta.get(b"cases_total", b"?").decode())
    if totals != {str(len(ids))}:
        problems.append(f"{len(ids)} distinct cases, footers say cases_total = {sorted(totals)}")
    numeric = [f.name for f in table.schema
               if f.type in ("double", "float", "int64", "int32")]
    for r in rows:
        status = r.get("status")
        if status is None or status == "":
            problems.append(f"no status: {r.get('case_id')}")
            continue
        if status not in KNOWN:
            problems.append(f"unknown status {status!r}: {label(r)}")
        flagged = status != "converged" or not r.get("valid")
        if not flagged:
            bad = [c for c in numeric
                   if isinstance(r[c], float) and not math.isfinite(r[c])]
            if bad:
                problems.append(f"NaN/inf in {', '.join(bad)} of an unflagged row: {label(r)}")
            missing = [c for c in FILMS if r[c] is None]
            if missing:
                problems.append(f"no {', '.join(missing)} in a converged valid row: {label(r)}")
        if status == "converged":
            films = [f"{c} = {r[c]:.4g}" for c in FILMS if r[c] is not None and r[c] <= 0]
            if films:
                problems.append(f"converged with a film <= 0 ({', '.join(films)}): {label(r)}")
    # NaN stored anywhere at all (the writer stores null instead), counted for the summary.
    nan_cells = sum(pc.sum(pc.is_nan(table[c])).as_py() or 0
                    for c in numeric if str(table.schema.field(c).type) in ("double", "float"))
    statuses = Counter(r["status"] for r in rows)
    print(f"{path}: {len(rows)} rows, {len(ids)} cases; statuses "
          + ", ".join(f"{k} {v}" for k, v in sorted(statuses.items()))
          + f"; valid false {sum(1 for r in rows if not r['valid'])}; NaN cells {nan_cells}")
    for p in problems:
        print("FAIL:", p)
    if problems:
        print(f"stress check: {len(problems)} problems")
        return 1
    print("stress check ok")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit(__doc__)
    sys.exit(main(sys.argv[1]))
