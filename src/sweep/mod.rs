//! The sweep engine: `ehlmap sweep SPEC` turns a TOML spec of (M, L) axes (and D for point
//! contacts), models and numerical settings into a Parquet dataset with one row per case.
//!
//! Contract:
//!
//! * **Validated up front** ([`spec`]): an unknown key, an empty axis, M <= 0, L < 0, D outside
//!   (0, 1], a bad range or model combination stops the command with exit code 2 and a message
//!   `FILE:LINE: KEY: what is wrong`, before anything is solved or written. `contact = "point"`
//!   needs the ellipticity axis `D`; a line spec must not give one.
//! * **Stable ids** ([`plan`]): each case has a 64-bit FNV-1a id of its canonical parameter
//!   string (physics, models, numerics; not the sweep name or output settings). A case id stored
//!   anywhere in the dataset directory is never solved again: a rerun (with or without
//!   `--resume`) solves only what is missing.
//! * **Deterministic results** ([`executor`]): each case is one single-threaded solve,
//!   independent of the others, so every column except `wall_s` is identical whatever
//!   `--threads` or `--shard`. Work is taken largest estimated cost first. A line case that fails
//!   cold is warm-started ([`crate::strategy::warm`]) from its own chain of lower-M neighbours,
//!   solved within the same task, so warm starts do not break this either; `warm_start` records
//!   the neighbour's case id.
//! * **Shards**: `--shard i/n` (or `SLURM_ARRAY_TASK_ID`/`SLURM_ARRAY_TASK_COUNT`) keeps the cases
//!   whose mixed id is `i - 1 (mod n)`; the union of shards 1..n is the whole sweep.
//! * **Storage** ([`crate::store::results`]): `<out>/<name>/part-<i>of<n>-<run>.parquet`, one file
//!   per process, rewritten atomically (temporary file + rename) after every batch; a `kill -9`
//!   loses at most the cases solved since the last flush, and never leaves a file that a reader
//!   chokes on. Failed solves are rows with their `status` and `reason`; non-finite outputs are
//!   nulls with `valid = false`.
//! * **One writer per shard** ([`lock`]): a run holds the lock file `<out>/.<name>.<i>of<n>.lock`
//!   (pid, host, start, command); a second run of the shard (or of an overlapping shard, or of
//!   another shard with other settings) refuses naming the holder; a stale lock (its process
//!   gone, e.g. after `kill -9`) is taken over with a warning; the lock goes at the end of the
//!   run, normal or not.
//! * **Tied to the spec** ([`settings`], [`dataset`]): every part file's footer holds the
//!   spec's row-defining settings (models, each contact's numerics) and their hash; a run into a
//!   dataset holding rows of other settings refuses (exit code 2) unless asked to start a new
//!   dataset, which moves those parts to `<out>/<name>.old-<hash>/`.
//! * **Exit codes**: 0 when every case of the shard is stored (numerical failures included),
//!   1 on an I/O error while running or a dataset shard another run holds, 2 on a bad spec, bad
//!   arguments or a spec whose settings conflict with the dataset's.

pub mod dataset;
pub mod executor;
pub mod lock;
pub mod plan;
pub mod progress;
pub mod row;
pub mod settings;
pub mod spec;
