//! The data of a validated spec: its contacts with their axes and numerical settings, the
//! models, the output settings, and the line of every key given (for later messages).

use super::error::SpecError;
pub use crate::model::case::Contact;
use crate::model::case::Elasticity;
use crate::model::lubricant::Density;
use crate::solve::params::{Converge, CycleType};
use std::collections::BTreeMap;
use std::path::PathBuf;

/// The viscosity model as the spec gives it (Roelands from eta0 is resolved per case, since z
/// depends on alpha_bar and so on M and L).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum ViscositySpec {
    /// Barus (`viscosity = "barus"`, the default).
    Barus,
    /// Roelands with the index given (`models.z`).
    RoelandsZ {
        /// Roelands pressure-viscosity index z > 0.
        z: f64,
        /// Hertzian pressure p_h (Pa), `models.ph`.
        ph_pa: f64,
    },
    /// Roelands with z derived per case from the ambient viscosity (`models.eta0`).
    RoelandsEta0 {
        /// Ambient viscosity eta0 (Pa s), with ln(eta0) + 9.67 > 0.
        eta0: f64,
        /// Hertzian pressure p_h (Pa), `models.ph`.
        ph_pa: f64,
    },
}

/// Numerical settings of every solve of the sweep.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Numerics {
    /// Finest grid: points (line) or points per direction (point), within
    /// [`Contact::grid_range`].
    pub grid: usize,
    /// Multigrid cycle type (`cycle = "v"` or `"w"`).
    pub cycle: CycleType,
    /// The stopping rule (`converge = "fast"`, the default: at the discretisation error;
    /// `"tight"`: at the tolerances).
    pub converge: Converge,
    /// Cycles allowed on the finest level.
    pub max_cycles: usize,
    /// Retry a failed solve with conservative settings (the fallback ladder).
    pub fallback: bool,
    /// Convergence tolerance on the load error, in (0, 1).
    pub tol_load: f64,
    /// Convergence tolerance on the relative change of H_c over a cycle, in (0, 1).
    pub tol_h: f64,
    /// Also solve each case on the half grid and store the Richardson error estimates
    /// (H_c_err, H_min_err).
    pub error_estimate: bool,
    /// Target relative accuracy of H_c and H_min: refine from 257 points up to `grid` until the
    /// error estimate meets it (`ehlmap solve --accuracy`); the estimate goes to H_c_err/H_min_err.
    pub accuracy: Option<f64>,
    /// Point contacts: the asymptotic far field on the domain's boundary (`far_field`, default
    /// true; false: P = 0 there, the truncated domain of the classic references). Always false
    /// for line contacts.
    pub far_field: bool,
}

impl Default for Numerics {
    fn default() -> Self {
        Numerics {
            grid: 2049,
            cycle: CycleType::V,
            converge: Converge::Fast,
            max_cycles: 60,
            fallback: true,
            tol_load: 1e-7,
            tol_h: 1e-6,
            error_estimate: false,
            accuracy: None,
            far_field: false,
        }
    }
}

impl Numerics {
    /// The defaults of a contact: 2049 points for line contacts, 129 per direction for point
    /// contacts; the rest as [`Numerics::default`].
    pub fn for_contact(contact: Contact) -> Self {
        match contact {
            Contact::Line => Numerics::default(),
            Contact::Point => Numerics {
                grid: 129,
                far_field: true,
                ..Numerics::default()
            },
        }
    }
}

/// Where and how often results are written.
#[derive(Clone, Debug, PartialEq)]
pub struct OutputSpec {
    /// Base directory of the dataset `<dir>/<name>/` (relative to the working directory);
    /// `--out` overrides it.
    pub dir: PathBuf,
    /// Rewrite the part file after this many finished cases ...
    pub batch: usize,
    /// ... or this many seconds after the previous write.
    pub flush_seconds: f64,
}

/// One contact type of a spec: its M and L axes (the spec's, or its own `[axes.line]` /
/// `[axes.point]`) and the numerical settings of its cases.
#[derive(Clone, Debug, PartialEq)]
pub struct ContactSpec {
    /// Line or point.
    pub contact: Contact,
    /// Values of the M axis for this contact, in the order given.
    pub m: Vec<f64>,
    /// Values of the L axis for this contact, in the order given.
    pub l: Vec<f64>,
    /// Numerical settings of this contact's cases (`[numerics]` with `[numerics.<contact>]`
    /// over it).
    pub numerics: Numerics,
}

/// A validated sweep spec.
#[derive(Clone, Debug, PartialEq)]
pub struct SweepSpec {
    /// The file as given on the command line (used in messages).
    pub file: String,
    /// The full TOML text (stored in every Parquet footer).
    pub text: String,
    /// Dataset name: the directory `<out>/<name>/` (default: the file stem).
    pub name: String,
    /// The contact types of the sweep with their numerical settings, in the order given (one,
    /// or line and point for a mixed spec).
    pub contacts: Vec<ContactSpec>,
    /// Free text of `description`, when given.
    pub description: Option<String>,
    /// M axis values after expansion, in the order given (each contact's own M and L are in
    /// `contacts`).
    pub m: Vec<f64>,
    /// L axis values after expansion, in the order given.
    pub l: Vec<f64>,
    /// D = Rx/Ry axis values of the point cases, in (0, 1]; `None` for a line-only spec.
    pub d: Option<Vec<f64>>,
    /// Composite RMS roughness axis in Moes film units (`[0]`: smooth surfaces only).
    pub sigma: Vec<f64>,
    /// Roughness orientation axis gamma (`[1]`: isotropic), for the cases with sigma > 0.
    pub gamma: Vec<f64>,
    /// The rough cases' other inputs (`[models]`; its sigma and gamma are the axes').
    pub roughness: crate::model::roughness::Roughness,
    /// Elastic or rigid surfaces, for every case.
    pub elasticity: Elasticity,
    /// Viscosity model, for every case.
    pub viscosity: ViscositySpec,
    /// Density model, for every case.
    pub density: Density,
    /// Where and how often results are written (`[output]`).
    pub output: OutputSpec,
    /// Line of each key that was given (dotted path, e.g. "axes.M"), for later messages.
    pub lines: BTreeMap<String, usize>,
}

impl SweepSpec {
    /// The numerics of `contact`, when the spec has that contact.
    pub fn numerics(&self, contact: Contact) -> Option<&Numerics> {
        self.contacts
            .iter()
            .find(|c| c.contact == contact)
            .map(|c| &c.numerics)
    }

    /// Whether the spec has cases of `contact`.
    pub fn has(&self, contact: Contact) -> bool {
        self.numerics(contact).is_some()
    }

    /// An error about `key` at the line where the spec gives it (line 1 if absent).
    pub fn error(&self, key: &str, message: impl Into<String>) -> SpecError {
        SpecError {
            file: self.file.clone(),
            line: self.lines.get(key).copied().unwrap_or(1),
            key: key.to_string(),
            message: message.into(),
        }
    }
}
