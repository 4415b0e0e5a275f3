//! Bad input through the binary, table-driven: command-line values out of range, malformed or
//! missing, options the command would ignore, bad case files (numbers, units, unknown and
//! missing keys), bad sweep specs, bad fit directories, outputs that cannot be written and
//! grids that do not fit in memory. Each row asserts the exit code of the table in docs/cli.md
//! (2 bad input, 1 I/O error), that stderr is one line `ehlmap: ...` naming the offending input,
//! and that nothing panicked or aborted. Every row is refused before any solve, so the whole
//! table runs in seconds.

use std::path::{Path, PathBuf};
use std::process::{Command, Output, Stdio};

/// Environment variables that change what a command does; removed unless a row sets them.
const ENV: [&str; 6] = [
    "SLURM_ARRAY_TASK_ID",
    "SLURM_ARRAY_TASK_COUNT",
    "SLURM_ARRAY_TASK_MIN",
    "SLURM_ARRAY_TASK_STEP",
    "SLURM_CPUS_PER_TASK",
    "EHLMAP_MAX_MEMORY",
];

/// One bad input: the command line (`{dir}` is the scratch directory, `{data}` tests/data),
/// environment variables, the expected exit code and a text stderr must contain.
struct Bad {
    cmd: String,
    env: Vec<(&'static str, &'static str)>,
    code: i32,
    needle: &'static str,
}

/// Bad input (exit 2) whose message contains `needle`.
fn input(needle: &'static str, cmd: &str) -> Bad {
    Bad {
        cmd: cmd.to_string(),
        env: vec![],
        code: 2,
        needle,
    }
}

/// An output that cannot be written (exit 1) whose message contains `needle`.
fn io(needle: &'static str, cmd: &str) -> Bad {
    Bad {
        code: 1,
        ..input(needle, cmd)
    }
}

/// Bad input under environment variables.
fn with_env(env: &[(&'static str, &'static str)], b: Bad) -> Bad {
    Bad {
        env: env.to_vec(),
        ..b
    }
}

/// 100 MB: less than any grid the memory rows ask for.
const SMALL_MEMORY: (&str, &str) = ("EHLMAP_MAX_MEMORY", "100M");

fn scratch() -> PathBuf {
    let d = std::env::temp_dir().join(format!("ehlmap-bad-inputs-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// A line case file (textbook Example 7-1 with distinct body values so that every line is
/// unique for [`edit`]).
const LINE: &str = "contact = \"line\"
load = 3000.0
length = 0.035
u1 = 1.08
u2 = 1.08
eta0 = 0.003
alpha = 2.3e-7
grid = 257

[body1]
radius_x = 0.016
E = 208e9
nu = 0.3
rq = 0.1e-6

[body2]
radius_x = -0.103
E = 207e9
nu = 0.29
rq = 0.2e-6
";

/// A point case file (the ball bearing, with its oil at a temperature).
const POINT: &str = "contact = \"point\"
load = 800.0
u1 = 2.94
u2 = 2.94
grid = 65

[lubricant]
oil = \"ISO VG 68\"
temperature = 70.0

[body1]
radius_x = 3.969e-3
radius_y = 3.969e-3
E = 208e9
nu = 0.3

[body2]
radius_x = 15.53e-3
radius_y = -4.128e-3
E = 207e9
nu = 0.29
";

/// A small valid sweep spec.
const SPEC: &str = "name = \"tiny\"
contact = \"line\"

[axes]
M = [10, 20]
L = [0, 5]

[numerics]
grid = 65
max_cycles = 60
";

/// `base` with the unique line `old` replaced by `new` (empty: removed).
fn edit(base: &str, old: &str, new: &str) -> String {
    let hits = base.lines().filter(|l| *l == old).count();
    assert_eq!(hits, 1, "{old:?} is not one line of the base");
    base.lines()
        .map(|l| if l == old { new } else { l })
        .collect::<Vec<_>>()
        .join("\n")
        + "\n"
}

/// The bad case files, spec files and directories, as (file name, content).
fn files() -> Vec<(&'static str, String)> {
    let l = |old: &str, new: &str| edit(LINE, old, new);
    let p = |old: &str, new: &str| edit(POINT, old, new);
    let s = |old: &str, new: &str| edit(SPEC, old, new);
    vec![
        ("ok-line.toml", LINE.to_string()),
        ("ok-point.toml", POINT.to_string()),
        ("ok-spec.toml", SPEC.to_string()),
        ("syntax.toml", l("load = 3000.0", "load = = 3")),
        ("unknown-key.toml", l("grid = 257", "grid = 257\nflux = 3")),
        (
            "unknown-body-key.toml",
            l("nu = 0.3", "nu = 0.3\npoisson = 0.3"),
        ),
        ("no-load.toml", l("load = 3000.0", "")),
        (
            "no-body1.toml",
            LINE.split("[body1]").next().unwrap().to_string()
                + "[body2]\nradius_x = 0.1\nE = 2e11\nnu = 0.3\n",
        ),
        ("no-E.toml", l("E = 208e9", "")),
        ("no-u2.toml", l("u2 = 1.08", "")),
        ("load-units.toml", l("load = 3000.0", "load = \"3 kN\"")),
        ("load-neg.toml", l("load = 3000.0", "load = -1.0")),
        ("load-zero.toml", l("load = 3000.0", "load = 0.0")),
        ("load-nan.toml", l("load = 3000.0", "load = nan")),
        ("load-inf.toml", l("load = 3000.0", "load = inf")),
        (
            "speed.toml",
            l("u1 = 1.08", "u1 = -1.08").replace("u2 = 1.08", "u2 = 0.0"),
        ),
        ("E-zero.toml", l("E = 208e9", "E = 0.0")),
        ("E-units.toml", l("E = 208e9", "E = \"208 GPa\"")),
        ("nu-half.toml", l("nu = 0.3", "nu = 0.5")),
        ("nu-minus.toml", l("nu = 0.29", "nu = -1.0")),
        ("radius-zero.toml", l("radius_x = 0.016", "radius_x = 0.0")),
        ("concave.toml", l("radius_x = -0.103", "radius_x = -0.01")),
        ("rq-neg.toml", l("rq = 0.1e-6", "rq = -1e-6")),
        ("no-length.toml", l("length = 0.035", "")),
        ("length-zero.toml", l("length = 0.035", "length = 0.0")),
        ("no-eta0.toml", l("eta0 = 0.003", "")),
        ("no-alpha.toml", l("alpha = 2.3e-7", "")),
        ("eta0-neg.toml", l("eta0 = 0.003", "eta0 = -0.003")),
        ("alpha-neg.toml", l("alpha = 2.3e-7", "alpha = -1e-8")),
        (
            "eta0-and-lub.toml",
            l(
                "grid = 257",
                "grid = 257\n[lubricant]\noil = \"ISO VG 68\"\ntemperature = 40.0\n",
            ),
        ),
        ("grid-huge.toml", l("grid = 257", "grid = 2000000")),
        ("grid-small.toml", l("grid = 257", "grid = 5")),
        ("grid-neg.toml", l("grid = 257", "grid = -5")),
        ("grid-float.toml", l("grid = 257", "grid = 257.5")),
        ("grid-max.toml", l("grid = 257", "grid = 1048577")),
        (
            "roelands-z.toml",
            l("grid = 257", "grid = 257\nroelands_z = -1.0"),
        ),
        (
            "roelands-both.toml",
            l(
                "grid = 257",
                "grid = 257\nroelands_z = 0.6\nroelands = true",
            ),
        ),
        (
            "roelands-alpha0.toml",
            l("alpha = 2.3e-7", "alpha = 0.0").replace("grid = 257", "grid = 257\nroelands = true"),
        ),
        (
            "contact.toml",
            l("contact = \"line\"", "contact = \"plane\""),
        ),
        (
            "radius-y-line.toml",
            l("radius_x = 0.016", "radius_x = 0.016\nradius_y = 0.02"),
        ),
        (
            "temp-hot.toml",
            p("temperature = 70.0", "temperature = 1e6"),
        ),
        (
            "temp-cold.toml",
            p("temperature = 70.0", "temperature = -300.0"),
        ),
        ("temp-missing.toml", p("temperature = 70.0", "")),
        (
            "temp-units.toml",
            p("temperature = 70.0", "temperature = \"70 C\""),
        ),
        ("oil.toml", p("oil = \"ISO VG 68\"", "oil = \"VG 9\"")),
        (
            "nu40.toml",
            p(
                "oil = \"ISO VG 68\"",
                "nu40 = 10.0\nnu100 = 20.0\ndensity = 870.0\nalpha = 2e-8",
            ),
        ),
        (
            "no-density.toml",
            p(
                "oil = \"ISO VG 68\"",
                "nu40 = 68.0\nnu100 = 8.7\nalpha = 2e-8",
            ),
        ),
        (
            "lub-key.toml",
            p(
                "oil = \"ISO VG 68\"",
                "oil = \"ISO VG 68\"\nviscosity = 3.0",
            ),
        ),
        (
            "point-length.toml",
            p("load = 800.0", "load = 800.0\nlength = 0.01"),
        ),
        (
            "point-d.toml",
            p("radius_y = -4.128e-3", "radius_y = 1e-3")
                .replace("radius_y = 3.969e-3", "radius_y = 1e-3"),
        ),
        (
            "point-ry-zero.toml",
            p("radius_y = 3.969e-3", "radius_y = 0.0"),
        ),
        (
            "point-cylinders.toml",
            p("radius_y = 3.969e-3", "").replace("radius_y = -4.128e-3", ""),
        ),
        ("point-grid.toml", p("grid = 65", "grid = 4097")),
        ("point-grid-max.toml", p("grid = 65", "grid = 2049")),
        ("spec-syntax.toml", s("name = \"tiny\"", "name = tiny")),
        (
            "spec-key.toml",
            s("name = \"tiny\"", "name = \"tiny\"\ncolour = 3"),
        ),
        ("spec-m.toml", s("M = [10, 20]", "M = [-1, 20]")),
        ("spec-m-units.toml", s("M = [10, 20]", "M = [\"10 N\"]")),
        (
            "spec-l.toml",
            s("L = [0, 5]", "L = { from = 0, to = 5, count = 0 }"),
        ),
        ("spec-grid.toml", s("grid = 65", "grid = 2000000")),
        ("spec-grid-max.toml", s("grid = 65", "grid = 1048577")),
        ("spec-cycles.toml", s("max_cycles = 60", "max_cycles = 0")),
        (
            "spec-ph.toml",
            s("max_cycles = 60", "max_cycles = 60\n[models]\nph = 1e9"),
        ),
        (
            "spec-point.toml",
            s("contact = \"line\"", "contact = \"point\""),
        ),
        (
            "spec-contact.toml",
            s("contact = \"line\"", "contact = \"plane\""),
        ),
        (
            "not-parquet/part-1of1-0001.parquet",
            "not a parquet file".to_string(),
        ),
        ("empty-dataset/.keep", String::new()),
        ("a-file", "a regular file".to_string()),
        (
            "anchors-elsewhere.json",
            r#"{"factor": 3.1622776601683795, "grids": [513, 1025, 2049], "anchors": [
                {"m": 3162.2776601683795, "d": 0.5, "h_c": 0.9, "h_c_error_bar": 0.001,
                 "h_pm": 0.9, "h_pm_error_bar": 0.001, "wall_s": 1.0}]}"#
                .to_string(),
        ),
    ]
}

/// The bad inputs.
fn table() -> Vec<Bad> {
    let sm = |b: Bad| with_env(&[SMALL_MEMORY], b);
    vec![
        // ---- solve: values
        input("M = 0", "solve --M 0"),
        input("M = -3", "solve --M -3 --L 1"),
        input("M = NaN", "solve --M NaN"),
        input("M = inf", "solve --M inf"),
        input("M = -1e-300", "solve --M -1e-300"),
        input("--M", "solve --M x"),
        input("--M", "solve --M"),
        input("--M", "solve --L 3"),
        input("L = -1", "solve --M 20 --L -1"),
        input("L = NaN", "solve --M 20 --L NaN"),
        input("L = inf", "solve --M 20 --L 1e400"),
        input("--L", "solve --M 20 --L ten"),
        input("--grid 9", "solve --M 20 --grid 9"),
        input("--time-limit 0", "solve --M 20 --time-limit 0"),
        input("--truncated-domain", "solve --M 20 --truncated-domain"),
        input(
            "--truncated-domain",
            "stability --truncated-domain --out {dir}/st",
        ),
        input("--time-limit -2", "solve --M 20 --time-limit -2"),
        input("--time-limit inf", "solve --M 20 --time-limit inf"),
        input("--time-limit", "solve --M 20 --time-limit soon"),
        input("--grid 2000000", "solve --M 20 --grid 2000000"),
        input("--grid", "solve --M 20 --grid -5"),
        input("--grid", "solve --M 20 --grid 1e3"),
        input(
            "--grid 4097",
            "solve --contact point --D 0.5 --M 20 --grid 4097",
        ),
        input("--grid 9", "solve --contact point --D 0.5 --M 20 --grid 9"),
        // (--contact point without --D is a circular contact, not an error)
        input("D = inf", "solve --contact point --D inf --M 20"),
        input("D = 0", "solve --contact point --D 0 --M 20"),
        input("D = 1.5", "solve --contact point --D 1.5 --M 20"),
        input("D = NaN", "solve --contact point --D NaN --M 20"),
        input("D = -0.2", "solve --contact point --D -0.2 --M 20"),
        input("--D", "solve --M 20 --D 0.5"),
        input("--contact", "solve --contact plane --M 20"),
        input("--viscosity", "solve --M 20 --viscosity foo"),
        input("--density", "solve --M 20 --density water"),
        input("--elasticity", "solve --M 20 --elasticity soft"),
        input("--method", "solve --M 20 --method magic"),
        input("--cycle", "solve --M 20 --cycle x"),
        input("--unknown-flag", "solve --M 20 --unknown-flag"),
        // ---- solve: models
        input("--ph", "solve --M 20 --viscosity roelands --z 0.6"),
        input("--eta0", "solve --M 20 --viscosity roelands --ph 1e9"),
        input(
            "--eta0",
            "solve --M 20 --viscosity roelands --ph 1e9 --eta0 0.05 --z 0.6",
        ),
        input(
            "--eta0 1e300",
            "solve --M 20 --viscosity roelands --ph 1e9 --eta0 1e300",
        ),
        input(
            "eta0 = -1",
            "solve --M 20 --viscosity roelands --ph 1e9 --eta0 -1",
        ),
        input(
            "eta0 = 0.000001",
            "solve --M 20 --L 3 --viscosity roelands --ph 1e9 --eta0 1e-6",
        ),
        input(
            "z = -1",
            "solve --M 20 --viscosity roelands --ph 1e9 --z -1",
        ),
        input("z = 0", "solve --M 20 --viscosity roelands --ph 1e9 --z 0"),
        input(
            "ph = -1",
            "solve --M 20 --viscosity roelands --ph -1 --z 0.6",
        ),
        input(
            "ph = NaN",
            "solve --M 20 --viscosity roelands --ph NaN --z 0.6",
        ),
        input("--ph", "solve --M 20 --density dowson-higginson"),
        input("ph = 0", "solve --M 20 --density dowson-higginson --ph 0"),
        input("--eta0", "solve --M 20 --eta0 0.05"),
        input("--z", "solve --M 20 --z 0.6"),
        input("--ph", "solve --M 20 --ph 1e9"),
        // ---- solve: options the method, contact or target would ignore
        input("--grid 8193", "solve --M 20 --method newton --grid 8193"),
        input(
            "--grid 33",
            "solve --contact point --D 0.5 --M 20 --method newton",
        ),
        input("--cycle", "solve --M 20 --method newton --cycle w"),
        input(
            "--max-cycles",
            "solve --M 20 --method relax --max-cycles 10",
        ),
        input(
            "--no-fallback",
            "solve --M 20 --method newton --no-fallback",
        ),
        input("--accuracy", "solve --M 20 --method relax --accuracy 0.01"),
        input("--trace", "solve --M 20 --method newton --trace"),
        input(
            "--threads",
            "solve --contact point --D 1 --M 20 --grid 33 --method newton --threads 2",
        ),
        input("--accuracy 0", "solve --M 20 --accuracy 0"),
        input("--accuracy 1.5", "solve --M 20 --accuracy 1.5"),
        input("--accuracy NaN", "solve --M 20 --accuracy NaN"),
        input("--accuracy -0.1", "solve --M 20 --accuracy -0.1"),
        input("--full-model", "solve --M 20 --grid 513 --full-model"),
        input("--accuracy", "solve --M 20 --grid 513 --accuracy 0.01"),
        input("--no-estimate", "solve --M 20 --no-estimate"),
        input("--max-grid", "solve --M 20 --method newton --max-grid 1025"),
        input("--max-grid", "solve --M 20 --max-grid 0"),
        input("--max-grid 0", "solve --M 20 --accuracy 0.01 --max-grid 0"),
        input(
            "--max-grid 257",
            "solve --M 20 --accuracy 0.01 --max-grid 257",
        ),
        input(
            "--max-grid 2000000",
            "solve --M 20 --accuracy 0.01 --max-grid 2000000",
        ),
        input(
            "--max-grid 4097",
            "solve --contact point --D 1 --M 20 --accuracy 0.01 --max-grid 4097",
        ),
        input("--grid 1025", "solve --M 20 --accuracy 0.01 --grid 1025"),
        input("--max-cycles 0", "solve --M 20 --max-cycles 0"),
        input("--max-cycles 1000001", "solve --M 20 --max-cycles 1000001"),
        input("--max-cycles", "solve --M 20 --max-cycles -1"),
        input("--threads 0", "solve --M 20 --threads 0"),
        input("--threads 2", "solve --M 20 --threads 2"),
        input(
            "--threads 0",
            "solve --contact point --D 1 --M 20 --threads 0",
        ),
        input(
            "--threads 100000",
            "solve --contact point --D 1 --M 20 --threads 100000",
        ),
        input(
            "--profile",
            "solve --contact point --D 0.5 --M 20 --profile {dir}/p.parquet",
        ),
        input("--fields", "solve --M 20 --fields {dir}/f.parquet"),
        // ---- solve: outputs and memory
        io(
            "--profile",
            "solve --M 20 --grid 65 --profile /proc/nope/p.parquet",
        ),
        io(
            "--profile",
            "solve --M 20 --grid 65 --profile /dev/null/p.parquet",
        ),
        io("--profile", "solve --M 20 --grid 65 --profile {dir}"),
        io(
            "--fields",
            "solve --contact point --D 1 --M 20 --grid 33 --fields /proc/nope/f.parquet",
        ),
        io("--plot", "solve --M 20 --grid 65 --plot /proc/plots"),
        io("--plot", "solve --M 20 --grid 65 --plot {dir}/a-file"),
        io("--plot", "solve --M 20 --grid 65 --plot /dev/null/plots"),
        sm(input("--grid 1048577", "solve --M 20 --grid 1048577")),
        sm(input(
            "--grid 2049",
            "solve --contact point --D 1 --M 20 --grid 2049",
        )),
        sm(input(
            "--max-grid 1048577",
            "solve --M 20 --accuracy 0.01 --max-grid 1048577",
        )),
        with_env(
            &[("EHLMAP_MAX_MEMORY", "banana")],
            input("EHLMAP_MAX_MEMORY", "solve --M 20 --grid 65"),
        ),
        // ---- case: files
        input("nofile.toml", "case {dir}/nofile.toml"),
        input("empty-dataset", "case {dir}/empty-dataset"),
        input("syntax.toml:2", "case {dir}/syntax.toml"),
        input("flux", "case {dir}/unknown-key.toml"),
        input("poisson", "case {dir}/unknown-body-key.toml"),
        input("load", "case {dir}/no-load.toml"),
        input("body1", "case {dir}/no-body1.toml"),
        input("`E`", "case {dir}/no-E.toml"),
        input("u2", "case {dir}/no-u2.toml"),
        input("load = \"3 kN\"", "case {dir}/load-units.toml"),
        input("load = -1", "case {dir}/load-neg.toml"),
        input("load = 0", "case {dir}/load-zero.toml"),
        input("load = NaN", "case {dir}/load-nan.toml"),
        input("load = inf", "case {dir}/load-inf.toml"),
        input("u1 + u2", "case {dir}/speed.toml"),
        input("body1.E = 0", "case {dir}/E-zero.toml"),
        input("E = \"208 GPa\"", "case {dir}/E-units.toml"),
        input("body1.nu = 0.5", "case {dir}/nu-half.toml"),
        input("body2.nu = -1", "case {dir}/nu-minus.toml"),
        input("body1.radius_x = 0", "case {dir}/radius-zero.toml"),
        input("1/R1 + 1/R2", "case {dir}/concave.toml"),
        input("body1.rq", "case {dir}/rq-neg.toml"),
        input("length", "case {dir}/no-length.toml"),
        input("length = 0", "case {dir}/length-zero.toml"),
        input("eta0", "case {dir}/no-eta0.toml"),
        input("alpha", "case {dir}/no-alpha.toml"),
        input("eta0 = -0.003", "case {dir}/eta0-neg.toml"),
        input("alpha = -0.00000001", "case {dir}/alpha-neg.toml"),
        input("[lubricant]", "case {dir}/eta0-and-lub.toml"),
        input("grid = 2000000", "case {dir}/grid-huge.toml"),
        input("--time-limit 0", "case {dir}/ok-line.toml --time-limit 0"),
        input(
            "--time-limit NaN",
            "case {dir}/ok-point.toml --time-limit NaN",
        ),
        input("grid = 2000000", "case {dir}/grid-huge.toml --no-solve"),
        input("grid = 5", "case {dir}/grid-small.toml"),
        input("grid = -5", "case {dir}/grid-neg.toml"),
        input("grid = 257.5", "case {dir}/grid-float.toml"),
        sm(input("grid = 1048577", "case {dir}/grid-max.toml")),
        sm(input("grid = 2049", "case {dir}/point-grid-max.toml")),
        input("roelands_z = -1", "case {dir}/roelands-z.toml"),
        input("roelands_z", "case {dir}/roelands-both.toml"),
        input("eta0 = 0.003 gives", "case {dir}/roelands-alpha0.toml"),
        input("contact = \"plane\"", "case {dir}/contact.toml"),
        input("body1.radius_y", "case {dir}/radius-y-line.toml"),
        input(
            "lubricant.temperature = 1000000",
            "case {dir}/temp-hot.toml",
        ),
        input("lubricant.temperature = -300", "case {dir}/temp-cold.toml"),
        input("temperature", "case {dir}/temp-missing.toml"),
        input("temperature = \"70 C\"", "case {dir}/temp-units.toml"),
        input("lubricant.oil", "case {dir}/oil.toml"),
        input("lubricant.nu40/nu100", "case {dir}/nu40.toml"),
        input("lubricant.density", "case {dir}/no-density.toml"),
        input("viscosity", "case {dir}/lub-key.toml"),
        input("length", "case {dir}/point-length.toml"),
        input("D = Rx/Ry", "case {dir}/point-d.toml"),
        input("body1.radius_y = 0", "case {dir}/point-ry-zero.toml"),
        input("1/Ry1 + 1/Ry2", "case {dir}/point-cylinders.toml"),
        input("grid = 4097", "case {dir}/point-grid.toml"),
        input(
            "--plot",
            "case {dir}/ok-line.toml --no-solve --plot {dir}/plots",
        ),
        io("--plot", "case {dir}/ok-line.toml --plot /proc/plots"),
        // ---- sweep
        input("nofile.toml", "sweep {dir}/nofile.toml"),
        input("spec-syntax.toml:1", "sweep {dir}/spec-syntax.toml"),
        input("colour", "sweep {dir}/spec-key.toml"),
        input("axes.M", "sweep {dir}/spec-m.toml"),
        input("axes.M", "sweep {dir}/spec-m-units.toml"),
        input("axes.L", "sweep {dir}/spec-l.toml"),
        input("numerics.grid", "sweep {dir}/spec-grid.toml"),
        input("numerics.max_cycles", "sweep {dir}/spec-cycles.toml"),
        input("models.ph", "sweep {dir}/spec-ph.toml"),
        input("D", "sweep {dir}/spec-point.toml"),
        input("contact", "sweep {dir}/spec-contact.toml"),
        input(
            "--shard 0/4",
            "sweep {dir}/ok-spec.toml --shard 0/4 --dry-run",
        ),
        input(
            "--shard 5/4",
            "sweep {dir}/ok-spec.toml --shard 5/4 --dry-run",
        ),
        input(
            "--shard abc",
            "sweep {dir}/ok-spec.toml --shard abc --dry-run",
        ),
        input("--threads", "sweep {dir}/ok-spec.toml --threads 0"),
        input("--threads", "sweep {dir}/ok-spec.toml --threads 5000"),
        input(
            "--resume",
            "sweep {dir}/ok-spec.toml --resume --out {dir}/sweeps",
        ),
        input("--progress", "sweep {dir}/ok-spec.toml --progress loud"),
        io(
            "--out /dev/null",
            "sweep {dir}/ok-spec.toml --out /dev/null",
        ),
        io("--out", "sweep {dir}/ok-spec.toml --out {dir}/a-file"),
        io("--out", "sweep {dir}/ok-spec.toml --out /proc/sweeps"),
        io(
            "--out",
            "sweep {dir}/ok-spec.toml --out /dev/null --dry-run",
        ),
        with_env(
            &[("SLURM_ARRAY_TASK_ID", "3")],
            input(
                "SLURM_ARRAY_TASK_COUNT",
                "sweep {dir}/ok-spec.toml --dry-run",
            ),
        ),
        with_env(
            &[
                ("SLURM_ARRAY_TASK_ID", "x"),
                ("SLURM_ARRAY_TASK_COUNT", "4"),
            ],
            input("SLURM_ARRAY_TASK_ID", "sweep {dir}/ok-spec.toml --dry-run"),
        ),
        with_env(
            &[("SLURM_CPUS_PER_TASK", "0")],
            input(
                "SLURM_CPUS_PER_TASK",
                "sweep {dir}/ok-spec.toml --out {dir}/sweeps",
            ),
        ),
        sm(input(
            "numerics.grid = 1048577",
            "sweep {dir}/spec-grid-max.toml --out {dir}/sweeps --threads 1",
        )),
        // ---- fit
        input("nodir", "fit {dir}/nodir"),
        input("a-file", "fit {dir}/a-file"),
        input("empty-dataset", "fit {dir}/empty-dataset"),
        input("part-1of1-0001.parquet", "fit {dir}/not-parquet"),
        input("<DATASETS>", "fit"),
        input(
            "--jump",
            "fit {data}/smoke-line --no-limit-solves --jump {dir}/a-file",
        ),
        input(
            "--jump",
            "fit {data}/smoke-line --no-limit-solves --jump {dir}/missing.json",
        ),
        input(
            "no solved point cases",
            "fit {data}/smoke-line --no-limit-solves --jump-solves {dir}/j.json --out {dir}/r",
        ),
        input(
            "--anchors",
            "fit {data}/point-257 --no-limit-solves --anchors {dir}/a-file --out {dir}/r",
        ),
        input(
            "not those of these data",
            "fit {data}/point-257 --no-limit-solves --anchors {dir}/anchors-elsewhere.json \
             --out {dir}/r",
        ),
        input(
            "no point case at L = 0, M >= 100",
            "fit {data}/smoke-line --no-limit-solves --anchor-solves {dir}/a.json --out {dir}/r",
        ),
        input(
            "--out",
            "fit {data}/smoke-line --out {data}/smoke-line --no-limit-solves",
        ),
        io(
            "--out",
            "fit {data}/smoke-line --out /proc/report --no-limit-solves",
        ),
        io(
            "--out",
            "fit {data}/smoke-line --out {dir}/a-file --no-limit-solves",
        ),
        input(
            "--check: ",
            "fit {data}/smoke-line --check {data}/smoke-line --out {dir}/fc --no-limit-solves",
        ),
        input(
            "--check: ",
            "fit {data}/smoke-line --check {dir}/nodir --out {dir}/fc",
        ),
        // ---- a formula as the model
        input(
            "cannot read it",
            "solve --M 20 --formula {dir}/nodir/fit.json",
        ),
        input(
            "not a fit report",
            "solve --M 20 --formula {dir}/ok-spec.toml",
        ),
        input(
            "--formula applies to the accuracy ladder",
            "solve --M 20 --grid 257 --formula x",
        ),
        input(
            "--formula and --full-model",
            "solve --M 20 --full-model --formula x",
        ),
        input(
            "not a fit report",
            "case {dir}/ok-line.toml --formula {dir}/ok-spec.toml",
        ),
        input(
            "not a fit report",
            "sweep {dir}/ok-spec.toml --formula {dir}/ok-spec.toml",
        ),
        // ---- bench and stability
        input("--repeats 0", "bench --quick --repeats 0 --out {dir}/bench"),
        input("--repeats", "bench --repeats -1 --out {dir}/bench"),
        input("--accuracy 0.01", "bench --accuracy 0.01 --out {dir}/bench"),
        input(
            "--quick",
            "bench --selection {dir}/ok-spec.toml --quick --out {dir}/bench",
        ),
        input(
            "--repeats",
            "bench --selection {dir}/ok-spec.toml --repeats 2 --out {dir}/bench",
        ),
        input(
            "--accuracy 2",
            "bench --selection {dir}/ok-spec.toml --accuracy 2 --out {dir}/bench",
        ),
        input(
            "--selection",
            "bench --selection {dir}/nofile.toml --out {dir}/bench",
        ),
        sm(input(
            "numerics.grid",
            "bench --selection {dir}/spec-grid-max.toml --out {dir}/bench",
        )),
        io("--out", "bench --quick --out /proc/bench"),
        io(
            "--out",
            "bench --selection {dir}/ok-spec.toml --out {dir}/a-file",
        ),
        input("--grid 5", "stability --grid 5 --out {dir}/st"),
        input("--grid 2000000", "stability --grid 2000000 --out {dir}/st"),
        input("--point-D 0", "stability --point-D 0 --out {dir}/st"),
        input("--point-D NaN", "stability --point-D NaN --out {dir}/st"),
        input(
            "--grid 2049",
            "stability --point-D 0.5 --grid 2049 --out {dir}/st",
        ),
        sm(input(
            "--grid 1048577",
            "stability --grid 1048577 --out {dir}/st",
        )),
        io("--out", "stability --quick --out /proc/st"),
        // ---- chart
        input("circles", "chart circles"),
        input("--D 0", "chart regimes --D 0 --out {dir}/charts"),
        input("--D 2", "chart regimes --D 2 --out {dir}/charts"),
        input("--D NaN", "chart regimes --D NaN --out {dir}/charts"),
        input(
            "nofile.toml",
            "chart regimes --case {dir}/nofile.toml --out {dir}/charts",
        ),
        input(
            "flux",
            "chart regimes --case {dir}/unknown-key.toml --out {dir}/charts",
        ),
        input(
            "--D",
            "chart regimes --case {dir}/ok-point.toml --D 0.3 --out {dir}/charts",
        ),
        input(
            "--D",
            "chart regimes --case {dir}/ok-line.toml --D 0.5 --out {dir}/charts",
        ),
        io("--out", "chart regimes --out /proc/charts"),
        io("--out", "chart regimes --out {dir}/a-file"),
        // ---- the command itself
        input("frobnicate", "frobnicate"),
        input("--frob", "--frob"),
    ]
}

fn run(b: &Bad, dir: &Path, data: &Path) -> (String, Output) {
    let cmd = b
        .cmd
        .replace("{dir}", dir.to_str().unwrap())
        .replace("{data}", data.to_str().unwrap());
    let mut c = Command::new(env!("CARGO_BIN_EXE_ehlmap"));
    c.args(cmd.split_whitespace()).stdin(Stdio::null());
    for v in ENV {
        c.env_remove(v);
    }
    for (k, v) in &b.env {
        c.env(k, v);
    }
    (cmd, c.output().expect("run ehlmap"))
}

#[test]
fn every_bad_input_is_refused_naming_it() {
    let dir = scratch();
    for (name, text) in files() {
        let p = dir.join(name);
        std::fs::create_dir_all(p.parent().unwrap()).unwrap();
        std::fs::write(p, text).unwrap();
    }
    let data = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/data");
    let table = table();
    assert!(table.len() >= 100, "{} bad inputs", table.len());
    let mut failures = vec![];
    for b in &table {
        let (cmd, o) = run(b, &dir, &data);
        let err = String::from_utf8_lossy(&o.stderr);
        let mut why = vec![];
        if o.status.code() != Some(b.code) {
            why.push(format!("exit {:?}, want {}", o.status.code(), b.code));
        }
        if !err.contains(b.needle) {
            why.push(format!("stderr does not name {:?}", b.needle));
        }
        if err.contains("panicked") || matches!(o.status.code(), Some(101) | Some(134) | None) {
            why.push("panicked or aborted".to_string());
        }
        if err.lines().count() != 1 || !err.starts_with("ehlmap: ") {
            why.push("stderr is not one line `ehlmap: ...`".to_string());
        }
        if !why.is_empty() {
            failures.push(format!(
                "ehlmap {cmd}: {}\n    stderr: {err}",
                why.join("; ")
            ));
        }
    }
    // Nothing was written where outputs were refused or bad input named.
    for out in ["sweeps", "bench", "st", "charts", "plots"] {
        let p = dir.join(out);
        let empty = !p.exists() || std::fs::read_dir(&p).unwrap().next().is_none();
        if !empty {
            failures.push(format!("{} was written", p.display()));
        }
    }
    assert!(
        failures.is_empty(),
        "{} of {} bad inputs:\n{}",
        failures.len(),
        table.len(),
        failures.join("\n")
    );
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn a_full_stdout_is_an_io_error() {
    // Results that cannot be written to stdout (a full disk behind `>`): exit 1 naming stdout.
    let full = std::fs::OpenOptions::new().write(true).open("/dev/full");
    let Ok(full) = full else {
        return; // no /dev/full on this system
    };
    let o = Command::new(env!("CARGO_BIN_EXE_ehlmap"))
        .args(["solve", "--M", "20", "--grid", "65", "--json"])
        .stdout(Stdio::from(full))
        .output()
        .unwrap();
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "{err}");
    assert!(err.starts_with("ehlmap: stdout: "), "{err}");
}
