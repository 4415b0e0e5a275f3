//! The films a solve reports and a fit describes: H_c at X = 0, H_pm at the pressure maximum on
//! the centre line (Moes' central film), H_min; how each is read from a solve.

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
    /// The three films, in report order.
    pub const ALL: [Film; 3] = [Film::Centre, Film::PressureMax, Film::Minimum];

    /// The name used in reports and `fit.json` (H_c, H_pm, H_min).
    pub fn name(self) -> &'static str {
        match self {
            Film::Centre => "H_c",
            Film::PressureMax => "H_pm",
            Film::Minimum => "H_min",
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
