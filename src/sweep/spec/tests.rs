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
    let e = err("contact = \"point\"\n[axes]\nM = [5]\nL = [0]\nD = [0.5]\n");
    assert!(e.message.contains("not available in this build") && e.line == 1);
    let e = err("contact = \"point\"\n[axes]\nM = [5]\nL = [0]\nD = [1.5]\n");
    assert_eq!((e.line, e.key.as_str()), (5, "axes.D"));
    let e = err("contact = \"line\"\n[axes]\nM = { from = 0, to = 10, count = 3, scale = \"log\" }\nL = [0]\n");
    assert_eq!(e.line, 3);
    let e = err("contact = \"line\"\n[axes]\nM = [1]\nL = [0]\n[numerics]\ngrid = 8\n");
    assert_eq!((e.line, e.key.as_str()), (6, "numerics.grid"));
    let e = err("contact = \"line\"\n[axes]\nM = [1\n");
    assert!(e.message.contains("invalid TOML") && e.line >= 3, "{e}");
}
