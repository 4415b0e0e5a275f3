//! The blended-asymptote law of either contact: Moes' line blend ([`crate::fit::model`]) or
//! NVM's point blend ([`crate::fit::point_model`]), evaluated at (M, L, D) with its four
//! asymptotes.

use crate::fit::model::LineModel;
use crate::fit::point_model::PointModel;
use serde::{Deserialize, Serialize};

/// The blended-asymptote law of either contact.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(tag = "kind", rename_all = "lowercase")]
pub enum Blend {
    /// A line-contact law (Moes 1992 form).
    Line(LineModel),
    /// A point-contact law (Nijenbanning-Venner-Moes 1994 form).
    Point(PointModel),
}

impl Blend {
    /// The blended film at (M, L, D) in Moes units; a line law ignores D.
    pub fn eval(&self, m: f64, l: f64, d: f64) -> f64 {
        match self {
            Blend::Line(x) => x.eval(m, l),
            Blend::Point(x) => x.eval(m, l, d),
        }
    }

    /// The four asymptotes [H_RI, H_EI, H_RP, H_EP] at (M, L, D) (the last two 0 at L = 0).
    pub fn asymptotes(&self, m: f64, l: f64, d: f64) -> [f64; 4] {
        match self {
            Blend::Line(x) => x.asymptotes(m, l),
            Blend::Point(x) => x.asymptotes(m, l, d),
        }
    }
}
