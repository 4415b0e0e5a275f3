//! The file layout of a sweep dataset, defined once: [`COLUMNS`] lists every column in file
//! order with its name, the schema version that introduced it and its [`Access`] (Arrow type,
//! nullability, and how the value is taken from and put into a [`CaseRow`]). The writer, the
//! reader and [`schema`] are driven by this table alone, so adding a column is one entry (plus
//! the field of [`CaseRow`]).
//!
//! Named values (contact, elasticity, cycle, model, status) are stored as their `as_str` names
//! and parsed back with `FromStr`; an unknown name is an error of the setter, carrying the
//! parser's message.

use crate::model::error::ParamError;
use crate::store::results::row::CaseRow;
use arrow_schema::{DataType, Field, Schema};
use std::str::FromStr;
use std::sync::Arc;

/// Version of the row layout, stored in the footer as `ehlmap_schema`; no [`Column::since`] is
/// larger. Schema 2 added `accuracy`, `model_used`, `level`, `error_estimate` (a float) and
/// `warm_start`, and renamed schema 1's boolean `error_estimate` to `half_grid_estimate`.
/// Schema 3 added `converge` (the stopping rule) and `algebraic_error`. Schema 4 added the
/// rough-surface inputs (`sigma`, `gamma`, `slide_roll`) and outputs (`Lambda`, `Lambda_c`,
/// `asperity_load_fraction`, `P_asperity_max`, `H_c_smooth`, `H_min_smooth`,
/// `mixed_iterations`), all null for smooth surfaces. Schema 5 added `far_field` (false in the
/// rows of older files, whose point domains had P = 0 on the boundary). Schema 6 added
/// `H_c_pmax_err` and `P_max_err` (null in the rows of older files). Schema 7 added the point
/// contacts' centre-line minimum film `H_min_cl`, `X_min_cl` and `H_min_cl_err` (null for line
/// contacts and in the rows of older files).
pub const SCHEMA_VERSION: u32 = 7;

/// How one column's values are taken from a row (`get`) and put into one (`set`). The variant
/// fixes the Arrow type (Utf8, Float64, Int64, Boolean) and the nullability (`Opt*` columns are
/// nullable, the others not).
#[derive(Clone, Copy)]
pub enum Access {
    /// A required string; `set` fails on a name its field does not know.
    Str {
        /// The value of a row.
        get: fn(&CaseRow) -> &str,
        /// Store a value read from a file; `Err` says why it is not understood.
        set: fn(&mut CaseRow, &str) -> Result<(), ParamError>,
    },
    /// A nullable string.
    OptStr {
        /// The value of a row.
        get: fn(&CaseRow) -> Option<&str>,
        /// Store a value read from a file.
        set: fn(&mut CaseRow, Option<&str>),
    },
    /// A required float (never written when not finite).
    F64 {
        /// The value of a row.
        get: fn(&CaseRow) -> f64,
        /// Store a value read from a file.
        set: fn(&mut CaseRow, f64),
    },
    /// A nullable float (a non-finite value is written as null).
    OptF64 {
        /// The value of a row.
        get: fn(&CaseRow) -> Option<f64>,
        /// Store a value read from a file.
        set: fn(&mut CaseRow, Option<f64>),
    },
    /// A required integer.
    I64 {
        /// The value of a row.
        get: fn(&CaseRow) -> i64,
        /// Store a value read from a file.
        set: fn(&mut CaseRow, i64),
    },
    /// A nullable integer.
    OptI64 {
        /// The value of a row.
        get: fn(&CaseRow) -> Option<i64>,
        /// Store a value read from a file.
        set: fn(&mut CaseRow, Option<i64>),
    },
    /// A required boolean.
    Bool {
        /// The value of a row.
        get: fn(&CaseRow) -> bool,
        /// Store a value read from a file.
        set: fn(&mut CaseRow, bool),
    },
}

impl Access {
    /// The Arrow type of the column.
    pub fn data_type(&self) -> DataType {
        match self {
            Access::Str { .. } | Access::OptStr { .. } => DataType::Utf8,
            Access::F64 { .. } | Access::OptF64 { .. } => DataType::Float64,
            Access::I64 { .. } | Access::OptI64 { .. } => DataType::Int64,
            Access::Bool { .. } => DataType::Boolean,
        }
    }

    /// Whether the column may hold nulls.
    pub fn nullable(&self) -> bool {
        matches!(
            self,
            Access::OptStr { .. } | Access::OptF64 { .. } | Access::OptI64 { .. }
        )
    }
}

/// One column of the dataset layout.
#[derive(Clone, Copy)]
pub struct Column {
    /// The column name in the file.
    pub name: &'static str,
    /// The schema version that introduced the column: files of an older schema lack it, and the
    /// reader leaves the row's [`Default`] value.
    pub since: u32,
    /// Type, nullability and the row field.
    pub access: Access,
}

impl Column {
    /// The Arrow field of the column.
    pub fn field(&self) -> Field {
        Field::new(self.name, self.access.data_type(), self.access.nullable())
    }
}

/// `s` parsed as a named value (contact, model, status ...).
fn parse<T: FromStr<Err = ParamError>>(s: &str) -> Result<T, ParamError> {
    s.parse()
}

/// The [`Access`] of a row field by kind: `str` (a `String`), `name` (a type with `as_str` and
/// `FromStr`), `opt_str`, `f64`, `opt_f64`, `i64`, `opt_i64`, `bool`.
macro_rules! access {
    (str, $f:ident) => {
        Access::Str {
            get: |r| &r.$f,
            set: |r, v| {
                r.$f = v.to_string();
                Ok(())
            },
        }
    };
    (name, $f:ident) => {
        Access::Str {
            get: |r| r.$f.as_str(),
            set: |r, v| {
                r.$f = parse(v)?;
                Ok(())
            },
        }
    };
    (opt_str, $f:ident) => {
        Access::OptStr {
            get: |r| r.$f.as_deref(),
            set: |r, v| r.$f = v.map(str::to_string),
        }
    };
    (f64, $f:ident) => {
        Access::F64 {
            get: |r| r.$f,
            set: |r, v| r.$f = v,
        }
    };
    (opt_f64, $f:ident) => {
        Access::OptF64 {
            get: |r| r.$f,
            set: |r, v| r.$f = v,
        }
    };
    (i64, $f:ident) => {
        Access::I64 {
            get: |r| r.$f,
            set: |r, v| r.$f = v,
        }
    };
    (opt_i64, $f:ident) => {
        Access::OptI64 {
            get: |r| r.$f,
            set: |r, v| r.$f = v,
        }
    };
    (bool, $f:ident) => {
        Access::Bool {
            get: |r| r.$f,
            set: |r, v| r.$f = v,
        }
    };
}

/// A [`Column`]: `col!(name, kind, field)` (in every schema) or `col!(name, kind, field, since)`.
macro_rules! col {
    ($name:literal, $kind:ident, $f:ident) => {
        col!($name, $kind, $f, 1)
    };
    ($name:literal, $kind:ident, $f:ident, $since:literal) => {
        Column {
            name: $name,
            since: $since,
            access: access!($kind, $f),
        }
    };
}

/// Every column of a dataset file, in file order (documented in `docs/dataset-schema.md`).
pub static COLUMNS: &[Column] = &[
    col!("case_id", str, case_id),
    col!("sweep", str, sweep),
    col!("contact", name, contact),
    col!("M", f64, m),
    col!("L", f64, l),
    col!("D", opt_f64, d),
    col!("k", opt_f64, k),
    col!("elasticity", name, elasticity),
    col!("viscosity", str, viscosity),
    col!("density", str, density),
    col!("z", opt_f64, z),
    col!("eta0", opt_f64, eta0),
    col!("ph", opt_f64, ph),
    col!("sigma", opt_f64, sigma, 4),
    col!("gamma", opt_f64, gamma, 4),
    col!("slide_roll", opt_f64, slide_roll, 4),
    col!("grid_requested", i64, grid_requested),
    col!("cycle", name, cycle),
    col!("max_cycles", i64, max_cycles),
    col!("fallback", bool, fallback),
    col!("tol_load", f64, tol_load),
    col!("tol_h", f64, tol_h),
    col!("converge", name, converge, 3),
    col!("half_grid_estimate", bool, half_grid_estimate),
    col!("accuracy", opt_f64, accuracy, 2),
    col!("far_field", bool, far_field, 5),
    col!("model_used", name, model_used, 2),
    col!("level", opt_i64, level, 2),
    col!("error_estimate", opt_f64, error_estimate, 2),
    col!("algebraic_error", opt_f64, algebraic_error, 3),
    col!("warm_start", opt_str, warm_start, 2),
    col!("grid", opt_i64, grid),
    col!("levels", opt_i64, levels),
    col!("H_c", opt_f64, h_c),
    col!("H_c_pmax", opt_f64, h_c_pmax),
    col!("H_min", opt_f64, h_min),
    col!("X_min", opt_f64, x_min),
    col!("Y_min", opt_f64, y_min),
    col!("H_min_cl", opt_f64, h_min_cl, 7),
    col!("X_min_cl", opt_f64, x_min_cl, 7),
    col!("P_max", opt_f64, p_max),
    col!("spike_X", opt_f64, spike_x),
    col!("spike_P", opt_f64, spike_p),
    col!("H0", opt_f64, h0),
    col!("f", opt_f64, f),
    col!("load_error", opt_f64, load_error),
    col!("H_c_err", opt_f64, h_c_err),
    col!("H_min_err", opt_f64, h_min_err),
    col!("H_c_pmax_err", opt_f64, h_c_pmax_err, 6),
    col!("P_max_err", opt_f64, p_max_err, 6),
    col!("H_min_cl_err", opt_f64, h_min_cl_err, 7),
    col!("Lambda", opt_f64, lambda_min, 4),
    col!("Lambda_c", opt_f64, lambda_c, 4),
    col!("asperity_load_fraction", opt_f64, asperity_load_fraction, 4),
    col!("P_asperity_max", opt_f64, p_asperity_max, 4),
    col!("H_c_smooth", opt_f64, h_c_smooth, 4),
    col!("H_min_smooth", opt_f64, h_min_smooth, 4),
    col!("mixed_iterations", opt_i64, mixed_iterations, 4),
    col!("status", name, status),
    col!("reason", str, reason),
    col!("attempt", opt_i64, attempt),
    col!("work_units", opt_f64, work_units),
    col!("wall_s", opt_f64, wall_s),
    col!("valid", bool, valid),
];

/// The Arrow schema of a dataset file: one field per entry of [`COLUMNS`], in order.
pub fn schema() -> Arc<Schema> {
    Arc::new(Schema::new(
        COLUMNS.iter().map(Column::field).collect::<Vec<_>>(),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::store::results::row::sample;

    /// The file layout users read (polars, pyarrow): names, types, nullability, order.
    #[test]
    fn layout_is_the_documented_one() {
        use DataType::{Boolean as B, Float64 as F, Int64 as I, Utf8 as S};
        let want = [
            ("case_id", S, false),
            ("sweep", S, false),
            ("contact", S, false),
            ("M", F, false),
            ("L", F, false),
            ("D", F, true),
            ("k", F, true),
            ("elasticity", S, false),
            ("viscosity", S, false),
            ("density", S, false),
            ("z", F, true),
            ("eta0", F, true),
            ("ph", F, true),
            ("sigma", F, true),
            ("gamma", F, true),
            ("slide_roll", F, true),
            ("grid_requested", I, false),
            ("cycle", S, false),
            ("max_cycles", I, false),
            ("fallback", B, false),
            ("tol_load", F, false),
            ("tol_h", F, false),
            ("converge", S, false),
            ("half_grid_estimate", B, false),
            ("accuracy", F, true),
            ("far_field", B, false),
            ("model_used", S, false),
            ("level", I, true),
            ("error_estimate", F, true),
            ("algebraic_error", F, true),
            ("warm_start", S, true),
            ("grid", I, true),
            ("levels", I, true),
            ("H_c", F, true),
            ("H_c_pmax", F, true),
            ("H_min", F, true),
            ("X_min", F, true),
            ("Y_min", F, true),
            ("H_min_cl", F, true),
            ("X_min_cl", F, true),
            ("P_max", F, true),
            ("spike_X", F, true),
            ("spike_P", F, true),
            ("H0", F, true),
            ("f", F, true),
            ("load_error", F, true),
            ("H_c_err", F, true),
            ("H_min_err", F, true),
            ("H_c_pmax_err", F, true),
            ("P_max_err", F, true),
            ("H_min_cl_err", F, true),
            ("Lambda", F, true),
            ("Lambda_c", F, true),
            ("asperity_load_fraction", F, true),
            ("P_asperity_max", F, true),
            ("H_c_smooth", F, true),
            ("H_min_smooth", F, true),
            ("mixed_iterations", I, true),
            ("status", S, false),
            ("reason", S, false),
            ("attempt", I, true),
            ("work_units", F, true),
            ("wall_s", F, true),
            ("valid", B, false),
        ];
        let schema = schema();
        let got: Vec<(&str, DataType, bool)> = schema
            .fields()
            .iter()
            .map(|f| (f.name().as_str(), f.data_type().clone(), f.is_nullable()))
            .collect();
        assert_eq!(got, want);
        assert!(COLUMNS
            .iter()
            .all(|c| (1..=SCHEMA_VERSION).contains(&c.since)));
    }

    /// Every setter puts back what its getter took: a row rebuilt column by column is the row.
    #[test]
    fn setters_invert_getters() {
        let row = sample("00000000000000aa");
        let mut back = CaseRow::default();
        for c in COLUMNS {
            match c.access {
                Access::Str { get, set } => set(&mut back, get(&row)).unwrap(),
                Access::OptStr { get, set } => set(&mut back, get(&row)),
                Access::F64 { get, set } => set(&mut back, get(&row)),
                Access::OptF64 { get, set } => set(&mut back, get(&row)),
                Access::I64 { get, set } => set(&mut back, get(&row)),
                Access::OptI64 { get, set } => set(&mut back, get(&row)),
                Access::Bool { get, set } => set(&mut back, get(&row)),
            }
        }
        assert_eq!(back, row);
        let status = COLUMNS.iter().find(|c| c.name == "status").unwrap();
        let Access::Str { set, .. } = status.access else {
            panic!("status is a string column")
        };
        let e = set(&mut back, "done").unwrap_err();
        assert!(e.to_string().contains("\"done\""), "{e}");
    }
}
