#!/usr/bin/env python3
"""Open an ehlmap sweep dataset with polars and show H_c over M for each L.

    cargo run --release -- sweep sweeps/smoke.toml
    python3 examples/explore.py outputs/smoke            # plot to outputs/smoke-hc.png
    python3 examples/explore.py outputs/smoke --table    # print a table instead

Needs polars (pip install polars); plots with matplotlib when it is installed, else prints the
table. The dataset is a directory of part files, one per sweep process; polars' scan_parquet
reads the whole directory. A case id can appear in two parts only if runs overlapped: keep one.
Use only rows with status == "converged" and valid == true for fits.
"""

import sys
from pathlib import Path

import polars as pl


def load(dataset: Path) -> pl.DataFrame:
    lf = pl.scan_parquet(dataset)  # every part-*.parquet of the directory
    return (
        lf.filter((pl.col("status") == "converged") & pl.col("valid"))
        .unique(subset="case_id", keep="first")
        .select("case_id", "M", "L", "H_c", "H_min", "P_max", "H_c_err", "wall_s")
        .sort("L", "M")
        .collect()
    )


def footer(dataset: Path) -> None:
    """Print the footer metadata of each part (needs pyarrow; skipped without it)."""
    try:
        import pyarrow.parquet as pq
    except ImportError:
        return
    for part in sorted(dataset.glob("part-*.parquet")):
        meta = pq.read_metadata(part).metadata or {}
        kv = {k.decode(): v.decode() for k, v in meta.items() if k != b"ARROW:schema"}
        print(
            f"{part.name}: ehlmap {kv.get('ehlmap_version')} commit {kv.get('git_commit', '')[:12]} "
            f"shard {kv.get('shard')} rows {kv.get('rows')} created {kv.get('created')}"
        )


def main() -> int:
    args = [a for a in sys.argv[1:] if not a.startswith("--")]
    dataset = Path(args[0] if args else "outputs/smoke")
    if not any(dataset.glob("part-*.parquet")):
        print(f"{dataset}: no part-*.parquet files (run `ehlmap sweep SPEC` first)", file=sys.stderr)
        return 1
    footer(dataset)
    df = load(dataset)
    print(f"{dataset}: {df.height} converged cases")
    plt = None
    if "--table" not in sys.argv:
        try:
            import matplotlib

            matplotlib.use("Agg")
            import matplotlib.pyplot as plt
        except ImportError:
            print("matplotlib is not installed: printing the table instead")
    if plt is None:
        with pl.Config(tbl_rows=-1, tbl_cols=-1):
            print(df.pivot(on="L", index="M", values="H_c", sort_columns=True).sort("M"))
        return 0
    fig, ax = plt.subplots(figsize=(7, 5))
    for (l,), g in df.group_by("L", maintain_order=True):
        ax.loglog(g["M"], g["H_c"], "o-", label=f"L = {l:g}")
    ax.set_xlabel("M")
    ax.set_ylabel("H_c (Moes units)")
    ax.set_title(f"Central film thickness: {dataset.name}")
    ax.grid(True, which="both", alpha=0.3)
    ax.legend()
    out = dataset.parent / f"{dataset.name}-hc.png"
    fig.savefig(out, dpi=120, bbox_inches="tight")
    print(f"wrote {out}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
