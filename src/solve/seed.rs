//! A converged solution on a coarser grid of the same case and domain ([`Seed`]), from which
//! the multigrid's FMG ascent starts on the level whose nodes are its nodes
//! ([`crate::solve::multilevel::Multigrid`]). Invariant: only converged smooth solves that kept
//! their line profile or point fields give one.

/// A converged solution of the same case on a coarser grid of the same domain (the accuracy
/// ladder's previous grid): the FMG ascent starts from it on the level whose nodes are its
/// nodes, instead of from the coarsest level ([`crate::solve::fmg::Fas::install_seed`]).
#[derive(Clone, Debug, PartialEq)]
pub struct Seed {
    /// Node coordinates X.
    pub x: Vec<f64>,
    /// Node coordinates Y (point contacts; empty for line contacts).
    pub y: Vec<f64>,
    /// The pressure P at the nodes (row-major with X fastest for point contacts).
    pub p: Vec<f64>,
    /// H0 in Moes units ([`crate::solve::solution::Outputs::h0`]).
    pub h0_moes: f64,
}

impl Seed {
    /// The seed of a converged smooth solve that kept its line profile or point fields; None
    /// otherwise.
    pub fn of(s: &crate::solve::solution::Solution) -> Option<Seed> {
        let o = &s.outputs;
        if o.status != crate::solve::Status::Converged || o.mixed.is_some() || !o.h0.is_finite() {
            return None;
        }
        let (x, y, p) = match (&s.profile, &s.fields) {
            (Some(pr), _) => (pr.x.clone(), vec![], pr.p.clone()),
            (None, Some(f)) => (f.x.clone(), f.y.clone(), f.p.clone()),
            (None, None) => return None,
        };
        Some(Seed {
            x,
            y,
            p,
            h0_moes: o.h0,
        })
    }

    /// Whether a level with these node coordinates is the seed's grid.
    pub fn matches(&self, x: &[f64], y: &[f64]) -> bool {
        let same = |a: &[f64], b: &[f64]| {
            a.len() == b.len()
                && a.iter()
                    .zip(b)
                    .all(|(u, v)| (u - v).abs() <= 1e-12 * (1.0 + v.abs()))
        };
        same(&self.x, x) && same(&self.y, y)
    }
}
