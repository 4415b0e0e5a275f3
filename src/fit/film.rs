//! Which film a fit describes: H_c at X = 0, H_pm at the pressure maximum on the centre line
//! (Moes' central film), H_min; how each is read from a dataset row (with its error-estimate
//! filter) and from a solve.

use crate::fit::dataset::MAX_ERROR_ESTIMATE;
use crate::report::FitPoint;
use crate::solve::solution::Outputs;

/// The film a fit describes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Film {
    /// H_c: the film at X = 0 (Y = 0).
    Centre,
    /// H_pm: the film at the pressure maximum on the centre line, Moes' central film (its
    /// rigid-isoviscous line limit is the flux thickness 3/M). Where the piezoviscous spike is
    /// the global maximum it is the film under the spike, up to 0.9 % below H_c on the nightly
    /// line sweep (M 14-122, L 8-20).
    PressureMax,
    /// H_min: the minimum film.
    Minimum,
}

impl Film {
    pub const ALL: [Film; 3] = [Film::Centre, Film::PressureMax, Film::Minimum];

    /// The name used in reports and `fit.json` (H_c, H_pm, H_min).
    pub fn name(self) -> &'static str {
        match self {
            Film::Centre => "H_c",
            Film::PressureMax => "H_pm",
            Film::Minimum => "H_min",
        }
    }

    /// This film of a dataset case (None when the dataset does not carry it, or when its error
    /// estimate exceeds [`MAX_ERROR_ESTIMATE`]).
    pub fn of_point(self, p: &FitPoint) -> Option<f64> {
        let ok = |e: Option<f64>| e.is_none_or(|e| e <= MAX_ERROR_ESTIMATE);
        match self {
            Film::Centre => ok(p.h_c_err).then_some(p.h_c),
            Film::PressureMax => p.h_pm.filter(|_| ok(p.h_c_err) && ok(p.h_min_err)),
            Film::Minimum => ok(p.h_min_err).then_some(p.h_min),
        }
    }

    /// This film of a solve.
    pub fn of_outputs(self, o: &Outputs) -> f64 {
        match self {
            Film::Centre => o.h_c,
            Film::PressureMax => o.h_c_pmax,
            Film::Minimum => o.h_min,
        }
    }
}
