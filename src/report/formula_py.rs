//! `formula.py`: the fitted formulas as a standalone Python module (standard library only) whose
//! `H(M, L, D=None, film="H_c")` reproduces [`FittedModel::eval`] operation by operation (the
//! blend of [`crate::fit::model`] / [`crate::fit::point_model`] times the correction of
//! [`crate::fit::correction`], for the point H_min times the side-lobe factor of
//! [`crate::fit::side`], for an H_c with a corner the law of [`crate::fit::corner`] in place of
//! the correction; times the kriging residual of [`crate::fit::kriging`] where the law has one);
//! `D=None` is the line formula, a number the point formula. Every parameter is written with the
//! shortest decimal that reads back to the same f64, so Python and Rust agree to rounding
//! (tests/formula_py.rs: 1e-12 relative). Overflow in Python (which raises where Rust gives
//! infinity) is caught and mapped to infinity, as in the Rust evaluation.

use crate::fit::corner::{Corner, DEFICIT_POWER};
use crate::fit::correction::{Correction, Transition, LATTICE, TAIL};
use crate::fit::fitted::{Blend, FittedModel};
use crate::fit::kriging::Kriging;
use crate::fit::side::SideLobe;
use crate::fit::support::{Support, FADE_WIDTH};
use crate::report::{ContactReport, FitReport};
use std::fmt::Write;

const HEADER: &str = r#""""Film-thickness formulas fitted by ehlmap (`ehlmap fit`), in Moes' dimensionless units.

H(M, L, D=None, film="H_c"): the film "H_c" (centre), "H_pm" (at the pressure maximum) or "H_min"
of a line contact (D=None) or of a point contact of ellipticity D = Rx/Ry. Each formula is a blend
of four asymptotes (rigid/elastic x isoviscous/piezoviscous) times an interior correction that
vanishes wherever one asymptote dominates (docs/method.md of ehlmap). Standard library only.
"""
import math

INF = float("inf")
TAIL = {TAIL}
LATTICE = {LATTICE}
FADE_WIDTH = {FADE_WIDTH}


def _pow(a, b):
    try:
        return a ** b
    except OverflowError:
        return INF
    except ZeroDivisionError:
        return INF


def _exp(a):
    try:
        return math.exp(a)
    except OverflowError:
        return INF


def _cosh(a):
    try:
        return math.cosh(a)
    except OverflowError:
        return INF


def _line_asymptotes(x, c_ri, M, L):
    return [
        c_ri / M,
        _exp(x[0]) * _pow(M, x[1]),
        _exp(x[2]) * _pow(L, x[3]),
        _exp(x[4]) * _pow(M, x[5]) * _pow(L, x[6]),
    ]


def _line_blend(x, c_ri, M, L):
    h_ri, h_ei, h_rp, h_ep = _line_asymptotes(x, c_ri, M, L)
    decay = _exp(-x[11] * h_ei / h_ri)
    p, q = x[7] + x[12] * decay, x[8]
    s = x[9] + x[10] * decay
    iso = _pow(_pow(h_ri, p) + _pow(h_ei, p), s / p)
    piezo = _pow(_pow(h_rp, -q) + _pow(h_ep, -q), -s / q) if L > 0.0 else 0.0
    return _pow(iso + piezo, 1.0 / s)


def _nvm_d_factors(D):
    c = (1.0 + 0.006 * math.log(D) + 0.63 * _pow(D, 4.0 / 7.0)) / 1.63
    return [
        _pow((1.0 + 0.796 * _pow(D, 14.0 / 15.0)) / 1.796, -15.0 / 7.0) / D,
        _pow(c, -14.0 / 25.0) * _pow(D, -1.0 / 15.0),
        _pow((1.0 + 0.691 * D) / 1.691, -2.0 / 3.0),
        _pow(c, -7.0 / 20.0) * _pow(D, -1.0 / 24.0),
    ]


def _psi(shape, D):
    a, p, q = shape
    return _pow((1.0 + a * _pow(D, p)) / (1.0 + a), q)


def _agm(kc):
    a, b, t, w = 1.0, kc, 0.0, 1.0
    for _ in range(80):
        c = 0.5 * (a - b)
        t += w * c * c
        a, b = 0.5 * (a + b), math.sqrt(a * b)
        w *= 2.0
        if abs(c) <= 1e-10 * a:
            break
    return math.pi / (2.0 * a), t


def _d_from_kappa(kappa):
    m = (1.0 - kappa) * (1.0 + kappa)
    t = _agm(kappa)[1]
    return kappa * kappa * (0.5 * m + t) / (0.5 * m - t)


def _ei_d_factor(D):
    """The exact D factor k^(2/15) [4 E(m)/(pi (1 + D))]^(2/3) of the point elastic-isoviscous law."""
    if D == 1.0:
        return 1.0
    f = lambda u: math.log(_d_from_kappa(math.exp(u))) - math.log(D)
    lo, hi = -1.0, 0.0
    while f(lo) > 0.0:
        lo, hi = 2.0 * lo, lo
    for _ in range(200):
        mid = 0.5 * (lo + hi)
        if mid in (lo, hi):
            break
        if f(mid) > 0.0:
            hi = mid
        else:
            lo = mid
    kappa = math.exp(0.5 * (lo + hi))
    k_int, t = _agm(kappa)
    e_int = k_int * (1.0 - 0.5 * (1.0 - kappa) * (1.0 + kappa) - t)
    return (1.0 / kappa) ** (2.0 / 15.0) * (4.0 * e_int / (math.pi * (1.0 + D))) ** (2.0 / 3.0)


def _approach(x, m0, M, D):
    ln_d = math.log(D)
    m_g = math.hypot(M, m0)
    total = 0.0
    for j, p in enumerate((4.0 / 15.0, 8.0 / 15.0, 12.0 / 15.0)):
        c = x[16 + 3 * j : 19 + 3 * j]
        total += (c[0] + ln_d * (c[1] + ln_d * c[2])) * _pow(1.0 + m_g, -p)
    return _exp(total)


def _point_asymptotes(x, ri_shape, rp_shape, ei_exact, m0, M, L, D):
    f = _nvm_d_factors(D)
    f[0] = _psi(ri_shape, D) / D
    if rp_shape is not None:
        f[2] = f[0] * D * _psi(rp_shape, D)
    if ei_exact:
        f[1] = _ei_d_factor(D)
    return [
        _exp(x[0]) * f[0] * _pow(D, x[1]) / (M * M),
        _exp(x[2]) * _pow(M, x[3]) * f[1] * _pow(D, x[4]) * _approach(x, m0, M, D),
        _exp(x[5]) * _pow(L, x[6]) * f[2] * _pow(D, x[7]),
        _exp(x[8]) * _pow(M, x[9]) * _pow(L, x[10]) * f[3] * _pow(D, x[11]),
    ]


def _point_blend(x, ri_shape, rp_shape, ei_exact, m0, M, L, D):
    h_ri, h_ei, h_rp, h_ep = _point_asymptotes(x, ri_shape, rp_shape, ei_exact, m0, M, L, D)
    h_00 = _exp(x[14]) / D
    s = x[12] * (1.0 + _exp(-x[13] * h_ei / h_ri))
    r = x[15]
    ei = _pow(_pow(h_ei, -4) + _pow(h_00, -4), -r / 4.0)
    iso = _pow(_pow(h_ri, r) + ei, s / r)
    piezo = _pow(_pow(h_rp, -8) + _pow(h_ep, -8), -s / 8.0) if L > 0.0 else 0.0
    return _pow(iso + piezo, 1.0 / s)


def _bump(t):
    return 2.0 / (1.0 + _cosh(t))


def _tail(a):
    if a < 0.0:
        return _exp(a - a / TAIL) / (_exp(a) + 1.0)
    return _exp(-a / TAIL) / (1.0 + _exp(-a))


def _coords(asym, D):
    """The coordinates (a, b, c, ln D, w) of the blend's asymptotes."""
    ri, ei, rp, ep = asym
    hi, lo = max(ri, ei), min(ri, ei)
    iso = hi * _pow(1.0 + _pow(lo / hi, 4), 0.25)
    if rp > 0.0 and ep > 0.0:
        hi, lo = max(rp, ep), min(rp, ep)
        piezo = lo * _pow(1.0 + _pow(lo / hi, 4), -0.25)
        b, c = math.log(ep / rp), math.log(piezo / iso)
    else:
        b, c = float("nan"), -INF
    a = math.log(ei / ri)
    w = 1.0 / (1.0 + _exp(-c))
    return (a, b, c, math.log(D), w)


def _taper(u):
    if u <= 0.0:
        return 1.0
    if u >= 1.0:
        return 0.0
    return 0.5 * (1.0 + math.cos(math.pi * u))


def _fade(support, a, ln_d):
    """1 within the fitted cases' range of a at ln D, 0 FADE_WIDTH beyond it (ehlmap
    src/fit/support.rs)."""
    i, j, w = _interval(support["ln_d"], ln_d)
    lo = (1.0 - w) * support["lo"][i] + w * support["lo"][j]
    hi = (1.0 - w) * support["hi"][i] + w * support["hi"][j]
    return _taper((a - hi) / FADE_WIDTH) * _taper((lo - a) / FADE_WIDTH)


def _correction(terms, asym, D, support=None):
    """sum c_k phi_k (times the fade of its support, when it has one); terms = [(transition,
    (i, j, k, l, n), c, (lattice i, j, level)), ...]."""
    if not terms:
        return 0.0
    variables = _coords(asym, D)
    a, b, c, _, w = variables
    total = 0.0
    for transition, powers, coef, at in terms:
        lw = LATTICE * 0.5 ** at[2]
        if transition == "isoviscous":
            base = _bump(a) * (1.0 - w)
        elif transition == "tail":
            base = _tail(a) * (1.0 - w)
        elif transition == "shifted":
            base = _bump(a / lw - at[0]) * (1.0 - w)
        elif c == -INF:
            base = 0.0
        elif transition == "piezoviscous":
            base = _bump(b) * w
        elif transition == "cell":
            base = _bump(a / lw - at[0]) * _bump(c / lw - at[1])
        else:
            base = _bump(c)
        if base != 0.0:
            for v, k in zip(variables, powers):
                if k > 0:
                    base *= v ** k
        total += coef * base
    if support is not None and total != 0.0:
        total *= _fade(support, a, math.log(D))
    return total


def _interval(nodes, x):
    """The interval of x among increasing nodes and its weight in [0, 1] (clamped)."""
    n = len(nodes)
    if n < 2 or x <= nodes[0]:
        return 0, 0, 0.0
    if x >= nodes[-1]:
        return n - 1, n - 1, 0.0
    i = 1
    while nodes[i] <= x:
        i += 1
    return i - 1, i, (x - nodes[i - 1]) / (nodes[i] - nodes[i - 1])


def _ln_m_jump(table, L, D):
    """ln M_j(L, D): bilinear in (ln(1 + L), ln D) on the table, clamped to its box (ehlmap
    src/limits/jump.rs)."""
    i0, i1, u = _interval(table["ln_l1"], math.log1p(L))
    j0, j1, v = _interval(table["ln_d"], math.log(D))
    m = table["ln_m"]
    return (1.0 - u) * ((1.0 - v) * m[i0][j0] + v * m[i0][j1]) + u * (
        (1.0 - v) * m[i1][j0] + v * m[i1][j1]
    )


def _kriging(k, asym, M, L, D):
    """The kriging residual of a law at the coordinates (a, max(c, c_floor), ln D) of its
    asymptotes, and phi = tanh(ln(M / M_j) / width) with a corner coordinate (ehlmap
    src/fit/kriging.rs)."""
    a, _, c, ln_d, _ = _coords(asym, D)
    if math.isfinite(c):
        c = max(c, k["c_floor"])
    elif c < 0.0:
        c = k["c_floor"]
    jump = k.get("jump")
    if jump is None:
        return _kriging_at(k, (a, c, ln_d))
    phi = math.tanh((math.log(M) - _ln_m_jump(jump["table"], L, D)) / jump["width"])
    return _kriging_at(k, (a, c, ln_d), (phi, k["phis"], jump["scale"]))


def _kriging_at(k, x, phi=None):
    """sum_j w_j K(|x - z_j|_s), K the Matern 5/2 kernel; phi = (its value, the centres',
    its scale) adds the corner coordinate."""
    s = k["scales"]
    total = 0.0
    for j, (z, w) in enumerate(zip(k["centres"], k["weights"])):
        d2 = 0.0
        for i in range(3):
            t = x[i] - z[i]
            if t != 0.0:
                t /= s[i]
                d2 += t * t
        if phi is not None:
            t = phi[0] - phi[1][j]
            if t != 0.0:
                t /= phi[2]
                d2 += t * t
        if math.isfinite(d2):
            r = math.sqrt(5.0) * math.sqrt(d2)
            total += w * ((1.0 + r + r * r / 3.0) * _exp(-r))
    return total


def _logistic(t):
    if t >= 0.0:
        return 1.0 / (1.0 + _exp(-t))
    e = _exp(t)
    return e / (1.0 + e)


def _corner(k, blend, asym, D):
    """H_c through its corner on its blend: R exp(-rho (max(0, h) / rho)^power), R = blend
    exp(rho r + C_R), h = rho r + C_h, C_R and C_h faded beyond their supports when they have
    them (ehlmap src/fit/corner.rs)."""
    a, b, _, _, w = _coords(asym, D)
    r = _logistic(-a)
    if w > 0.0 and math.isfinite(b):
        r = (1.0 - w) * r + w * _logistic(b)
    rho = k["rho"]
    ln_r = rho * r + _correction(k["branch"], asym, D, k.get("branch_support"))
    h = rho * r + _correction(k["deficit"], asym, D, k.get("deficit_support"))
    right = blend * _exp(ln_r)
    return right * _exp(-(rho * (max(0.0, h) / rho) ** k["power"]))


def _side(side, M, L, D):
    """The side-lobe factor exp(-max(0, max(0, g) - r k)) of the point H_min (1 without one)."""
    if side is None:
        return 1.0
    x = (math.log(M), math.log(D), math.log1p(L))
    r = 1.0
    for key, v in (("ramp", x[0]), ("ramp_d", x[1])):
        if side.get(key) is not None:
            a, b = side[key]
            r *= min(max((v - a) / (b - a), 0.0), 1.0)
    if r == 0.0:
        return 1.0
    t = []
    for v, lo, hi in zip(x, side["lo"], side["hi"]):
        w = hi - lo
        t.append(min(max(2.0 * (v - lo) / w - 1.0, -1.0), 1.0) if w > 0.0 else 0.0)
    g = 0.0
    for powers, coef in zip(side["powers"], side["coef"]):
        m = 1.0
        for v, k in zip(t, powers):
            m *= v ** k
        g += coef * m
    big_g = max(0.0, r * g)
    if side.get("kriging") is not None:
        xc = [min(max(v, lo), max(hi, lo)) for v, lo, hi in zip(x, side["lo"], side["hi"])]
        big_g = big_g - r * _kriging_at(side["kriging"], (xc[0], xc[2], xc[1]))
    return _exp(-max(0.0, big_g))

"#;

fn f(v: f64) -> String {
    format!("{v:?}")
}

fn transition(t: Transition) -> &'static str {
    match t {
        Transition::Isoviscous => "isoviscous",
        Transition::Piezoviscous => "piezoviscous",
        Transition::Outer => "outer",
        Transition::Tail => "tail",
        Transition::Shifted => "shifted",
        Transition::Cell => "cell",
    }
}

fn terms(c: &Correction) -> String {
    let rows: Vec<String> = c
        .terms
        .iter()
        .zip(&c.coef)
        .map(|(t, k)| {
            let p = t.powers;
            format!(
                "(\"{}\", ({}, {}, {}, {}, {}), {}, ({}, {}, {}))",
                transition(t.transition),
                p[0],
                p[1],
                p[2],
                p[3],
                p[4],
                f(*k),
                t.at[0],
                t.at[1],
                t.level
            )
        })
        .collect();
    format!("[{}]", rows.join(", "))
}

fn list(v: &[f64]) -> String {
    v.iter().map(|v| f(*v)).collect::<Vec<_>>().join(", ")
}

fn side(s: Option<&SideLobe>) -> String {
    let Some(s) = s else {
        return "None".to_string();
    };
    let powers: Vec<String> = s
        .powers
        .iter()
        .map(|p| format!("({}, {}, {})", p[0], p[1], p[2]))
        .collect();
    format!(
        "{{\"lo\": [{}], \"hi\": [{}], \"powers\": [{}], \"coef\": [{}], \"ramp\": {}, \"ramp_d\": {}, \"kriging\": {}}}",
        list(&s.lo),
        list(&s.hi),
        powers.join(", "),
        list(&s.coef),
        s.ramp
            .map_or("None".to_string(), |r| format!("[{}]", list(&r))),
        s.ramp_d
            .map_or("None".to_string(), |r| format!("[{}]", list(&r))),
        kriging(s.kriging.as_ref())
    )
}

/// The kriging residual of a law (None without one).
fn kriging(k: Option<&Kriging>) -> String {
    let Some(k) = k else {
        return "None".to_string();
    };
    let centres: Vec<String> = k.centres.iter().map(|c| format!("[{}]", list(c))).collect();
    let jump = k.jump.as_ref().map_or("None".to_string(), |j| {
        let rows: Vec<String> = j.table.ln_m.iter().map(|r| format!("[{}]", list(r))).collect();
        format!(
            "{{\"table\": {{\"ln_l1\": [{}], \"ln_d\": [{}], \"ln_m\": [{}]}}, \"width\": {}, \"scale\": {}}}",
            list(&j.table.ln_l1),
            list(&j.table.ln_d),
            rows.join(", "),
            f(j.width),
            f(j.scale)
        )
    });
    format!(
        "{{\"scales\": [{}], \"c_floor\": {}, \"centres\": [{}], \"weights\": [{}], \"jump\": {}, \"phis\": [{}]}}",
        list(&k.scales),
        f(k.c_floor),
        centres.join(", "),
        list(&k.weights),
        jump,
        list(&k.phis)
    )
}

/// The range of a of a correction's cases at each ln D (None without one).
fn support(s: Option<&Support>) -> String {
    s.map_or("None".to_string(), |s| {
        format!(
            "{{\"ln_d\": [{}], \"lo\": [{}], \"hi\": [{}]}}",
            list(&s.ln_d),
            list(&s.lo),
            list(&s.hi)
        )
    })
}

/// The corner law of an H_c (None without one).
fn corner(c: Option<&Corner>) -> String {
    let Some(c) = c else {
        return "None".to_string();
    };
    format!(
        "{{\"branch\": {}, \"deficit\": {}, \"branch_support\": {}, \"deficit_support\": {}, \"rho\": {}, \"power\": {}}}",
        terms(&c.branch),
        terms(&c.deficit),
        support(c.branch.support.as_ref()),
        support(c.deficit.support.as_ref()),
        f(c.rho),
        f(DEFICIT_POWER)
    )
}

fn entry(m: &FittedModel) -> String {
    match &m.blend {
        Blend::Line(x) => format!(
            "{{\"c_ri\": {}, \"x\": [{}], \"terms\": {}, \"corner\": {}, \"kriging\": {}}}",
            f(x.c_ri),
            x.x.iter().map(|v| f(*v)).collect::<Vec<_>>().join(", "),
            terms(&m.correction),
            corner(m.corner.as_ref()),
            kriging(m.kriging.as_ref())
        ),
        Blend::Point(x) => format!(
            "{{\"x\": [{}], \"ri_shape\": [{}], \"rp_shape\": {}, \"ei_exact\": {}, \"approach_m0\": {}, \"terms\": {}, \"support\": {}, \"side\": {}, \"corner\": {}, \"kriging\": {}}}",
            list(&x.x),
            list(&x.ri_shape),
            x.rp_shape
                .map_or("None".to_string(), |r| format!("[{}]", list(&r))),
            if x.ei_exact { "True" } else { "False" },
            f(x.approach_m0),
            terms(&m.correction),
            support(m.correction.support.as_ref()),
            side(m.side.as_ref()),
            corner(m.corner.as_ref()),
            kriging(m.kriging.as_ref())
        ),
    }
}

fn table(name: &str, c: &ContactReport) -> String {
    let mut s = format!("{name} = {{\n");
    for q in [&c.h_c, &c.h_pm, &c.h_min].into_iter().flatten() {
        let _ = writeln!(s, "    \"{}\": {},", q.quantity, entry(&q.model));
    }
    s.push_str("}\n");
    s
}

const FOOTER: &str = r#"

def H(M, L, D=None, film="H_c"):
    """The fitted film at (M, L) of a line contact (D=None) or at (M, L, D) of a point contact."""
    if D is None:
        if film not in LINE:
            raise ValueError(f"no line formula for {film} (fitted: {sorted(LINE)})")
        e = LINE[film]
        asym = _line_asymptotes(e["x"], e["c_ri"], M, L)
        blend = _line_blend(e["x"], e["c_ri"], M, L)
        if e.get("corner") is not None:
            h = _corner(e["corner"], blend, asym, 1.0)
        else:
            h = blend * _exp(_correction(e["terms"], asym, 1.0))
        if e.get("kriging") is not None:
            h = h * _exp(_kriging(e["kriging"], asym, M, L, 1.0))
        return h
    if film not in POINT:
        raise ValueError(f"no point formula for {film} (fitted: {sorted(POINT)})")
    e = POINT[film]
    shapes = (e["ri_shape"], e.get("rp_shape"), e.get("ei_exact", False), e.get("approach_m0", 0.0))
    asym = _point_asymptotes(e["x"], *shapes, M, L, D)
    blend = _point_blend(e["x"], *shapes, M, L, D)
    if e.get("corner") is not None:
        h = _corner(e["corner"], blend, asym, D)
    else:
        h = blend * _exp(_correction(e["terms"], asym, D, e.get("support")))
    if e.get("kriging") is not None:
        h = h * _exp(_kriging(e["kriging"], asym, M, L, D))
    return h * _side(e.get("side"), M, L, D)
"#;

/// The text of `formula.py` for the report's fitted formulas (a contact not fitted gives an
/// empty table, and `H` then names the films it has).
pub fn formula_py(r: &FitReport) -> String {
    let mut s = HEADER
        .replace("{TAIL}", &f(TAIL))
        .replace("{LATTICE}", &f(LATTICE))
        .replace("{FADE_WIDTH}", &f(FADE_WIDTH));
    s.push_str(&table("LINE", &r.line));
    s.push('\n');
    s.push_str(&table("POINT", &r.point));
    s.push_str(FOOTER);
    s
}
