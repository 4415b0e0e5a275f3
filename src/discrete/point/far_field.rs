//! The asymptotic far field of a point contact: boundary values and the load beyond the domain
//! from the self-similar decay of the pressure, instead of P = 0 on a truncated domain.
//!
//! Far from the contact the film is the rigid gap H ~ H_0 + X^2/2 + D Y^2/2 and P is small
//! (eta = rho = 1), so the Reynolds equation div(H^3 grad P) = lambda dH/dX is invariant under
//! (X, Y, P) -> (s X, s Y, s^-3 P) as R grows: along every ray from the centre X = Y = 0 the
//! pressure decays like P = A(phi) R^-3 (the rigid pressure's r^-3 decay;
//! docs/known-limits.md). With the film's offset kept, H = c (R^2 + a^2) along the ray
//! (c = (cos^2 phi + D sin^2 phi)/2), the cos(phi) mode for D = 1 is exactly
//! P = -lambda R cos(phi) / (10 c^3 (R^2 + a^2)^2), i.e. P proportional to R/H^2 along the ray: the
//! law used here for every D, with the far film H_0 + X^2/2 + D Y^2/2 + coef W/R of the current
//! H_0: the rigid gap plus the deformation of the whole load W as a point force (the leading
//! term of the deformation integral far from the contact; coef the film's deformation
//! coefficient; 0 for rigid surfaces). For an elastic contact H_0 lies far below the central
//! film, and leaving the deformation out biased the film low by up to 1 % at L = 0 (docs/
//! validation.md, "Far field"); kept as a fixed function of position, it leaves the relation a
//! function of P and H_0 alone, so that Newton's residual is a function of its unknowns.
//!
//! **Boundary values.** Each boundary node b at r_b takes the value of the decay law from the
//! point q = (1 - delta) r_b of its ray that lies one spacing of the coarsest grid inside the
//! domain: P_b = P(q) (R_b/R_q) (H(q)/H_b)^2, delta = h_n/(n . r_b) for the edge with outward
//! normal n and coarsest spacing h_n across it (at a corner, the larger of its two edges'
//! values; the same q on every level, so that all levels impose one relation), P(q) and H(q)
//! bilinear in the interior nodes around q ((1 - delta)^3 P(q), the pure power law, where the
//! rigid film is not positive). The relation is applied after every change of P (a slave
//! value, lagged by one sweep within the smoother), on every level with its own spacing.
//!
//! **Load.** The load is the trapezoidal integral over the domain plus the tail beyond it: the
//! ray sector behind a boundary segment of length ds at distance d_n = n . r_b from the centre
//! spans dphi = ds d_n / R_b^2 and carries dphi int_{R_b}^inf P(R) R dR with the law above,
//! P_b (H_b/c)^2 I / R_b dphi, I = int_{R_b}^inf R^2/(R^2 + a^2)^2 dR in closed form
//! (P_b ds d_n for a = 0). So the load is hx hy sum P + sum_b P_b (w_b + t_b - hx hy), w_b the
//! trapezoidal weight (hx hy/2 on an edge, hx hy/4 at a corner), t_b the tail weight.
//!
//! Invariants: the interpolation uses interior nodes only; P >= 0 in gives P_b >= 0; the same
//! relation on every level of a hierarchy. Not modelled: the deformation by the pressure beyond
//! the domain, and the far deformation's change along a ray beyond the boundary in the tail
//! integral (its film offset there is the boundary node's). Reference: the far-field
//! law of docs/physics.md section 6c; measurements in docs/validation.md ("Far field").

/// One boundary node's slave relation and load weight.
#[derive(Clone, Copy, Debug, PartialEq)]
struct FarNode {
    /// The boundary node.
    node: usize,
    /// The four interior nodes around q and their bilinear weights.
    corners: [(usize, f64); 4],
    /// 1 - delta = R_q/R_b.
    shrink: f64,
    /// R_b.
    r: f64,
    /// c = (cos^2 phi + D sin^2 phi)/2 of the node's ray.
    c: f64,
    /// sum over the node's edges of ds d_n.
    ds_dn: f64,
    /// w_b - hx hy: what the node's trapezoidal weight adds to hx hy.
    trapezoid_extra: f64,
    /// The load's far deformation at q (bilinear in the corners' values) and at the node.
    u_q: f64,
    u_b: f64,
}

/// I = int_{r}^inf R^2/(R^2 + a2)^2 dR for a2 > -r^2.
fn tail_integral(r: f64, a2: f64) -> f64 {
    if a2.abs() < 1e-6 * r * r {
        // The series in a2/r^2: 1/r - (2/3) a2/r^3.
        return 1.0 / r - 2.0 * a2 / (3.0 * r * r * r);
    }
    if a2 > 0.0 {
        let a = a2.sqrt();
        std::f64::consts::FRAC_PI_4 / a - (r / a).atan() / (2.0 * a) + r / (2.0 * (r * r + a2))
    } else {
        let b = (-a2).sqrt();
        r / (2.0 * (r * r - b * b)) - ((r - b) / (r + b)).ln() / (4.0 * b)
    }
}

/// One boundary node's relation as a Jacobian needs it (see [`FarField::slaves`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Slave {
    /// The boundary node.
    pub node: usize,
    /// dP_b/dP_c for the interior nodes c it depends on (at the current film).
    pub links: [(usize, f64); 4],
    /// What the node's load weight adds to hx hy (trapezoid and tail), and its derivative with
    /// respect to the film at the node.
    pub load_extra: f64,
    /// d(load_extra)/dH_b.
    pub d_load_extra_dh: f64,
}

/// The far-field relations of one grid level (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct FarField {
    nodes: Vec<FarNode>,
}

impl FarField {
    /// The relations of the grid with node coordinates `x` (nx values) and `y` (ny values),
    /// row-major with X fastest, for the gap X^2/2 + D Y^2/2; q lies one spacing of the
    /// coarsest grid, `coarse` = (hx, hy), inside the boundary, so that every level of a
    /// multigrid hierarchy imposes the same relation (to its interpolation error). The centre
    /// X = Y = 0 must lie inside the domain. `deform` = coef W, the deformation coefficient
    /// times the load (0 for rigid surfaces): the film's far deformation is `deform`/R.
    pub fn new(x: &[f64], y: &[f64], d: f64, coarse: (f64, f64), deform: f64) -> Self {
        let (nx, ny) = (x.len(), y.len());
        assert!(
            nx >= 4 && ny >= 4,
            "a far field needs 2 x 2 interior nodes at least"
        );
        let (hx, hy) = (x[1] - x[0], y[1] - y[0]);
        let (cx, cy) = (coarse.0.max(hx), coarse.1.max(hy));
        let (x_in, x_out, y_lo, y_hi) = (x[0], x[nx - 1], y[0], y[ny - 1]);
        assert!(x_in < 0.0 && x_out > 0.0 && y_lo < 0.0 && y_hi > 0.0);
        let mut nodes = vec![];
        for j in 0..ny {
            for i in 0..nx {
                // The edges the node lies on: (spacing across, distance of the edge, length
                // of the node's share of the edge).
                let mut edges: Vec<(f64, f64, f64)> = vec![];
                let along_y = if j == 0 || j + 1 == ny { hy / 2.0 } else { hy };
                let along_x = if i == 0 || i + 1 == nx { hx / 2.0 } else { hx };
                if i == 0 {
                    edges.push((cx, -x_in, along_y));
                }
                if i + 1 == nx {
                    edges.push((cx, x_out, along_y));
                }
                if j == 0 {
                    edges.push((cy, -y_lo, along_x));
                }
                if j + 1 == ny {
                    edges.push((cy, y_hi, along_x));
                }
                if edges.is_empty() {
                    continue;
                }
                let delta = edges
                    .iter()
                    .map(|&(h, d, _)| h / d)
                    .fold(0.0f64, f64::max)
                    .min(0.9);
                let (qx, qy) = ((1.0 - delta) * x[i], (1.0 - delta) * y[j]);
                let corners = bilinear(x, y, qx, qy);
                let trapezoid = hx * hy / f64::from(1u32 << edges.len());
                let r = x[i].hypot(y[j]);
                let (cos, sin) = (x[i] / r, y[j] / r);
                let far = |c: usize| deform / x[c % nx].hypot(y[c / nx]);
                let u_q = corners.iter().map(|&(c, w)| w * far(c)).sum();
                nodes.push(FarNode {
                    node: j * nx + i,
                    corners,
                    shrink: 1.0 - delta,
                    r,
                    c: 0.5 * (cos * cos + d * sin * sin),
                    ds_dn: edges.iter().map(|&(_, dn, ds)| ds * dn).sum(),
                    trapezoid_extra: trapezoid - hx * hy,
                    u_q,
                    u_b: deform / r,
                });
            }
        }
        FarField { nodes }
    }

    /// Set every boundary value from the interior, with the far film `h0 + gap + deform/R`
    /// (module docs).
    pub fn apply(&self, p: &mut [f64], gap: &[f64], h0: f64) {
        for n in &self.nodes {
            let v: f64 = n.corners.iter().map(|&(c, w)| w * p[c]).sum();
            let (hq, hb) = Self::films(n, gap, h0);
            p[n.node] = (Self::factor(n, hq, hb) * v).max(0.0);
        }
    }

    /// The far films at q and at the node.
    fn films(n: &FarNode, gap: &[f64], h0: f64) -> (f64, f64) {
        let hq: f64 = n.corners.iter().map(|&(c, w)| w * (h0 + gap[c])).sum();
        (hq + n.u_q, Self::film_b(n, gap, h0))
    }

    /// The far film at the node.
    fn film_b(n: &FarNode, gap: &[f64], h0: f64) -> f64 {
        h0 + gap[n.node] + n.u_b
    }

    /// P_b/P(q) for node `n` with the films `hq` at q and `hb` at the node.
    fn factor(n: &FarNode, hq: f64, hb: f64) -> f64 {
        if hq > 0.0 && hb > 0.0 {
            (hq / hb).powi(2) / n.shrink
        } else {
            n.shrink.powi(3)
        }
    }

    /// Every boundary node's relation with the far film (linear in P; its dependence on H_0
    /// left out), with its load weight: for Newton's Jacobian.
    pub fn slaves<'a>(&'a self, gap: &'a [f64], h0: f64) -> impl Iterator<Item = Slave> + 'a {
        self.nodes.iter().map(move |n| {
            let (hq, hb) = Self::films(n, gap, h0);
            let f = Self::factor(n, hq, hb);
            let dh = 1e-7 * hb.abs().max(1e-12);
            let extra = |h: f64| n.trapezoid_extra + self.tail_weight(n, h);
            Slave {
                node: n.node,
                links: n.corners.map(|(c, w)| (c, f * w)),
                load_extra: extra(hb),
                d_load_extra_dh: (extra(hb + dh) - extra(hb - dh)) / (2.0 * dh),
            }
        })
    }

    /// The boundary nodes, in order.
    pub fn boundary(&self) -> impl Iterator<Item = usize> + '_ {
        self.nodes.iter().map(|n| n.node)
    }

    /// What the far field adds to hx hy sum P with the far film: the trapezoidal edge weights
    /// and the tail beyond the domain.
    pub fn load_correction(&self, p: &[f64], gap: &[f64], h0: f64) -> f64 {
        self.nodes
            .iter()
            .map(|n| {
                (n.trapezoid_extra + self.tail_weight(n, Self::film_b(n, gap, h0))) * p[n.node]
            })
            .sum()
    }

    /// t_b of node `n` with the film `hb` there (module docs; the pure power law's ds d_n
    /// while the film does not give R^2 + a^2 > 0).
    fn tail_weight(&self, n: &FarNode, hb: f64) -> f64 {
        let r2a2 = hb / n.c;
        if r2a2.is_nan() || r2a2 <= 0.0 {
            return n.ds_dn;
        }
        let a2 = r2a2 - n.r * n.r;
        n.ds_dn * r2a2 * r2a2 * tail_integral(n.r, a2) / n.r.powi(3)
    }
}

/// The interior nodes around (qx, qy) and their bilinear weights (cells clamped to the
/// interior: nodes 1..n-2 in each direction).
fn bilinear(x: &[f64], y: &[f64], qx: f64, qy: f64) -> [(usize, f64); 4] {
    let (nx, ny) = (x.len(), y.len());
    let cell = |v: &[f64], q: f64, n: usize| {
        let h = v[1] - v[0];
        let k = (((q - v[0]) / h).floor() as isize).clamp(1, n as isize - 3) as usize;
        (k, (q - v[k]) / h)
    };
    let (i, tx) = cell(x, qx, nx);
    let (j, ty) = cell(y, qy, ny);
    [
        (j * nx + i, (1.0 - tx) * (1.0 - ty)),
        (j * nx + i + 1, tx * (1.0 - ty)),
        ((j + 1) * nx + i, (1.0 - tx) * ty),
        ((j + 1) * nx + i + 1, tx * ty),
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(x0: f64, x1: f64, yh: f64, n: usize) -> (Vec<f64>, Vec<f64>) {
        let x = (0..=n)
            .map(|i| x0 + (x1 - x0) * i as f64 / n as f64)
            .collect();
        let y = (0..=n)
            .map(|j| -yh + 2.0 * yh * j as f64 / n as f64)
            .collect();
        (x, y)
    }

    /// The rigid gap R^2/2 (D = 1) at every node.
    fn gap(x: &[f64], y: &[f64]) -> Vec<f64> {
        let nx = x.len();
        (0..nx * y.len())
            .map(|c| 0.5 * (x[c % nx].powi(2) + y[c / nx].powi(2)))
            .collect()
    }

    #[test]
    fn the_tail_integral_in_closed_form_matches_quadrature() {
        for (r, a2) in [
            (6.0, 4.0),
            (6.0, -9.0),
            (6.0, 1e-9),
            (20.0, 30.0),
            (3.0, -8.5),
        ] {
            // Substitution R = r/t: int_0^1 r^3/(t^4 (r^2/t^2 + a2)^2) dt... by the midpoint
            // rule on R = r/t, dR = r/t^2 dt.
            let n = 200_000;
            let mut q = 0.0;
            for k in 0..n {
                let t = (k as f64 + 0.5) / n as f64;
                let rr = r / t;
                q += rr * rr / (rr * rr + a2).powi(2) * r / (t * t) / n as f64;
            }
            let i = tail_integral(r, a2);
            assert!((i / q - 1.0).abs() < 1e-6, "r {r} a2 {a2}: {i} vs {q}");
        }
    }

    #[test]
    fn with_a_film_offset_the_law_follows_r_over_h_squared() {
        // H = (R^2 + a^2)/2 (D = 1): the boundary values follow P = A R/(R^2 + a^2)^2, the exact
        // cos mode (module docs), to the interpolation error.
        let a2 = 30.0;
        let (x, y) = grid(-9.0, 3.0, 6.0, 64);
        let nx = x.len();
        let f = |x: f64, y: f64| {
            let r2 = x * x + y * y;
            if r2 < 1.0 {
                0.0
            } else {
                amplitude(-x / r2.sqrt()) * r2.sqrt() / (r2 + a2).powi(2)
            }
        };
        let mut p: Vec<f64> = (0..nx * y.len()).map(|c| f(x[c % nx], y[c / nx])).collect();
        let exact = p.clone();
        let ff = FarField::new(&x, &y, 1.0, (0.0, 0.0), 0.0);
        ff.apply(&mut p, &gap(&x, &y), 0.5 * a2);
        let worst = ff
            .boundary()
            .map(|b| ((p[b] - exact[b]) / exact[b]).abs())
            .fold(0.0f64, f64::max);
        assert!(worst < 3e-3, "{worst}");
        // The pure power law would be off by the film offset (several per cent here).
        let mut q = exact.clone();
        ff.apply(&mut q, &gap(&x, &y), 0.0);
        let off = ff
            .boundary()
            .map(|b| ((q[b] - exact[b]) / exact[b]).abs())
            .fold(0.0f64, f64::max);
        assert!(off > 10.0 * worst, "{off} vs {worst}");
    }

    /// A smooth A(phi), c = -cos(phi) (1 towards the inlet).
    fn amplitude(c: f64) -> f64 {
        1.0 + 0.8 * c + 0.3 * c * c
    }

    /// A field of the decay law A(phi) R^-3 (0 within R = 1).
    fn law(x: f64, y: f64) -> f64 {
        let r = (x * x + y * y).sqrt();
        if r < 1.0 {
            return 0.0;
        }
        amplitude(-x / r) * r.powi(-3)
    }

    #[test]
    fn boundary_values_follow_the_decay_law_at_second_order() {
        // The relation is exact for A R^-3 up to the bilinear interpolation of P(q): its error
        // falls like h^2.
        let mut errs = vec![];
        for n in [16usize, 32, 64] {
            let (x, y) = grid(-9.0, 3.0, 6.0, n);
            let ff = FarField::new(&x, &y, 1.0, (0.0, 0.0), 0.0);
            let nx = x.len();
            let mut p: Vec<f64> = (0..nx * y.len())
                .map(|c| law(x[c % nx], y[c / nx]))
                .collect();
            let film = gap(&x, &y);
            let exact = p.clone();
            for b in ff.boundary() {
                p[b] = 0.0;
            }
            ff.apply(&mut p, &film, 0.0);
            let worst = ff
                .boundary()
                .map(|b| ((p[b] - exact[b]) / exact[b]).abs())
                .fold(0.0f64, f64::max);
            errs.push(worst);
        }
        assert!(errs[2] < 2e-3, "{errs:?}");
        let rate = (errs[1] / errs[2]).log2();
        assert!(rate > 1.7, "rate {rate}, {errs:?}");
    }

    #[test]
    fn the_load_with_its_tail_is_the_integral_over_the_plane() {
        // What the far field adds to the trapezoidal sum over the domain is the tail of the law
        // beyond the rectangle: compare with the exact integral outside the rectangle by a fine
        // polar quadrature.
        let (x, y) = grid(-8.0, 4.0, 6.0, 96);
        let ff = FarField::new(&x, &y, 1.0, (0.0, 0.0), 0.0);
        let nx = x.len();
        let p: Vec<f64> = (0..nx * y.len())
            .map(|c| law(x[c % nx], y[c / nx]))
            .collect();
        let (hx, hy) = (x[1] - x[0], y[1] - y[0]);
        let load = hx * hy * p.iter().sum::<f64>() + ff.load_correction(&p, &gap(&x, &y), 0.0);
        // The exact tail: for each angle, from the rectangle's edge to infinity.
        let n_phi = 200_000;
        let mut tail = 0.0;
        for k in 0..n_phi {
            let phi = (k as f64 + 0.5) / n_phi as f64 * std::f64::consts::TAU;
            let (c, s) = (phi.cos(), phi.sin());
            let rx = if c > 0.0 { 4.0 / c } else { 8.0 / -c };
            let ry = 6.0 / s.abs();
            let r_b = rx.min(ry);
            // int_{r_b}^inf A R^-3 R dR = A / r_b
            tail += amplitude(-c) / r_b * std::f64::consts::TAU / n_phi as f64;
        }
        // The trapezoidal rule of the interior on the same grid (no tail).
        let mut inner = 0.0;
        for j in 0..y.len() {
            for i in 0..nx {
                let w = if i == 0 || i + 1 == nx { 0.5 } else { 1.0 }
                    * if j == 0 || j + 1 == y.len() { 0.5 } else { 1.0 };
                inner += w * hx * hy * p[j * nx + i];
            }
        }
        let tail_discrete = load - inner;
        assert!(
            (tail_discrete / tail - 1.0).abs() < 5e-3,
            "{tail_discrete} vs {tail}"
        );
    }
}
