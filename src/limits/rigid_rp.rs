//! The rigid-piezoviscous point asymptote and its D factor, from the solver's own rigid solves
//! and the exact slender limit.
//!
//! Under Barus viscosity the reduced pressure q = (1 - exp(-alpha p))/alpha of a rigid contact
//! obeys the isoviscous Reynolds equation, so the rigid Barus film is the rigid isoviscous film
//! whose peak alpha q_max is below 1, and the rigid-piezoviscous limit is alpha q_max = 1.
//! Rigid isoviscous scaling (p ~ h^(-3/2) at fixed geometry and speed) makes
//! alpha_bar P_max H^(3/2) = c L at any M, so alpha q_max = 1 where H^(3/2) = c L:
//!
//! H_RP = pi(D) H_RI(M = 1, D) L^(2/3),   pi(D) = (alpha_bar(M = 1, L = 1) P_max)^(2/3)
//!
//! with P_max and H_RI(1, D) = c_RI f_RI(D) of the rigid isoviscous solve at M = 1 (H_RI of the
//! film fitted: the rigid-piezoviscous film has the rigid-isoviscous shape, so H_pm and H_c keep
//! their rigid ratio).
//!
//! Slender limit, exact: as D -> 0 the centre strip y = 0 is a Martin line contact with the
//! point's film H_c, so pi(D) H_c(D) tends to the line's rigid-piezoviscous constant
//! [`B_RP_LINE`], and with D M^2 H_c -> [`C_SLENDER_CENTRE`],
//! pi(D)/D -> [`B_RP_LINE`]/[`C_SLENDER_CENTRE`]. The law is NVM-like,
//!
//! pi(D) = [`PI_CIRCULAR`] D psi(D),   psi(D) = [(1 + a D^p)/(1 + a)]^q,
//!
//! with q fixed by the slender limit (psi(0) = (1 + a)^-q) and (a, p) = [`SHAPE`] a
//! least-squares fit in log to far-field rigid solves at 14 values of D in [0.005, 1] (257^2,
//! 513^2 and 1025^2, Richardson over the two finer grids, tight convergence): within 0.06 % of
//! every solve (docs/validation.md, "The held asymptotes"). So the point RP law is
//!
//! H_RP = c_RI [`PI_CIRCULAR`] f_RI(D) D psi(D) L^(2/3)
//!
//! (b = c_RI [`PI_CIRCULAR`], f_RP(D) = f_RI(D) D psi(D), 1 at D = 1), held by the point fits.
//! [`FarFieldRigid::rp_constant`] is the check: H_RP / L^(2/3) of the far-field solves.

use crate::limits::rigid_d_factor::{FarFieldRigid, C_SLENDER_CENTRE};
use crate::solve::film::Film;

/// The line rigid-piezoviscous constant of the film at X = 0: H_RP = (c L)^(2/3) with
/// c = alpha_bar(L = 1) P_max H^(3/2) of the solver's rigid L = 0 line solve at 4097 points
/// (docs/validation.md); times 3/2.4475 for the film at the pressure maximum.
pub const B_RP_LINE: f64 = 1.0496;

/// pi(1) = (alpha_bar(M = 1, L = 1) P_max)^(2/3) of the circular rigid isoviscous contact
/// (far-field solves on 513^2 and 1025^2, Richardson; +-1e-5).
pub const PI_CIRCULAR: f64 = 0.0200046;

/// (a, p) of psi(D).
pub const SHAPE: [f64; 2] = [0.90442, 1.00157];

/// psi(0) = pi(D)/(pi(1) D) as D -> 0, from the slender limit.
pub fn psi_slender() -> f64 {
    B_RP_LINE / (PI_CIRCULAR * C_SLENDER_CENTRE)
}

/// The constants (a, p, q) of psi(D) = [(1 + a D^p)/(1 + a)]^q, q from the slender limit.
pub fn rp_shape() -> [f64; 3] {
    let [a, p] = SHAPE;
    [a, p, -psi_slender().ln() / (1.0 + a).ln()]
}

/// psi(D) = [(1 + a D^p)/(1 + a)]^q for the constants (a, p, q): 1 at D = 1.
pub fn psi([a, p, q]: [f64; 3], d: f64) -> f64 {
    ((1.0 + a * d.powf(p)) / (1.0 + a)).powf(q)
}

/// pi(D) of the law: [`PI_CIRCULAR`] D psi(D).
pub fn pi_law(d: f64) -> f64 {
    PI_CIRCULAR * d * psi(rp_shape(), d)
}

impl FarFieldRigid {
    /// H_RP / L^(2/3) of `film` from these solves: pi(D) H of each grid, extrapolated with
    /// order 2 (the spacing halves); `alpha_bar_1` is alpha_bar at M = 1, L = 1 and this D.
    pub fn rp_constant(&self, film: Film, alpha_bar_1: f64) -> f64 {
        self.extrapolated(|o| (alpha_bar_1 * o.p_max).powf(2.0 / 3.0) * film.of_outputs(o))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::limits::rigid_d_factor::ri_shape;
    use crate::limits::rigid_point::C_RI_CENTRE;

    #[test]
    fn the_law_meets_the_line_constant_in_the_slender_limit() {
        let s = rp_shape();
        assert!((psi(s, 1.0) - 1.0).abs() < 1e-15);
        // psi(0) is the slender value; pi(D) H_c(D) -> B_RP_LINE as D -> 0.
        assert!((psi(s, 0.0) / psi_slender() - 1.0).abs() < 1e-12);
        // The rigid-isoviscous law of H_c: f_RI has the form of psi, over D.
        let hc = |d: f64| C_RI_CENTRE * psi(ri_shape(Film::Centre), d) / d;
        let d = 1e-9;
        assert!((pi_law(d) * hc(d) / B_RP_LINE - 1.0).abs() < 1e-6);
        // Close to NVM's exponent -2/3 of [(1 + 0.691 D)/1.691] in f_RP, but not it.
        assert!(s[2] > 1.0 && s[2] < 1.5, "{s:?}");
    }
}
