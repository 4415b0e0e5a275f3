//! How each contact is fitted: a [`Recipe`] names a contact's start model per film (the published
//! laws with the solver's own limit constants held), the parameters freed in stage 1 and stage 2
//! of [`super::staged`], the physical test of a fitted blend and the candidate interior
//! corrections that the held-out selection chooses from ([`crate::fit::heldout`]).
//!
//! Line: [`line_recipe`] (Moes 1992 form). Point: [`point_recipe`] (NVM 1994 form, the free set
//! depending on the D values and the L > 0 cases in the data).

use crate::fit::approach::fit_approach;
use crate::fit::corner::{self, CornerParams};
use crate::fit::correction::{line_terms, point_terms, Coordinates};
use crate::fit::dataset::FitPoint;
use crate::fit::fitted::Blend;
use crate::fit::heldout::{lattice, nested, Basis};
use crate::fit::lsq::Sample;
use crate::fit::model::{LineModel, PARAM_NAMES};
use crate::fit::point_model::{PointModel, POINT_PARAM_NAMES};
use crate::limits::anchors::Anchor;
use crate::limits::jump::JumpTable;
use crate::limits::{point_ei, rigid_d_factor, rigid_point, rigid_rp};
use crate::solve::film::Film;
use crate::strategy::closed_form::MARTIN_FLUX;

/// The exact rigid-isoviscous constant of the line film at X = 0 (Martin, Reynolds exit condition).
pub const C_RI_CENTRAL: f64 = 2.4475;

/// The rigid-piezoviscous constant of the line film at X = 0: H_RP = (c L)^(2/3), c = alpha p_max
/// H^(3/2)/L of the rigid isoviscous solution (the Barus reduced pressure reaches 1/alpha;
/// docs/physics.md section 5), with c from the solver's rigid L = 0 solve at 4097 points
/// (docs/validation.md). The line RP law (held); the report re-derives the limit from a
/// fresh solve (`crate::report::checks`).
pub const B_RP_CENTRAL: f64 = rigid_rp::B_RP_LINE;

/// The elastic-isoviscous constant of the line films at X = 0 and at the pressure maximum:
/// H_EI = a M^(-1/5) with a from the solver's L = 0 solves beyond the nightly data (H M^(1/5) =
/// 2.4855 at M = 3000, 2.4878 at M = 1e4 on 65537 points; docs/validation.md). Held, with the
/// exponent of asymptotic theory.
pub const A_EI_CENTRAL: f64 = 2.488;

/// The elastic-isoviscous constant of the line minimum film (1.9842 at M = 3000, 1.9837 at
/// M = 1e4), held like [`A_EI_CENTRAL`].
pub const A_EI_MIN: f64 = 1.984;

/// The elastic-piezoviscous constant of the line films at X = 0 and at the pressure maximum
/// (equal there: the pressure maximum is at the centre): H_EP = d M^(-1/8) L^(3/4) with d the
/// limit L -> infinity of H M^(1/8) L^(-3/4) of the solver's solves at M = 1e4 (1.33187, 1.31854,
/// 1.31240 at L = 20, 40, 80 on 65537 points, each within 0.25 %; the differences shrink 0.46
/// times per doubling of L, so Aitken's extrapolation gives 1.3072), +-0.004 (the same from
/// M = 3000, L = 20 and 40, at the ratio seen at M = 1e4: 1.3034; at L = 40 the constant moves by
/// 0.5 % over M = 1e3-3e4). Solves at L >= 120 fail on the fine grids they need (issue 22).
/// docs/validation.md, "The held asymptotes".
pub const D_EP_CENTRAL: f64 = 1.307;

/// The elastic-piezoviscous constant of the line minimum film, from the same solves (0.99432,
/// 0.98497, 0.98095; Aitken 0.9779; from M = 3000 0.9745), held like [`D_EP_CENTRAL`]; +-0.01
/// (the extrapolation amplifies grid differences: from the grids a 0.3 % target stops at it is
/// 0.968). The report re-derives both constants ([`crate::limits::line_ep`]).
pub const D_EP_MIN: f64 = 0.978;

/// The line free sets. Every asymptote is held: RI fixed by theory ([`C_RI_CENTRAL`]), EI at
/// the solver's limit ([`A_EI_CENTRAL`] M^(-1/5)), RP at its rigid limit ([`B_RP_CENTRAL`]
/// L^(2/3)), EP at its limit ([`D_EP_CENTRAL`] M^(-1/8) L^(3/4)). Stage 1 fits the blend's s0,
/// stage 2 the blending powers p, q and the s-law too. (With the lattice correction the
/// held-out errors are those of a fitted EP constant and of free exponents: docs/validation.md.)
pub(super) const LINE_STAGE1: [usize; 1] = [9];
pub(super) const LINE_STAGE2: [usize; 6] = [7, 8, 9, 10, 11, 12];

/// Fewest cases a contact's fit needs, whatever its free parameters (two per held-out fold).
pub const MIN_CASES: usize = 10;

/// The start of a line fit of `film`: Moes' blend with the held asymptotes: H_RI at its exact
/// constant (2.4475 at X = 0 and for H_min, 3 at the pressure maximum), H_RP at its rigid limit
/// scaled the same way (the rigid-piezoviscous film has the rigid-isoviscous shape), H_EI and
/// H_EP at the solver's limits.
fn line_start(film: Film) -> LineModel {
    let (c_ri, scale) = match film {
        Film::Centre => (C_RI_CENTRAL, 1.0),
        Film::PressureMax => (MARTIN_FLUX, 1.0),
        Film::Minimum => (C_RI_CENTRAL, 0.75),
    };
    let mut m = LineModel::moes();
    m.c_ri = c_ri;
    m.x[2] = (B_RP_CENTRAL * c_ri / C_RI_CENTRAL).ln();
    m.x[3] = 2.0 / 3.0;
    for k in [0, 4] {
        m.x[k] += f64::ln(scale);
    }
    m.x[0] = match film {
        Film::Minimum => A_EI_MIN,
        _ => A_EI_CENTRAL,
    }
    .ln();
    m.x[1] = -0.2;
    m.x[4] = match film {
        Film::Minimum => D_EP_MIN,
        _ => D_EP_CENTRAL,
    }
    .ln();
    m.x[5] = -0.125;
    m.x[6] = 0.75;
    m
}

fn line_physical(m: &LineModel) -> bool {
    let x = &m.x;
    x[7] > 0.5
        && x[7] + x[12] > 0.5
        && x[8] > 0.5
        && x[9] > 0.5
        && x[11] > 0.0
        && x.iter().all(|v| v.abs() < 50.0)
}

/// How one contact is fitted: the start model of each film, the two free sets, the physical
/// test, and the wrapping into [`crate::fit::fitted::FittedModel`].
pub(super) struct Recipe<Mo> {
    pub(super) contact: &'static str,
    pub(super) start: fn(Film) -> Mo,
    pub(super) stage1: Vec<usize>,
    pub(super) stage2: Vec<usize>,
    /// Blend parameters held at their start in the later fallbacks of [`super::staged`].
    pub(super) late: &'static [usize],
    pub(super) physical: fn(&Mo) -> bool,
    pub(super) names: &'static [&'static str],
    pub(super) wrap: fn(Mo) -> Blend,
    /// The candidate corrections for data at these coordinates ([`crate::fit::heldout`]), the
    /// lattice ones fading beyond their cases when the flag ([`Recipe::fades`]) says so.
    pub(super) bases: fn(&[Coordinates], bool) -> Vec<Basis>,
    /// Whether H_min is fitted as the centre line's minimum times the side-lobe factor
    /// ([`crate::fit::side`]) when the data carry H_min,cl (point contacts).
    pub(super) side_lobes: bool,
    /// The corner law's lattice and ridges when H_c is fitted through its corner with H_pm
    /// ([`crate::fit::corner`]; where the data allow it).
    pub(super) corner: Option<CornerParams>,
    /// Where the point H_c corner lies, from solves ([`crate::limits::jump`]): its kriging then
    /// also offers the corner coordinate ([`crate::fit::kriging`]). None: not given.
    pub(super) jump: Option<JumpTable>,
    /// The parameters held at their start for a film, whatever the free sets say (the point
    /// H_pm elastic-isoviscous law: [`point_held`]).
    pub(super) held: fn(Film) -> &'static [usize],
    /// What a fit on some samples starts from, given the start model and the anchors (held
    /// parameters set from the samples themselves, so each held-out fold sets them from its own
    /// training cases: the point approach factor, [`point_pre`]; else the start, [`no_pre`]).
    pub(super) pre: fn(&Mo, &[Sample], &[Sample]) -> Mo,
    /// The solver's limit films beyond the data that [`Recipe::pre`] also fits to, by film
    /// ([`crate::limits::anchors`]; the point approach factor); [`Recipe::for_film`] keeps the
    /// film's own.
    pub(super) anchors: Vec<(Film, Sample)>,
    /// Whether the lattice corrections fade beyond their cases ([`crate::fit::support`]): the
    /// point H_c and H_pm, whose laws are evaluated at the coordinates they are fitted at (not
    /// H_min, the centre line's law times the side-lobe factor).
    pub(super) fades: bool,
}

impl<Mo> Recipe<Mo> {
    /// This recipe for `film`: its free sets without the parameters [`Recipe::held`] holds.
    pub(super) fn for_film(&self, film: Film) -> Recipe<Mo> {
        let held = (self.held)(film);
        let keep = |v: &[usize]| v.iter().copied().filter(|k| !held.contains(k)).collect();
        Recipe {
            stage1: keep(&self.stage1),
            stage2: keep(&self.stage2),
            jump: self.jump.clone(),
            anchors: self
                .anchors
                .iter()
                .copied()
                .filter(|(f, _)| *f == film)
                .collect(),
            fades: self.fades && film != Film::Minimum,
            ..*self
        }
    }
}

/// No parameter held beyond the free sets.
fn none_held(_: Film) -> &'static [usize] {
    &[]
}

/// The point films whose elastic-isoviscous law is held at the line's limit carried over by the
/// local inlet analysis ([`point_ei`]): H_pm holds a_EI and e_EI (indices 2 and 4), its approach
/// factor set before the fit ([`point_pre`]); so does H_c with `CENTRE` ([`with_point_ei_limit`]),
/// else it keeps a fitted EI law (held, its law is exact as M -> infinity but worse held out).
/// H_min is set in the side lobes and keeps its fitted law (docs/validation.md, "The approach to
/// the point elastic-isoviscous limit").
fn point_held<const CENTRE: bool>(film: Film) -> &'static [usize] {
    match film {
        Film::PressureMax => &[2, 4],
        Film::Centre if CENTRE => &[2, 4],
        _ => &[],
    }
}

/// Ridge weights of the line lattice candidates ([`line_bases`]).
pub const LINE_RIDGES: [f64; 3] = [1e-5, 1e-4, 1e-3];

/// Lattice levels offered to line fits (spacing [`crate::fit::correction::LATTICE`] / 2^level),
/// coarsest first: the held-out error chooses, the simpler on a tie. Point fits take level 0
/// only: on the point data (15 M x 7 L x 4 D) the half spacing was worse held out for every film
/// (docs/validation.md).
pub const LATTICE_LEVELS: [u8; 2] = [0, 1];

/// The line candidates: the nested terms, then the lattice ([`crate::fit::heldout::lattice`]) at
/// each of [`LATTICE_LEVELS`] with each of [`LINE_RIDGES`].
fn line_bases(z: &[Coordinates], _fade: bool) -> Vec<Basis> {
    let mut out = nested(&line_terms());
    for level in LATTICE_LEVELS {
        out.extend(lattice(z, level, &LINE_RIDGES, 0));
    }
    out
}

/// Ridge weights of the point lattice candidates ([`point_bases`]); 1e-1 is chosen by the point
/// H_min on the 0.5 % point data (docs/validation.md).
pub const POINT_RIDGES: [f64; 3] = [1e-3, 1e-2, 1e-1];

/// The point lattice's bumps are also taken times ln D, ..., (ln D)^POINT_LN_D_POWERS (the films'
/// D trends are not linear in ln D between the rigid and elastic sides; docs/validation.md).
pub const POINT_LN_D_POWERS: u8 = 2;

/// The point candidates: the nested terms, then the level-0 lattice with each term also times
/// powers of ln D up to [`POINT_LN_D_POWERS`] ([`crate::fit::heldout::lattice`]) with each of
/// [`POINT_RIDGES`]; with `fade` the lattice fades beyond its cases' range of a at each D
/// ([`crate::fit::support`]: its bumps are local, and those past the data are set by their
/// tails), the nested terms (global functions of the transitions, each set by all the cases) do
/// not.
fn point_bases(z: &[Coordinates], fade: bool) -> Vec<Basis> {
    let mut out = nested(&point_terms());
    let mut grid = lattice(z, 0, &POINT_RIDGES, POINT_LN_D_POWERS);
    for b in &mut grid {
        b.fade = fade;
    }
    out.extend(grid);
    out
}

/// Free point parameters for the data: the D corrections only with two or more D values, the
/// piezoviscous laws only with L > 0 cases.
fn point_free(pts: &[FitPoint]) -> Vec<usize> {
    let mut ds: Vec<f64> = pts.iter().map(|p| p.dd()).collect();
    ds.sort_by(f64::total_cmp);
    ds.dedup();
    let any_piezo = pts.iter().any(|p| p.l > 0.0);
    PointModel::ASYMPTOTES
        .iter()
        .copied()
        .filter(|k| ds.len() >= 2 || !PointModel::D_EXPONENTS.contains(k))
        .filter(|k| any_piezo || !PointModel::PIEZO.contains(k))
        .collect()
}

/// The start of a point fit of `film`: NVM 1994 with the solver's rigid-isoviscous law (c_RI
/// and its D factor) and rigid-piezoviscous law (b = c_RI pi(1), beta = 2/3, f_RP = f_RI(D) D
/// psi(D), e_RP = 0; [`rigid_rp`]), both held, its elastic laws scaled by 0.6 for H_min.
fn point_start(film: Film) -> PointModel {
    let scale: f64 = if film == Film::Minimum { 0.6 } else { 1.0 };
    let mut start = PointModel::nvm();
    start.x[0] = rigid_point::c_ri(film).ln();
    start.ri_shape = rigid_d_factor::ri_shape(film);
    start.x[5] = (rigid_point::c_ri(film) * rigid_rp::PI_CIRCULAR).ln();
    start.x[6] = 2.0 / 3.0;
    start.x[7] = 0.0;
    start.rp_shape = Some(rigid_rp::rp_shape());
    for k in [2, 8] {
        start.x[k] += scale.ln();
    }
    start
}

/// The elastic-isoviscous law of `start` at the line's limit carried over by the local inlet
/// analysis: a_EI = [`A_EI_CENTRAL`] [`point_ei::circular_over_line`], the exact f_EI(D)
/// ([`point_ei::ei_d_factor`]), e_EI = 0.
fn at_ei_limit(mut start: PointModel) -> PointModel {
    start.x[2] = (A_EI_CENTRAL * point_ei::circular_over_line()).ln();
    start.x[4] = 0.0;
    start.ei_exact = true;
    start
}

/// [`point_start`] with the elastic-isoviscous law at its limit ([`at_ei_limit`]) for the films
/// that [`point_held`] holds it for.
fn point_start_ei_limit<const CENTRE: bool>(film: Film) -> PointModel {
    let start = point_start(film);
    if point_held::<CENTRE>(film).contains(&2) {
        at_ei_limit(start)
    } else {
        start
    }
}

/// The point recipe with the H_c elastic-isoviscous law held at its limit as well as H_pm's
/// (`ehlmap fit --point-ei-limit`): [`point_start_ei_limit`] and [`point_held`] with `CENTRE`,
/// its approach factor fitted first and held ([`point_pre`]), and the H_c corner law
/// judging the cases whose H_pm is not resolved by the corrected H_pm law (better held out with
/// the held H_c: [`CornerParams::pm_corrected`]).
pub(super) fn with_point_ei_limit(mut r: Recipe<PointModel>) -> Recipe<PointModel> {
    r.start = point_start_ei_limit::<true>;
    r.held = point_held::<true>;
    r.corner = r.corner.map(|c| CornerParams {
        pm_corrected: true,
        ..c
    });
    r
}

/// The anchors' films as L = 0 samples, by film (those within their error-bar bound:
/// [`Anchor::film`]), for [`Recipe::anchors`].
pub(super) fn anchor_samples(anchors: &[Anchor]) -> Vec<(Film, Sample)> {
    let at = |a: &Anchor, h| Sample {
        m: a.m,
        l: 0.0,
        d: a.d,
        h,
    };
    anchors
        .iter()
        .flat_map(|a| {
            [Film::Centre, Film::PressureMax]
                .into_iter()
                .filter_map(move |film| a.film(film).map(|h| (film, at(a, h))))
        })
        .collect()
}

/// No change to the start before a fit.
fn no_pre<Mo: Clone>(start: &Mo, _: &[Sample], _: &[Sample]) -> Mo {
    start.clone()
}

/// Before a point fit whose H_EI is held at the exact limit (`ei_exact`): its approach factor
/// from the data's elastic-isoviscous cases and the anchors ([`fit_approach`]), then held.
fn point_pre(start: &PointModel, data: &[Sample], anchors: &[Sample]) -> PointModel {
    if start.ei_exact {
        fit_approach(start, data, anchors).model
    } else {
        start.clone()
    }
}

/// The line recipe: Moes' form, stage 1 [`LINE_STAGE1`], stage 2 [`LINE_STAGE2`].
pub(super) fn line_recipe() -> Recipe<LineModel> {
    Recipe {
        contact: "line",
        start: line_start,
        stage1: LINE_STAGE1.to_vec(),
        stage2: LINE_STAGE2.to_vec(),
        late: &[],
        physical: line_physical,
        names: &PARAM_NAMES,
        wrap: Blend::Line,
        bases: line_bases,
        side_lobes: false,
        corner: Some(corner::LINE),
        jump: None,
        held: none_held,
        pre: no_pre,
        anchors: vec![],
        fades: false,
    }
}

/// The point recipe for the data `pts`. H_RI and H_RP are held at the solver's limits, H_pm's
/// H_EI at its limit times the approach factor fitted first ([`point_start_ei_limit`],
/// [`point_held`], [`point_pre`]), and the exponents of the other EI laws and of H_EP at
/// theory's ([`PointModel::ASYMPTOTES`]). Stage 1 also holds the
/// H_EP law's constant and D correction at NVM's: with few elastic cases they are not
/// identifiable and run off when freed (docs/validation.md, "Earlier fit changes"). Stage 2
/// (from `FULL_FIT_MIN_POINTS` cases) frees them and the blend, and is kept only when physical,
/// identified and better.
pub(super) fn point_recipe(pts: &[FitPoint]) -> Recipe<PointModel> {
    let all_free = point_free(pts);
    let free: Vec<usize> = all_free
        .iter()
        .copied()
        .filter(|k| ![8, 11].contains(k))
        .collect();
    let mut all = all_free;
    // The blend: s0, s1, c_00 and the rigid/elastic isoviscous power r.
    all.extend([12, 13, 14, 15]);
    Recipe {
        contact: "point",
        start: point_start_ei_limit::<false>,
        stage1: free,
        stage2: all,
        late: &[14, 15],
        physical: PointModel::physical,
        names: &POINT_PARAM_NAMES,
        wrap: Blend::Point,
        bases: point_bases,
        side_lobes: true,
        corner: Some(corner::POINT),
        jump: None,
        held: point_held::<false>,
        pre: point_pre,
        anchors: vec![],
        fades: true,
    }
}
