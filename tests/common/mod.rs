//! Helpers shared by the integration tests.

use ehlmap::model::case::PointCase;
use ehlmap::solve::point::{solve_point, PointSolveParams};
use ehlmap::solve::Status;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

/// Run the `ehlmap` binary with `args` and collect its output.
#[allow(dead_code)]
pub fn ehlmap(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(args)
        .output()
        .expect("run ehlmap")
}

/// The Slurm variables a sweep reads (cleared by tests that run sweeps, so a test run inside a
/// Slurm job does not become one shard of it).
#[allow(dead_code)]
pub const SLURM_VARS: [&str; 5] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_COUNT",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_STEP",
    "SLURM_CPUS_PER_TASK",
];

/// A fresh scratch directory `ehlmap-<tag>-<pid>` under the system's temporary directory,
/// removed when dropped unless the test is failing (then it is kept to look at).
#[allow(dead_code)]
pub struct Scratch(PathBuf);

#[allow(dead_code)]
impl Scratch {
    /// Create the directory (emptied first if a former run left it).
    pub fn new(tag: &str) -> Self {
        let d = std::env::temp_dir().join(format!("ehlmap-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&d);
        std::fs::create_dir_all(&d).unwrap();
        Scratch(d)
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        if !std::thread::panicking() {
            let _ = std::fs::remove_dir_all(&self.0);
        }
    }
}

/// Write `spec` (TOML) to `<name>.toml` in a fresh temporary directory tagged `tag` and run
/// `ehlmap sweep` on it into that directory without progress output: (directory, spec file,
/// output). The dataset is `directory/<name>`.
#[allow(dead_code)]
pub fn sweep_in_temp(tag: &str, name: &str, spec: &str) -> (PathBuf, PathBuf, Output) {
    let dir = std::env::temp_dir().join(format!("ehlmap-{tag}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join(format!("{name}.toml"));
    std::fs::write(&file, spec).unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .arg("sweep")
        .arg(&file)
        .arg("--out")
        .arg(&dir)
        .args(["--progress", "none"])
        .output()
        .unwrap();
    (dir, file, out)
}

/// Full-model point H_c and H_min extrapolated (Richardson, order 2) from `grid` and its half
/// grid, and the larger relative change of the two between those grids.
#[allow(dead_code)]
pub fn point_reference(c: &PointCase, grid: usize) -> ((f64, f64), f64) {
    let solve = |g: usize| {
        let mut p = PointSolveParams::default();
        p.mg.grid = g;
        let o = solve_point(c, &p).outputs;
        assert_eq!(o.status, Status::Converged, "reference: {}", o.reason);
        (o.h_c, o.h_min)
    };
    let (a, b) = (solve((grid - 1) / 2 + 1), solve(grid));
    let ext = (b.0 + (b.0 - a.0) / 3.0, b.1 + (b.1 - a.1) / 3.0);
    (ext, (b.0 / a.0 - 1.0).abs().max((b.1 / a.1 - 1.0).abs()))
}
