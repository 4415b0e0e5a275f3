//! Sweeps with an accuracy target: each case stops at the first grid whose error estimate meets
//! the target (up to the spec's grid), and the estimate is stored in H_c_err / H_min_err.

mod common;

use ehlmap::store::results::read_dataset;
use std::process::Command;

#[test]
fn sweep_accuracy_target_picks_the_grid_per_case() {
    let (dir, spec, out) = common::sweep_in_temp(
        "acc",
        "acc",
        "name = \"acc\"\ncontact = \"line\"\n[axes]\nM = [20, 100]\nL = [5]\n\
         [numerics]\ngrid = 4097\naccuracy = 0.01\n",
    );
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

#[test]
fn mixed_sweep_with_targets_records_model_level_and_estimate() {
    let (dir, _, out) = common::sweep_in_temp(
        "sel",
        "sel",
        "name = \"sel\"\ncontact = [\"line\", \"point\"]\n[axes]\nM = [0.05, 20]\nL = [0]\nD = [1]\n\
         [axes.point]\nM = [20]\nL = [5]\n\
         [numerics]\naccuracy = 0.02\n[numerics.line]\ngrid = 4097\n[numerics.point]\ngrid = 129\n",
    );
    let log = String::from_utf8_lossy(&out.stderr);
    assert!(out.status.success(), "{log}");
    assert!(log.contains("models used: closed-form 1 ("), "{log}");
    assert!(log.contains("), full 2 ("), "{log}");
    let rows = read_dataset(&dir.join("sel")).unwrap();
    assert_eq!(rows.len(), 3);
    for r in &rows {
        assert_eq!(r.status, "converged", "{}", r.reason);
        assert!(r.valid, "{}", r.reason);
        assert_eq!(r.accuracy, Some(0.02));
        let est = r.error_estimate.expect("an estimate");
        assert!(est <= 0.02, "{est}");
        match (r.contact.as_str(), r.m) {
            ("line", m) if m < 1.0 => {
                // Martin's film, no grid: level and P_max null, yet a valid row.
                assert_eq!(r.model_used, "closed-form");
                assert_eq!((r.level, r.grid, r.p_max), (None, None, None));
                assert!((r.h_c.unwrap() * m / 2.4475 - 1.0).abs() < 1e-12);
            }
            (_, _) => {
                assert_eq!(r.model_used, "full");
                let (level, grid) = (r.level.unwrap(), r.grid.unwrap());
                let base = if r.contact == "line" { 32 } else { 16 };
                assert_eq!(grid - 1, base << level, "level {level}, grid {grid}");
            }
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}
