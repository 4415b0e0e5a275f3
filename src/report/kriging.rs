//! The kriging stage of a film law ([`crate::fit::kriging`]): cross-validated on the folds of
//! the law's own selection (each fold's law fitted without the fold), kept when it lowers the
//! held-out RMS without raising the held-out max, then fitted to the final law's residuals on
//! all cases.

use crate::fit::correction::{Coordinates, Correction};
use crate::fit::heldout::{folds_of, worst_and_rms, HeldOut, FOLDS};
use crate::fit::kriging::{self, Fold, Kriging, KrigingChoice, X};
use crate::fit::lsq::Sample;
use crate::fit::model::FilmModel;
use crate::limits::jump::JumpTable;

/// A law's film at a sample, with the asymptotes of its blend (the kriging's coordinates).
pub(super) type LawAt<'a> = dyn Fn(&Sample) -> ([f64; 4], f64) + Sync + 'a;

/// A law fitted without fold f, at a sample (None: that fold's fit failed).
pub(super) type FoldLawAt<'a> = dyn Fn(usize, &Sample) -> Option<([f64; 4], f64)> + Sync + 'a;

/// The corrected blend `blend` x `correction` at `s`: [`LawAt`].
pub(super) fn corrected_at<Mo: FilmModel>(
    blend: &Mo,
    correction: &Correction,
    s: &Sample,
) -> ([f64; 4], f64) {
    let asym = blend.asymptotes(s.m, s.l, s.d);
    (asym, correction.apply(blend.film(s.m, s.l, s.d), asym, s.d))
}

/// The kriging coordinates (phi from `jump`, else 0) and log residual ln(H / H_law) of `s`.
fn residual(law: ([f64; 4], f64), s: &Sample, c_floor: f64, jump: Option<&JumpTable>) -> (X, f64) {
    let phi = jump.map_or(0.0, |t| kriging::phi(t, kriging::JUMP_WIDTH, s.m, s.l, s.d));
    (
        kriging::with_phi(kriging::point(&Coordinates::new(law.0, s.d), c_floor), phi),
        (s.h / law.1).ln(),
    )
}

/// The kriging residual of the law `all` fitted to `data`, with the held-out errors of the law
/// with it (`fold_law`: the law fitted without each fold of [`folds_of`] `data`; `plain`: the
/// law's own held-out errors); None when a fold has no law, a system fails, or it does not lower
/// the held-out RMS or raises the max. With `jump` the candidates include the corner coordinate
/// ([`kriging::candidates`]).
pub(super) fn kriged(
    data: &[Sample],
    all: &LawAt,
    fold_law: &FoldLawAt,
    plain: &HeldOut,
    jump: Option<&JumpTable>,
) -> Option<(Kriging, KrigingChoice, HeldOut)> {
    let laws: Vec<([f64; 4], f64)> = data.iter().map(all).collect();
    let z: Vec<Coordinates> = data
        .iter()
        .zip(&laws)
        .map(|(s, l)| Coordinates::new(l.0, s.d))
        .collect();
    let floor = kriging::c_floor(&z);
    let fold = folds_of(data);
    let folds = (0..FOLDS)
        .map(|f| {
            let mut out = Fold {
                train: vec![],
                test: vec![],
            };
            for (i, s) in data.iter().enumerate() {
                let (x, r) = residual(fold_law(f, s)?, s, floor, jump);
                if fold[i] == f {
                    out.test.push((i, x, r));
                } else {
                    out.train.push((x, r));
                }
            }
            Some(out)
        })
        .collect::<Option<Vec<Fold>>>()?;
    let kriging::Selection {
        scales,
        nugget,
        errors,
        ..
    } = kriging::select(&folds, data.len(), plain.chosen.max.abs(), jump.is_some())?;
    if errors.iter().any(|e| e.is_nan()) || plain.cases.len() != errors.len() {
        return None;
    }
    let without = &plain.chosen;
    let (worst, rms) = worst_and_rms(&errors);
    if rms >= without.rms || errors[worst].abs() > without.max.abs() {
        return None;
    }
    let (x, r): (Vec<X>, Vec<f64>) = data
        .iter()
        .zip(&laws)
        .map(|(s, l)| residual(*l, s, floor, jump))
        .unzip();
    let k = kriging::fit(&x, &r, scales, nugget, floor, jump)?;
    let h = plain.clone().with_errors(&errors);
    let choice = KrigingChoice {
        scales: [scales[0], scales[1], scales[2]],
        nugget,
        tried: kriging::candidates(jump.is_some()).len(),
        jump_scale: k.jump.as_ref().map(|j| j.scale),
        rms,
        max: errors[worst].abs(),
        without_rms: without.rms,
        without_max: without.max.abs(),
    };
    Some((k, choice, h))
}
