//! `ehlmap case` on the textbook's Example 7-1 (seed 002), worked by hand from the book's data:
//! R = 16 (-103)/(16 - 103) mm = 18.94 mm, E' = 208 GPa/(1 - 0.09) = 228.6 GPa,
//! W' = 3000/(0.035 E' R) = 1.98e-5, U = 0.003 x 1.08/(E' R) = 7.48e-13, G = 2.3e-7 E' = 52571,
//! g_v = G W'^(3/2)/U^(1/2) = 5353 (the book prints 3264 and then uses 5366: an arithmetic slip),
//! g_e = W'/U^(1/2) = 22.9, regime rigid-piezoviscous (the book's R-V),
//! h_min = 1.66 g_v^(2/3) U R/W' = 0.364 um (the book's 0.24 um follows from its g_h = 339.2,
//! which matches neither g_v: a second slip).

mod common;
use common::ehlmap;

#[test]
fn textbook_example_7_1() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/sweeps/cases/example-7-1.toml");
    let out = ehlmap(&["case", path, "--json", "--no-solve"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let f = |k: &str| v[k].as_f64().unwrap();
    let close = |a: f64, b: f64, tol: f64| (a / b - 1.0).abs() < tol;
    assert!(close(f("r"), 18.943e-3, 1e-3), "R {}", f("r"));
    assert!(close(f("e_reduced"), 228.57e9, 1e-3));
    assert!(close(f("w_prime"), 1.980e-5, 2e-3));
    assert!(close(f("u_mean"), 7.483e-13, 2e-3));
    assert!(close(f("g"), 52571.0, 1e-3));
    assert!(close(f("g_v"), 5353.0, 2e-3), "g_v {}", f("g_v"));
    assert!(close(f("g_e"), 22.88, 2e-3));
    assert_eq!(v["regime"], "RigidPiezoviscous");
    let films = v["films"].as_array().unwrap();
    let book = films
        .iter()
        .find(|x| x[0].as_str().unwrap().starts_with("textbook"))
        .unwrap();
    assert!(close(book[2].as_f64().unwrap(), 0.364e-6, 5e-3), "{book}");
    // Moes (u_s) groups: M = W'/sqrt(2U), L = G (2U)^(1/4).
    assert!(close(f("m"), 1.980e-5 / (2.0 * 7.483e-13f64).sqrt(), 3e-3));
    assert!(close(
        f("l"),
        52571.0 * (2.0 * 7.483e-13f64).powf(0.25),
        3e-3
    ));
}

#[test]
fn contradictory_inputs_exit_2_naming_the_input() {
    let dir = std::env::temp_dir().join(format!("ehlmap-case-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/sweeps/cases/example-7-1.toml"
    ))
    .unwrap();
    for (from, to, needle) in [
        (
            "nu = 0.3\nrq = 0.1e-6\n\n[body2]",
            "nu = 0.5\nrq = 0.1e-6\n\n[body2]",
            "body1.nu",
        ),
        ("u2 = 1.08", "u2 = -1.08", "u1 + u2"),
        ("radius_x = -0.103", "radius_x = -0.012", "convex"),
        ("\neta0 = 0.003\n", "\neta0 = -0.003\n", "eta0"),
        ("\neta0 = 0.003\n", "\neta0 = 0.003\nbogus = 1\n", "bogus"),
    ] {
        let text = base.replacen(from, to, 1);
        assert_ne!(text, base, "{from}");
        let p = dir.join("case.toml");
        std::fs::write(&p, text).unwrap();
        let out = ehlmap(&["case", p.to_str().unwrap(), "--no-solve"]);
        assert_eq!(out.status.code(), Some(2), "{needle}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{needle}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn line_case_with_a_walther_oil() {
    // Example 7-1 with ISO VG 32 at 40 C instead of eta0/alpha: eta0 = nu40 rho(40 C) exactly
    // (the Walther line passes through its 40 C point), rho = 860 (1 - 6.5e-4 x 25) kg/m^3,
    // alpha the table's 1.9e-8 1/Pa.
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/sweeps/cases/example-7-1.toml"
    ))
    .unwrap();
    let text = base.replacen("eta0 = 0.003\nalpha = 2.3e-7\n", "", 1)
        + "\n[lubricant]\noil = \"ISO VG 32\"\ntemperature = 40.0\n";
    assert!(!text.contains("\neta0 ="));
    let dir = std::env::temp_dir().join(format!("ehlmap-case-oil-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let p = dir.join("case.toml");
    std::fs::write(&p, &text).unwrap();
    let out = ehlmap(&["case", p.to_str().unwrap(), "--json", "--no-solve"]);
    assert!(
        out.status.success(),
        "{}\n{text}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let eta0 = v["eta0"].as_f64().unwrap();
    let hand = 32e-6 * 860.0 * (1.0 - 6.5e-4 * 25.0);
    assert!((eta0 / hand - 1.0).abs() < 1e-12, "{eta0} vs {hand}");
    assert_eq!(v["alpha"].as_f64().unwrap(), 1.9e-8);
    // eta0/alpha given twice is contradictory
    let both = format!("eta0 = 0.003\nalpha = 2.3e-7\n{text}");
    std::fs::write(&p, both).unwrap();
    let out = ehlmap(&["case", p.to_str().unwrap(), "--no-solve"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("contradictory"));
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_case_with_roughness_is_solved_with_rough_surfaces_beside_the_smooth_one() {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/sweeps/cases/example-7-1.toml");
    let out = ehlmap(&["case", path, "--json"]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let smooth = &v["numerical"];
    let rough = &v["mixed"];
    assert_eq!(rough["status"], "converged");
    // sigma = sqrt(2) x 0.1 um in Moes units: the smooth h_c (m) over H_c converts it.
    let h_c_m = v["films"].as_array().unwrap()[0][2].as_f64().unwrap();
    let um_per_moes = h_c_m / smooth["H_c"].as_f64().unwrap() * 1e6;
    let sigma_um = rough["sigma"].as_f64().unwrap() * um_per_moes;
    assert!(
        (sigma_um / (2f64.sqrt() * 0.1) - 1.0).abs() < 1e-9,
        "{sigma_um}"
    );
    assert_eq!(rough["H_c_smooth"], smooth["H_c"]);
    assert_eq!(rough["slide_roll"], 0.0);
    // Lambda about 2.2: the rough film is thicker (isotropic flow factors below 1).
    let lam = rough["Lambda"].as_f64().unwrap();
    assert!(lam > 1.0 && lam < 3.0, "{lam}");
    assert!(rough["H_c"].as_f64().unwrap() > smooth["H_c"].as_f64().unwrap());
    // --smooth-only skips it.
    let out = ehlmap(&["case", path, "--json", "--smooth-only"]);
    let v: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert!(v["mixed"].is_null());
}

#[test]
fn a_roughness_orientation_needs_a_roughness() {
    let dir = std::env::temp_dir().join(format!("ehlmap-case-gamma-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let base = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/sweeps/cases/example-7-1.toml"
    ))
    .unwrap();
    let no_rq: String = base
        .lines()
        .filter(|l| !l.starts_with("rq"))
        .collect::<Vec<_>>()
        .join("\n");
    for (name, text, needle) in [
        (
            "a.toml",
            format!("gamma = 3.0\n{no_rq}"),
            "needs a roughness",
        ),
        ("b.toml", format!("gamma = 0.0\n{base}"), "gamma = 0"),
    ] {
        let f = dir.join(name);
        std::fs::write(&f, text).unwrap();
        let out = ehlmap(&["case", f.to_str().unwrap(), "--no-solve"]);
        assert_eq!(out.status.code(), Some(2), "{name}");
        let err = String::from_utf8_lossy(&out.stderr);
        assert!(err.contains(needle), "{name}: {err}");
    }
    std::fs::remove_dir_all(&dir).ok();
}
