//! `--plot` pictures and `ehlmap chart regimes`: the files exist and are real PNG/SVG images of
//! non-trivial size (the marching-squares routine is tested on a paraboloid in
//! `pictures::contour`).

use std::path::Path;

mod common;
use common::ehlmap;

fn check_png_svg(dir: &Path, stem: &str) {
    let png = std::fs::read(dir.join(format!("{stem}.png"))).unwrap();
    assert_eq!(&png[..8], b"\x89PNG\r\n\x1a\n", "{stem}.png");
    assert!(png.len() > 20_000, "{stem}.png is {} bytes", png.len());
    let svg = std::fs::read_to_string(dir.join(format!("{stem}.svg"))).unwrap();
    assert!(svg.contains("<svg") && svg.contains("</svg>"), "{stem}.svg");
    assert!(svg.len() > 20_000, "{stem}.svg is {} bytes", svg.len());
}

fn tmp(name: &str) -> std::path::PathBuf {
    std::env::temp_dir().join(format!("ehlmap-pictures-{name}-{}", std::process::id()))
}

#[test]
fn solve_plot_line_and_point() {
    let dir = tmp("solve");
    let d = dir.to_str().unwrap();
    let out = ehlmap(&[
        "solve", "--M", "20", "--L", "10", "--grid", "513", "--plot", d,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    check_png_svg(&dir, "line-M20-L10-profile");
    let out = ehlmap(&[
        "solve",
        "--contact",
        "point",
        "--M",
        "20",
        "--L",
        "10",
        "--D",
        "0.5",
        "--grid",
        "65",
        "--plot",
        d,
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for s in ["profile", "film", "pressure"] {
        check_png_svg(&dir, &format!("point-M20-L10-D0.5-{s}"));
    }
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn case_plot_and_regime_chart() {
    let dir = tmp("case");
    let d = dir.to_str().unwrap();
    let case = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/sweeps/cases/ball-bearing.toml"
    );
    let out = ehlmap(&["case", case, "--plot", d]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    for s in ["profile", "film", "pressure"] {
        check_png_svg(&dir, &format!("ball-bearing-{s}"));
    }
    let out = ehlmap(&["chart", "regimes", "--out", d]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    check_png_svg(&dir, "regimes");
    let out = ehlmap(&["chart", "regimes", "--out", d, "--case", case]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let listed = String::from_utf8_lossy(&out.stdout);
    assert!(listed.contains("regimes-D0.03"), "{listed}");
    // a bad D exits with code 2 naming it
    let out = ehlmap(&["chart", "regimes", "--out", d, "--D", "1.5"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&out.stderr).contains("--D"));
    std::fs::remove_dir_all(&dir).ok();
}
