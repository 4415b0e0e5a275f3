//! Spec parsing: good specs, and errors naming file, line and key.

use super::*;

fn err(text: &str) -> SpecError {
    parse("t.toml", text, "t").unwrap_err()
}

const OK: &str = "contact = \"line\"\n[axes]\nM = [5, 20]\nL = { from = 0, to = 10, count = 3 }\n";

#[test]
fn parses_lists_and_ranges() {
    let s = parse("t.toml", OK, "t").unwrap();
    assert_eq!(s.m, vec![5.0, 20.0]);
    assert_eq!(s.l, vec![0.0, 5.0, 10.0]);
    assert_eq!(s.name, "t");
    let log = expand_range(1.0, 1000.0, 4, true);
    assert_eq!(log, vec![1.0, 10.0, 100.0, 1000.0]);
}

#[test]
fn errors_name_line_and_key() {
    let e = err("contact = \"line\"\n[axes]\nM = [5, -1]\nL = [0]\n");
    assert_eq!((e.line, e.key.as_str()), (3, "axes.M"));
    assert!(e.to_string().starts_with("t.toml:3: axes.M: M = -1"), "{e}");
    let e = err("contact = \"line\"\n[axes]\nM = [5]\nL = [0]\nQ = 3\n");
    assert_eq!((e.line, e.key.as_str()), (5, "axes.Q"));
    let e = err("contact = \"line\"\n[axes]\nM = []\nL = [0]\n");
    assert!(e.message.contains("empty") && e.line == 3, "{e}");
    let e = err("contact = \"point\"\n[axes]\nM = [5]\nL = [0]\nD = [1.5]\n");
    assert_eq!((e.line, e.key.as_str()), (5, "axes.D"));
    let e = err("contact = \"line\"\n[axes]\nM = { from = 0, to = 10, count = 3, scale = \"log\" }\nL = [0]\n");
    assert_eq!(e.line, 3);
    let e = err("contact = \"line\"\n[axes]\nM = [1]\nL = [0]\n[numerics]\ngrid = 8\n");
    assert_eq!((e.line, e.key.as_str()), (6, "numerics.grid"));
    let e = err("contact = \"line\"\n[axes]\nM = [1\n");
    assert!(e.message.contains("invalid TOML") && e.line >= 3, "{e}");
}

const POINT: &str = "contact = \"point\"\n[axes]\nM = [10, 100]\nL = [0, 10]\n";

#[test]
fn point_specs_parse_with_their_defaults() {
    let s = parse("p.toml", &format!("{POINT}D = [0.5, 1]\n"), "p").unwrap();
    assert_eq!(s.contacts[0].contact, Contact::Point);
    assert_eq!(s.d, Some(vec![0.5, 1.0]));
    // No grid named: the default accuracy target, up to the ladder's largest point grid.
    assert_eq!(
        s.contacts[0].numerics,
        Numerics {
            grid: 1025,
            accuracy: Some(0.01),
            ..Numerics::for_contact(Contact::Point)
        }
    );
    let text = format!(
        "{POINT}D = {{ from = 0.05, to = 1, count = 4, scale = \"log\" }}\n\
         [numerics]\ngrid = 65\nerror_estimate = true\n"
    );
    let s = parse("p.toml", &text, "p").unwrap();
    let d = s.d.unwrap();
    assert_eq!((d.len(), d[0], d[3]), (4, 0.05, 1.0));
    assert!(d.windows(2).all(|w| w[0] < w[1]));
    assert_eq!(s.contacts[0].numerics.grid, 65);
    assert!(s.contacts[0].numerics.error_estimate);
    // The line defaults: no grid named, so the default accuracy target up to 16385 points.
    let l = parse("t.toml", OK, "t").unwrap();
    assert_eq!(
        l.contacts[0].numerics,
        Numerics {
            grid: 16385,
            accuracy: Some(0.01),
            ..Numerics::default()
        }
    );
}

#[test]
fn bad_point_specs_name_line_and_key() {
    let e = err(&format!("{POINT}D = [0.5, 0]\n"));
    assert_eq!((e.line, e.key.as_str()), (5, "axes.D"), "{e}");
    assert!(e.message.contains("D = 0 is invalid"), "{e}");
    let e = err(&format!("{POINT}D = [1.5]\n"));
    assert_eq!((e.line, e.key.as_str()), (5, "axes.D"), "{e}");
    assert!(e.message.contains("D = 1.5 is invalid"), "{e}");
    let e = err(&format!("{POINT}D = {{ from = 0.5, to = 2, count = 3 }}\n"));
    assert_eq!((e.line, e.key.as_str()), (5, "axes.D"), "{e}");
    let e = err(POINT);
    assert_eq!(e.key, "axes.D", "{e}");
    assert!(
        e.message.contains("missing") && e.message.contains("(0, 1]"),
        "{e}"
    );
    let e = err("contact = \"line\"\n[axes]\nM = [5]\nL = [0]\nD = [0.5]\n");
    assert_eq!((e.line, e.key.as_str()), (5, "axes.D"), "{e}");
    assert!(e.message.contains("point\" only"), "{e}");
    for (grid, ok) in [
        (9, false),
        (17, true),
        (2049, true),
        (2050, false),
        (4097, false),
    ] {
        let r = parse(
            "p.toml",
            &format!("{POINT}D = [1]\n[numerics]\ngrid = {grid}\n"),
            "p",
        );
        assert_eq!(r.is_ok(), ok, "grid {grid}: {r:?}");
        if let Err(e) = r {
            assert_eq!((e.line, e.key.as_str()), (7, "numerics.grid"), "{e}");
            assert!(e.message.contains("from 17 to 2049"), "{e}");
        }
    }
    let e = err(&format!(
        "{POINT}D = [1]\n[numerics]\ngrid = 17\nerror_estimate = true\n"
    ));
    assert_eq!(
        (e.line, e.key.as_str()),
        (8, "numerics.error_estimate"),
        "{e}"
    );
    assert!(e.message.contains("grid >= 33"), "{e}");
    // Point accuracy targets are accepted now (refined from 33^2 nodes up to the grid).
    let s = parse(
        "p.toml",
        &format!("{POINT}D = [1]\n[numerics]\naccuracy = 0.01\n"),
        "p",
    )
    .unwrap();
    assert_eq!(s.contacts[0].numerics.accuracy, Some(0.01));
}

const MIXED: &str =
    "contact = [\"line\", \"point\"]\n[axes]\nM = [5, 20, 100]\nL = [0, 10]\nD = [0.5, 1]\n";

#[test]
fn mixed_specs_hold_both_contacts_with_their_own_axes_and_numerics() {
    let text = format!(
        "{MIXED}[axes.point]\nM = [10]\n[numerics]\nerror_estimate = true\n\
         [numerics.line]\ngrid = 1025\n[numerics.point]\ngrid = 65\naccuracy = 0.02\n"
    );
    let s = parse("m.toml", &text, "m").unwrap();
    assert_eq!(s.contacts.len(), 2);
    let (line, point) = (&s.contacts[0], &s.contacts[1]);
    assert_eq!(
        (line.contact, point.contact),
        (Contact::Line, Contact::Point)
    );
    assert_eq!(line.m, vec![5.0, 20.0, 100.0]);
    assert_eq!(
        (point.m.clone(), point.l.clone()),
        (vec![10.0], vec![0.0, 10.0])
    );
    assert_eq!((line.numerics.grid, point.numerics.grid), (1025, 65));
    assert!(line.numerics.error_estimate && point.numerics.error_estimate);
    assert_eq!(
        (line.numerics.accuracy, point.numerics.accuracy),
        (None, Some(0.02))
    );
    // 3 x 2 line cases and 1 x 2 x 2 point cases, with distinct ids.
    let cases = crate::sweep::plan::plan(&s).unwrap();
    assert_eq!(cases.len(), 6 + 4);
    assert_eq!(cases.iter().filter(|c| c.d.is_none()).count(), 6);
    // Defaults per contact when nothing is given.
    let s = parse("m.toml", MIXED, "m").unwrap();
    let line = s.numerics(Contact::Line).unwrap();
    assert_eq!((line.grid, line.accuracy), (16385, Some(0.01)));
    let point = s.numerics(Contact::Point).unwrap();
    assert_eq!((point.grid, point.accuracy), (1025, Some(0.01)));
}

#[test]
fn mixed_spec_errors_name_the_key() {
    let e = err("contact = [\"line\", \"line\"]\n[axes]\nM = [5]\nL = [0]\n");
    assert_eq!((e.line, e.key.as_str()), (1, "contact"));
    assert!(e.message.contains("twice"), "{e}");
    let e = err("contact = []\n[axes]\nM = [5]\nL = [0]\n");
    assert!(e.message.contains("empty"), "{e}");
    // A point part without D, a line-only spec with a point table, a bad per-contact value.
    let e = err("contact = [\"line\", \"point\"]\n[axes]\nM = [5]\nL = [0]\n");
    assert_eq!(e.key, "axes.D");
    let e = err("contact = \"line\"\n[axes]\nM = [5]\nL = [0]\n[numerics.point]\ngrid = 65\n");
    assert_eq!((e.line, e.key.as_str()), (5, "numerics.point"));
    let e = err(&format!("{MIXED}[numerics.point]\ngrid = 4097\n"));
    assert_eq!((e.line, e.key.as_str()), (7, "numerics.point.grid"));
    let e = err(&format!("{MIXED}[axes.point]\nM = [-1]\n"));
    assert_eq!((e.line, e.key.as_str()), (7, "axes.point.M"));
    let e = err(&format!(
        "{MIXED}[numerics.point]\ngrid = 17\nerror_estimate = true\n"
    ));
    assert_eq!(e.key, "numerics.point.error_estimate");
}

#[test]
fn roughness_axes_parse_and_plan_one_smooth_case_per_point() {
    let text =
        "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\nsigma = [0, 0.5, 1]\ngamma = [0.5, 1]\n";
    let s = parse("t.toml", text, "t").unwrap();
    assert_eq!(s.sigma, vec![0.0, 0.5, 1.0]);
    assert_eq!(s.gamma, vec![0.5, 1.0]);
    let cases = crate::sweep::plan::plan(&s).unwrap();
    // sigma = 0 is one smooth case whatever gamma: 1 + 2 x 2.
    assert_eq!(cases.len(), 5);
    let smooth: Vec<_> = cases
        .iter()
        .filter(|c| c.models.roughness.is_none())
        .collect();
    assert_eq!(smooth.len(), 1);
    // The smooth case keeps the id it has in a spec without roughness axes.
    let plain = parse(
        "t.toml",
        "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\n",
        "t",
    )
    .unwrap();
    let plain = crate::sweep::plan::plan(&plain).unwrap();
    assert_eq!(smooth[0].id, plain[0].id);
    let rough: Vec<_> = cases.iter().filter_map(|c| c.models.roughness).collect();
    assert!(rough.iter().any(|r| r.sigma == 1.0 && r.gamma == 0.5));
}

#[test]
fn roughness_axes_reject_bad_values() {
    let base = "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\n";
    let e = err(&format!("{base}sigma = [0, -1]\n"));
    assert_eq!((e.line, e.key.as_str()), (5, "axes.sigma"));
    let e = err(&format!("{base}sigma = [1]\ngamma = [0]\n"));
    assert_eq!((e.line, e.key.as_str()), (6, "axes.gamma"));
    let e = err(&format!("{base}gamma = [2]\n"));
    assert!(e.key == "axes.gamma" && e.message.contains("sigma"), "{e}");
    let e = err(&format!("{base}sigma = [nan]\n"));
    assert_eq!(e.key, "axes.sigma");
}

#[test]
fn roughness_models_reach_the_rough_cases_and_need_a_sigma_axis() {
    let text = "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\nsigma = [1]\n[models]\n\
                slide_roll = 0.5\nrough_surface = \"1\"\nph_over_e = 0.01\n\
                eta_beta_sigma = 0.05\nsigma_over_beta = 0.002\n";
    let s = parse("t.toml", text, "t").unwrap();
    let cases = crate::sweep::plan::plan(&s).unwrap();
    let r = cases[0].models.roughness.expect("rough");
    assert_eq!((r.sigma, r.slide_roll, r.variance_ratio_1), (1.0, 0.5, 1.0));
    assert_eq!((r.ph_over_e, r.asperity.eta_beta_sigma), (0.01, 0.05));
    assert_eq!(r.asperity.sigma_over_beta, 0.002);
    let settings = crate::sweep::settings::Settings::of_spec(&s);
    assert_eq!(settings.get("models.ph_over_e"), Some("1e-2"));
    // Without rough cases the keys are errors naming themselves; out of range too.
    let e = err("contact = \"line\"\n[axes]\nM = [20]\nL = [0]\n[models]\nslide_roll = 0.5\n");
    assert_eq!((e.line, e.key.as_str()), (6, "models.slide_roll"));
    assert!(e.message.contains("sigma"), "{e}");
    let e = err(
        "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\nsigma = [0, 1]\n[models]\nph_over_e = 2\n",
    );
    assert_eq!(e.key, "models.ph_over_e");
    // A smooth spec's settings hold no roughness key.
    let plain = parse(
        "t.toml",
        "contact = \"line\"\n[axes]\nM = [20]\nL = [0]\n",
        "t",
    )
    .unwrap();
    assert!(crate::sweep::settings::Settings::of_spec(&plain)
        .get("models.slide_roll")
        .is_none());
}
