//! Build script: records the git commit (`git rev-parse HEAD`, or "unknown" outside a checkout)
//! as `EHLMAP_GIT_COMMIT`, which the sweep engine writes to every Parquet footer.

use std::path::Path;
use std::process::Command;

fn main() {
    let commit = Command::new("git")
        .args(["rev-parse", "HEAD"])
        .output()
        .ok()
        .filter(|o| o.status.success())
        .and_then(|o| String::from_utf8(o.stdout).ok())
        .map(|s| s.trim().to_string())
        .filter(|s| !s.is_empty())
        .unwrap_or_else(|| "unknown".to_string());
    println!("cargo:rustc-env=EHLMAP_GIT_COMMIT={commit}");
    println!("cargo:rerun-if-changed=build.rs");
    // Re-run when HEAD moves: HEAD itself, the branch it points to, and packed refs.
    let git = Path::new(".git");
    if git.is_dir() {
        println!("cargo:rerun-if-changed=.git/HEAD");
        if let Ok(head) = std::fs::read_to_string(git.join("HEAD")) {
            if let Some(r) = head.trim().strip_prefix("ref: ") {
                if git.join(r).exists() {
                    println!("cargo:rerun-if-changed=.git/{r}");
                }
            }
        }
        if git.join("packed-refs").exists() {
            println!("cargo:rerun-if-changed=.git/packed-refs");
        }
    }
}
