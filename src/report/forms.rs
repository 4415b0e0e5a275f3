//! The fitted formulas' form in words, as report.md states it above each contact's
//! coefficients: the blend, its held asymptotes, the interior correction, the corner law and the
//! kriging residual (the mathematics: docs/method.md, "Fit"; the code: [`crate::fit`]).

use crate::fit::fitted::Blend;
use crate::report::ContactReport;

/// The line formula's form.
pub(super) const LINE_FORM: &str =
    "Formula (Moes units): H = H_blend exp(C). H_blend = [ (H_RI^p + H_EI^p)^(s/p) + (H_RP^-q + \
H_EP^-q)^(-s/q) ]^(1/s), s = s0 + s1 exp(-s2 H_EI/H_RI), p = p0 + p1 exp(-s2 H_EI/H_RI), \
H_RI = 2.4475/M (exact, fixed), H_EI = a M^-1/5 (held at the solver's limit: a = 2.488, 1.984 \
for H_min, from L = 0 solves up to M = 1e4), H_RP = b L^(2/3) (held at the solver's \
rigid-piezoviscous limit b = 1.0496, times 3/2.4475 for H_pm), H_EP = d M^(-1/8) L^(3/4) (the \
exponents of asymptotic theory; held at the solver's limit d = 1.307, 0.978 for H_min, from \
solves at M = 1e4 and L up to 80 extrapolated in L). p, q, the s-law and p1 start from Moes' (7/3, 7/2, 7/5 + 8/5 \
exp(-2 H_EI/H_RI), 0) and are fitted too with 40 or more converged cases (a 1 sigma of 0 marks a \
parameter held fixed). H_pm, the film at the pressure maximum (Moes' central film), is fitted \
with the same form and its own exact H_RI = 3/M (the flux thickness); H_min with \
H_RI = 2.4475/M. C = sum c_k phi_k is the interior correction: each phi_k is a transition bump \
times a monomial and vanishes wherever one asymptote dominates (coordinates a = ln(H_EI/H_RI), \
b = ln(H_EP/H_RP), c = ln(H_piezo/H_iso), w = 1/(1 + e^-c); bumps g(t) = 2/(1 + cosh t): \
isoviscous g(a)(1 - w), piezoviscous g(b) w, outer g(c)), or a lattice of bumps \
g(a/W - i)(1 - w) and g(a/W - i) g(c/W - j) (W = 0.75 or 0.375) over the data, fitted with a ridge weight; \
the candidate (number of terms, or lattice spacing and ridge) is chosen by 5-fold held-out error, the \
coefficients fitted on all cases. H_pm is not fitted where the pressure maximum is not \
grid-converged (the outlet spike, or P_max_err above 2 %). Where the data show the corner at \
which H_c meets H_pm, H_c is the corner law of its section (with the asymptotes of its blend). \
Where it lowers the held-out RMS and not its max, the law is also multiplied by a kriging \
residual exp(k), k = sum_j w_j K(|z - z_j|_s): K the Matern 5/2 kernel, z = (a, max(c, c_floor)) \
of each data case, scales s and nugget chosen by the same folds, w fitted to the law's log \
residuals; k falls to 0 away from the data and in every asymptotic limit. formula.py evaluates H.";

/// The point formula's form.
const POINT_FORM: &str = "Formula (Moes point units, NVM 1994 form): H = H_blend exp(C). \
H_blend = { [H_RI^r + (H_EI^-4 + H_00^-4)^(-r/4)]^(s/r) + (H_RP^-8 + H_EP^-8)^(-s/8) }^(1/s), \
s = s0 (1 + exp(-s1 H_EI/H_RI)); H_RI = c_RI f_RI(D) D^e_RI M^-2, H_EI = a f_EI(D) D^e_EI \
M^alpha, H_RP = b f_RP(D) D^e_RP L^beta, H_EP = d f_EP(D) D^e_EP M^gamma L^delta, \
H_00 = c_00/D, with f_EI, f_EP NVM's D factors normalised to 1 at D = 1 and e_* free \
corrections (0 = NVM; held at 0 when the data have one D). H_RI is held: c_RI at the solver's \
rigid constant, its rigid solves extrapolated to an unbounded domain (35.5 for H_c and H_min, \
45.0 for H_pm; NVM 41.3), e_RI = 0, and f_RI = [(1 + a D^p)/(1 + a)]^q / D the solver's own \
(NVM: a = 0.796, p = 14/15, q = -15/7): a and p fitted to far-field rigid solves over D in \
[0.005, 1], q set by the exact slender limit D M^2 H_c -> 2 (2.4475 pi)^2 (times 3/2.4475 for \
H_pm). H_RP is held at the solver's rigid-piezoviscous limit alpha q_max = 1: b = c_RI pi(1), \
beta = 2/3, e_RP = 0, f_RP = f_RI(D) D psi(D), psi = [(1 + a D^p)/(1 + a)]^q with pi(D) = \
(alpha_bar(M = 1, L = 1) P_max)^(2/3) of the rigid solves = pi(1) D psi(D): a and p fitted to the \
same solves, q set by the exact slender limit pi(D) H_c(D) -> 1.0496 (the line's constant). \
H_EI and H_EP keep the exponents of asymptotic theory (M^(-2/15); M^(-1/12) L^(3/4)); \
their constants and D corrections are fitted, H_EP's first held at NVM's, then all of them and \
the blend (s0, s1, c_00, r: NVM's 1.5, 1.2, 1.8, 3/2) too (kept \
only if physical, identified and better) with 40 or more converged cases. C = sum c_k phi_k is \
the interior correction (as for line contacts, with ln D factors), its size chosen by 5-fold \
held-out error; a lattice correction of H_c or H_pm is multiplied by F = t((a - a_hi)/2) t((a_lo - a)/2), t(u) = 1 for u <= 0, \
(1 + cos(pi u))/2 for 0 < u < 1, 0 for u >= 1, with a_lo(ln D) and a_hi(ln D) the smallest and \
largest a = ln(H_EI/H_RI) of the fitted cases at each of their D, linear in ln D between them \
and held beyond (the support table below; formula.py `_fade`): beyond the data the formula is \
its blend. Where it lowers the held-out RMS and not its max, the law (corrected blend or \
corner law) is also multiplied by a kriging residual exp(k), k = sum_j w_j K(|z - z_j|_s): K the \
Matern 5/2 kernel, z = (a, max(c, c_floor), ln D) of each data case, scales s and nugget chosen \
by the same folds, w fitted to the law's log residuals; k falls to 0 away from the data and in \
every asymptotic limit. H_c is the film at the centre, H_pm the film at the pressure maximum on the \
centre line, H_min the minimum film: each has its own fit. Where the data show the corner at \
which H_c meets H_pm, H_c is the corner law of its section (with the asymptotes of its blend).";

/// What the point form says when the H_pm elastic-isoviscous law is held at its limit (the
/// default; H_c's too with `ehlmap fit --point-ei-limit`).
const POINT_EI_LIMIT: &str =
    " H_EI of H_pm (and of H_c with --point-ei-limit) is held at its limit, the \
line's 2.488 M^(-1/5) carried over by the local inlet analysis of the leading edge: a = 2.488 x \
0.941415 = 2.3422, f_EI(D) = k^(2/15) [4 E(m)/(pi (1 + D))]^(2/3) exact (k = a/b of the Hertz \
ellipse, E(m) its elliptic integral; 1 at D = 1), e_EI = 0, times the fitted approach factor \
g(M, D) = exp(sum_j (c_j0 + c_j1 ln D + c_j2 (ln D)^2) (1 + M_g)^(-p_j)), p = 4/15, 8/15 and \
12/15 (parameters g1, g1_lnD, g1_lnD2, g2, ..., g3_lnD2), which tends to 1 as M -> infinity: \
the solver's films approach the limit slowly. g is fitted first, by linear least squares on the \
cases at L = 0 and M >= 100 (each case's H_EI from its film by inverting the L = 0 blend) and, \
with `--anchors`, on the solver's films half a decade of M beyond the data; M_g = M without \
anchors (the third power then 0), M_g = (M^2 + 100^2)^(1/2) with them (`approach_m0` in \
fit.json), and held in the fit.";

/// The point formula's form for the contact's report `c`.
pub(super) fn point_form(c: &ContactReport) -> String {
    let held = c.h_pm.as_ref().and_then(|q| match &q.model.blend {
        Blend::Point(p) if p.ei_exact => Some(p.approach_m0),
        _ => None,
    });
    let mut s = POINT_FORM.to_string();
    if let Some(m0) = held {
        s.push_str(POINT_EI_LIMIT);
        if m0 > 0.0 {
            s.push_str(&format!(" This fit had anchors: M_0 = {m0}."));
        } else {
            s.push_str(" This fit had no anchors: M_g = M.");
        }
    }
    s
}
