//! The kriging stage of a smooth film law ([`crate::fit::kriging`]): cross-validated on the
//! folds of the law's own selection (each fold's blend and correction, fitted without the fold),
//! kept when it lowers the held-out RMS without raising the held-out max, then fitted to the
//! final law's residuals on all cases.

use crate::fit::correction::{Coordinates, Correction};
use crate::fit::heldout::{folds_of, worst_and_rms, HeldOut, Selected, FOLDS};
use crate::fit::kriging::{self, Fold, Kriging, KrigingChoice, NUGGETS, SCALES};
use crate::fit::lsq::Sample;
use crate::fit::model::FilmModel;

/// The kriging coordinates and log residual ln(H / H_law) of `s` under `blend` x `correction`.
fn residual<Mo: FilmModel>(
    blend: &Mo,
    correction: &Correction,
    s: &Sample,
    c_floor: f64,
) -> ([f64; 3], f64) {
    let asym = blend.asymptotes(s.m, s.l, s.d);
    let law = correction.apply(blend.film(s.m, s.l, s.d), asym, s.d);
    (
        kriging::point(&Coordinates::new(asym, s.d), c_floor),
        (s.h / law).ln(),
    )
}

/// The kriging residual of the law `blend` x `correction` fitted to `data`, with the held-out
/// errors of the law with it (`sel`: the law's selection, whose fold fits it reuses); None when
/// a fold has no fit, a system fails, or it does not lower the held-out RMS or raises the max.
pub(super) fn kriged<Mo: FilmModel>(
    data: &[Sample],
    blend: &Mo,
    correction: &Correction,
    sel: &Selected<Mo>,
) -> Option<(Kriging, KrigingChoice, HeldOut)> {
    let z: Vec<Coordinates> = data
        .iter()
        .map(|s| Coordinates::new(blend.asymptotes(s.m, s.l, s.d), s.d))
        .collect();
    let floor = kriging::c_floor(&z);
    let fold = folds_of(data);
    let folds = (0..FOLDS)
        .map(|f| {
            let (b, c) = sel.fits.get(f)?.as_ref()?;
            let mut out = Fold {
                train: vec![],
                test: vec![],
            };
            for (i, s) in data.iter().enumerate() {
                let (x, r) = residual(b, c, s, floor);
                if fold[i] == f {
                    out.test.push((i, x, r));
                } else {
                    out.train.push((x, r));
                }
            }
            Some(out)
        })
        .collect::<Option<Vec<Fold>>>()?;
    let (scales, nugget, errors) = kriging::select(&folds, floor, data.len())?;
    if errors.iter().any(|e| e.is_nan()) {
        return None;
    }
    let plain = &sel.heldout.chosen;
    let (worst, rms) = worst_and_rms(&errors);
    if rms >= plain.rms || errors[worst].abs() > plain.max.abs() {
        return None;
    }
    let (x, r): (Vec<[f64; 3]>, Vec<f64>) = data
        .iter()
        .map(|s| residual(blend, correction, s, floor))
        .unzip();
    let k = kriging::fit(&x, &r, scales, nugget, floor)?;
    let mut h = sel.heldout.clone();
    for (c, e) in h.cases.iter_mut().zip(&errors) {
        c.error = *e;
    }
    h.chosen.rms = rms;
    h.chosen.max = errors[worst];
    h.chosen.worst = (data[worst].m, data[worst].l, data[worst].d);
    let choice = KrigingChoice {
        scales,
        nugget,
        tried: SCALES.len() * NUGGETS.len(),
        rms,
        max: errors[worst].abs(),
        without_rms: plain.rms,
        without_max: plain.max.abs(),
    };
    Some((k, choice, h))
}
