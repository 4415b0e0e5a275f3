//! Which law a film keeps: its smooth law (the corrected blend), the smooth law times a kriging
//! residual, its corner law (H_c, where the data show the corner) or the corner law times a
//! kriging residual. Each is cross-validated on the smooth law's folds; the lowest held-out RMS
//! wins, the simpler law on a tie (in that order).

use crate::fit::corner::{Corner, CornerChoice, CornerParams};
use crate::fit::correction::Correction;
use crate::fit::dataset::FitPoint;
use crate::fit::heldout::{HeldOut, Selected};
use crate::fit::kriging::{Kriging, KrigingChoice};
use crate::fit::lsq::Sample;
use crate::fit::model::FilmModel;
use crate::report::corner::{corner_fit, Blends, CornerFit};
use crate::report::kriging::{corrected_at, kriged};
use crate::report::recipe::Recipe;
use crate::solve::film::Film;

/// The law kept for a film, with the held-out errors of the formula as kept.
pub(super) struct Kept {
    /// Held-out errors (None: the cross-validation could not be made).
    pub(super) heldout: Option<HeldOut>,
    /// The corner law in place of the correction.
    pub(super) corner: Option<(Corner, CornerChoice)>,
    /// The kriging residual on top of the correction or the corner law.
    pub(super) kriging: Option<(Kriging, KrigingChoice)>,
}

/// The law the film `film` keeps, given its samples `data`, its fitted blend `model` with its
/// `correction`, the smooth law's selection `cv` and, for H_c, the fitted H_pm blend and its
/// correction `pm`.
pub(super) fn kept<Mo: FilmModel>(
    film: Film,
    pts: &[FitPoint],
    data: &[Sample],
    (model, correction): (&Mo, &Correction),
    cv: Option<Selected<Mo>>,
    pm: Option<(&Mo, &Correction)>,
    r: &Recipe<Mo>,
) -> Kept {
    let Some(sel) = cv else {
        return Kept {
            heldout: None,
            corner: None,
            kriging: None,
        };
    };
    let mut best = Kept {
        heldout: Some(sel.heldout.clone()),
        corner: None,
        kriging: None,
    };
    let rms = |k: &Kept| k.heldout.as_ref().map_or(f64::INFINITY, |h| h.chosen.rms);
    let offer = |k: Kept, best: &mut Kept| {
        if rms(&k) < rms(best) {
            *best = k;
        }
    };
    let all = |s: &Sample| corrected_at(model, correction, s);
    let fold = |f: usize, s: &Sample| {
        let (b, c) = sel.fits.get(f)?.as_ref()?;
        Some(corrected_at(b, c, s))
    };
    let jump = (film == Film::Centre).then_some(r.jump.as_ref()).flatten();
    if let Some((k, choice, h)) = kriged(data, &all, &fold, &sel.heldout, jump) {
        offer(
            Kept {
                heldout: Some(h),
                corner: None,
                kriging: Some((k, choice)),
            },
            &mut best,
        );
    }
    let (Some(params), Film::Centre, Some((pm, pm_correction))) = (r.corner, film, pm) else {
        return best;
    };
    // The corner law's corrections fade beyond the data where the recipe's lattice does.
    let params = CornerParams {
        fade: r.fades,
        ..params
    };
    let blends = Blends {
        own: model,
        pm,
        pm_correction,
        folds: &sel.blends,
        wrap: r.wrap,
    };
    let Some(CornerFit {
        law,
        choice,
        heldout,
        folds,
    }) = corner_fit(pts, data, &blends, &params, &sel.heldout)
    else {
        return best;
    };
    let corner_at = |b: &Mo, c: &Corner, s: &Sample| {
        let asym = b.asymptotes(s.m, s.l, s.d);
        (asym, c.apply(b.film(s.m, s.l, s.d), asym, s.d))
    };
    let all = |s: &Sample| corner_at(model, &law, s);
    let fold = |f: usize, s: &Sample| Some(corner_at(sel.blends.get(f)?, folds.get(f)?, s));
    let kriging = kriged(data, &all, &fold, &heldout, jump);
    offer(
        Kept {
            heldout: Some(heldout),
            corner: Some((law.clone(), choice.clone())),
            kriging: None,
        },
        &mut best,
    );
    if let Some((k, kc, h)) = kriging {
        offer(
            Kept {
                heldout: Some(h),
                corner: Some((law, choice)),
                kriging: Some((k, kc)),
            },
            &mut best,
        );
    }
    best
}
