//! Sweeps with an accuracy target: each case stops at the first grid whose error estimate meets
//! the target (up to the spec's grid), and the estimate is stored in H_c_err / H_min_err.

use ehlmap::io::results::read_dataset;
use std::process::Command;

#[test]
fn sweep_accuracy_target_picks_the_grid_per_case() {
    let dir = std::env::temp_dir().join(format!("ehlmap-acc-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let spec = dir.join("acc.toml");
    std::fs::write(
        &spec,
        "name = \"acc\"\ncontact = \"line\"\n[axes]\nM = [20, 100]\nL = [5]\n\
         [numerics]\ngrid = 4097\naccuracy = 0.01\n",
    )
    .unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args([
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
            "--progress",
            "none",
        ])
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let rows = read_dataset(&dir.join("acc")).unwrap();
    assert_eq!(rows.len(), 2);
    for r in &rows {
        assert_eq!(r.status, "converged", "{}", r.reason);
        let est = r.h_c_err.expect("an estimate");
        assert!(est <= 0.01, "{est}");
        assert!(r.grid.unwrap() < 4097, "grid {:?}", r.grid);
        assert!(r.reason.contains("accuracy"), "{}", r.reason);
    }
    // An invalid target is a spec error (exit 2) naming the key.
    std::fs::write(
        &spec,
        "name = \"acc\"\ncontact = \"line\"\n[axes]\nM = [20]\nL = [5]\n[numerics]\naccuracy = 2\n",
    )
    .unwrap();
    let bad = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args([
            "sweep",
            spec.to_str().unwrap(),
            "--out",
            dir.to_str().unwrap(),
        ])
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("numerics.accuracy"));
    std::fs::remove_dir_all(&dir).ok();
}
