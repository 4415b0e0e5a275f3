//! The speed-accuracy bench and the stability map on a tiny ladder: every method reports the
//! same discretisation error on the same grid (same discrete problem), errors fall at second
//! order, and the Pareto summary picks a converged, accurate-enough run.

use ehlmap::bench::{speed, stability};
use ehlmap::model::case::{LineCase, PointCase};

#[test]
fn methods_share_the_discretisation_error_and_pareto_is_consistent() {
    let cases = [(
        "line M=20 L=5",
        speed::BenchCase::Line(LineCase::new(20.0, 5.0).unwrap()),
    )];
    let mut log = |_: &str| {};
    let (refs, rows) = speed::run(&cases, &[257, 513], 1, 2049, &mut log);
    assert_eq!(refs.len(), 1);
    assert!(rows.iter().all(|r| r.status == "converged"), "{rows:?}");
    for g in [257usize, 513] {
        // Every method converged tightly solves the same discrete problem: one error.
        let errs: Vec<f64> = rows
            .iter()
            .filter(|r| r.grid == g && r.method != "multigrid-V-fast")
            .map(|r| r.err_h_c)
            .collect();
        assert_eq!(errs.len(), 6, "six tight methods at {g} points");
        let spread = errs.iter().fold(0.0f64, |a, &e| a.max((e - errs[0]).abs()));
        assert!(spread < 1e-5, "methods differ on the same grid: {errs:?}");
        // The default stopping rule leaves an algebraic error of about a tenth of the
        // discretisation error: its error is within 20 % of the tight one's.
        let fast = rows
            .iter()
            .find(|r| r.grid == g && r.method == "multigrid-V-fast")
            .unwrap();
        assert!(
            (fast.err_h_c - errs[0]).abs() < 0.2 * errs[0],
            "fast {} against tight {}",
            fast.err_h_c,
            errs[0]
        );
    }
    let tight = |g: usize| {
        rows.iter()
            .find(|r| r.grid == g && r.method == "multigrid-V")
            .unwrap()
            .err_h_c
    };
    let (e257, e513) = (tight(257), tight(513));
    let order = (e257 / e513).log2();
    assert!(order > 1.6 && order < 2.4, "observed order {order}");
    for (_, t, best) in speed::pareto(&rows, &[0.05, 1e-6]) {
        match best {
            Some(b) => assert!(b.err_h_c <= t && b.err_h_min <= t && b.status == "converged"),
            None => assert!(t < 1e-3, "a 5 % target must be met on this ladder"),
        }
    }
}

#[test]
fn point_bench_runs_every_method_and_newton_matches_multigrid() {
    let cases = [(
        "circular M=20 L=10",
        speed::BenchCase::Point(PointCase::new(20.0, 10.0, 1.0).unwrap()),
    )];
    let mut log = |_: &str| {};
    let (refs, rows) = speed::run(&cases, &[33], 1, 129, &mut log);
    assert_eq!(refs.len(), 1);
    let methods: Vec<&str> = rows.iter().map(|r| r.method.as_str()).collect();
    assert_eq!(
        methods,
        [
            "multigrid-V-fast",
            "multigrid-V",
            "multigrid-V-1cycle",
            "multigrid-V-direct",
            "multigrid-W",
            "newton",
            "relax"
        ]
    );
    let get = |m: &str| rows.iter().find(|r| r.method == m).unwrap();
    for m in [
        "multigrid-V-fast",
        "multigrid-V",
        "multigrid-V-direct",
        "multigrid-W",
        "newton",
    ] {
        assert_eq!(get(m).status, "converged", "{m}");
    }
    // FFT and direct deformation products give the same discrete solution.
    assert!((get("multigrid-V-direct").h_c / get("multigrid-V").h_c - 1.0).abs() < 1e-9);
    // Same discrete problem: the same error against the Richardson reference.
    assert!((get("newton").err_h_c - get("multigrid-V").err_h_c).abs() < 1e-5);
    // 33^2 against the 65/129 Richardson value: a few per cent.
    assert!(get("multigrid-V").err_h_c > 1e-3 && get("multigrid-V").err_h_c < 0.2);
}

#[test]
fn stability_map_records_every_cell() {
    let mut log = |_: &str| {};
    let cells = stability::run(&[20.0], &[0.0, 10.0], 257, &mut log);
    assert_eq!(cells.len(), 2 * stability::map_methods(257).len());
    let s = stability::summary(&cells);
    assert!(s.iter().any(|(n, ok, all)| n == "multigrid" && ok == all));
    assert!(cells.iter().all(|c| !c.reason.is_empty()));
}

#[test]
fn selection_bench_measures_the_saving_at_the_target() {
    use ehlmap::bench::selection;
    let text =
        "contact = \"line\"\n[axes]\nM = [0.05, 20, 100]\nL = [0, 5]\n[numerics]\ngrid = 4097\n";
    let spec = ehlmap::sweep::spec::parse("sel.toml", text, "sel").unwrap();
    let cases = ehlmap::sweep::plan::plan(&spec).unwrap();
    let target = 0.01;
    let pairs = selection::run(&cases, "sel", target);
    assert_eq!(pairs.len(), 6);
    let (mut t_sel, mut t_full) = (0.0, 0.0);
    for p in &pairs {
        assert_eq!(p.full.status, "converged", "{}", p.full.reason);
        assert_eq!(p.selected.status, "converged", "{}", p.selected.reason);
        // Against the full model on 4097 points (itself within ~3e-4 of the limit), the
        // targeted answer is within the target.
        let dev = p.deviation().unwrap();
        assert!(dev <= target, "M={} L={}: {dev}", p.full.m, p.full.l);
        assert!(p.selected.grid.unwrap_or(0) < 4097);
        t_sel += p.selected.wall_s.unwrap();
        t_full += p.full.wall_s.unwrap();
    }
    let closed = pairs
        .iter()
        .filter(|p| p.selected.model_used == "closed-form")
        .count();
    assert_eq!(closed, 1, "M = 0.05, L = 0 is Martin's film");
    assert!(t_sel < t_full, "{t_sel} s with selection vs {t_full} s");
    let md = selection::summary(&pairs, target, "sel.toml");
    assert!(md.contains("within the target in 6 of 6"), "{md}");
}

#[test]
fn the_box_map_records_status_attempt_work_and_time_limit_per_case() {
    use ehlmap::bench::box_map::{box_summary, run_box, BoxCase};
    use ehlmap::{Case, LineCase, PointCase};
    // An easy line case meets the default target; a hard point corner with a tenth of a second
    // reaches its limit and says so.
    let cases = [
        BoxCase {
            case: Case::Line(LineCase::new(10.0, 0.0).unwrap()),
            panel: 0,
        },
        BoxCase {
            case: Case::Point(PointCase::new(3e4, 30.0, 1.0).unwrap()),
            panel: 1,
        },
    ];
    let cells = run_box(&cases, 0.1, false, &|_| {});
    let (easy, hard) = (&cells[0], &cells[1]);
    assert_eq!(easy.status, "converged", "{}", easy.reason);
    assert!(easy.accuracy_met && !easy.timed_out, "{easy:?}");
    assert_eq!((easy.attempt, easy.contact.as_str()), (1, "line"));
    assert!(easy.work_units > 0.0 && easy.error_estimate.unwrap() <= 0.01);
    assert!(hard.timed_out && !hard.accuracy_met, "{hard:?}");
    assert_eq!(hard.status, "max-iterations", "{}", hard.reason);
    assert_eq!((hard.d, hard.l), (1.0, 30.0));
    let s = box_summary(&cells);
    assert_eq!(s[0].1..=s[0].4, 1..=1, "{s:?}");
    assert_eq!((s[1].1, s[1].3, s[1].4), (0, 1, 1), "{s:?}");
}

#[test]
fn stability_box_writes_its_table_chart_and_summary() {
    use arrow_array::{Array, BooleanArray, StringArray};
    use parquet::arrow::arrow_reader::ParquetRecordBatchReaderBuilder;
    let dir = std::env::temp_dir().join(format!("ehlmap-box-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args([
            "stability",
            "--box",
            "--quick",
            "--time-limit",
            "0.2",
            "--out",
        ])
        .arg(&dir)
        .output()
        .unwrap();
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let file = std::fs::File::open(dir.join("stability.parquet")).unwrap();
    let mut rows = 0;
    for batch in ParquetRecordBatchReaderBuilder::try_new(file)
        .unwrap()
        .build()
        .unwrap()
    {
        let b = batch.unwrap();
        let status = b.column_by_name("status").unwrap();
        let status = status.as_any().downcast_ref::<StringArray>().unwrap();
        let timed = b.column_by_name("timed_out").unwrap();
        let timed = timed.as_any().downcast_ref::<BooleanArray>().unwrap();
        for i in 0..b.num_rows() {
            let st = status.value(i);
            assert!(
                [
                    "converged",
                    "diverged",
                    "stalled",
                    "max-iterations",
                    "under-resolved"
                ]
                .contains(&st),
                "{st}"
            );
            // A timed-out case is a result, never a crash or a null.
            assert!(!timed.is_null(i));
        }
        for name in [
            "M",
            "L",
            "D",
            "attempt",
            "grid",
            "work_units",
            "wall_s",
            "reason",
        ] {
            assert!(b.column_by_name(name).is_some(), "{name}");
        }
        rows += b.num_rows();
    }
    // 2 model sets x (3 x 2 line + 3 D x 3 x 2 point).
    assert_eq!(rows, 48);
    assert!(dir.join("stability.png").exists());
    let md = std::fs::read_to_string(dir.join("stability.md")).unwrap();
    assert!(md.contains("| point D = 0.01, Roelands + DH |"), "{md}");
    // Flags that do not apply with --box are refused before any solve.
    let bad = std::process::Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["stability", "--box", "--grid", "257", "--out"])
        .arg(&dir)
        .output()
        .unwrap();
    assert_eq!(bad.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&bad.stderr).contains("--grid 257"));
    let _ = std::fs::remove_dir_all(&dir);
}
