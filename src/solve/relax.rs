//! The relaxation constants ([`RelaxParams`], [`Smoother`]) and the steps of a banded line
//! solve that do not depend on the contact, used by the line smoother
//! ([`crate::solve::line::relax`]) and the point contact's x-line smoother
//! ([`crate::solve::point::relax`]): how a node enters the system ([`node_kind`],
//! [`distributed`], [`xi`]), its row ([`pinned_row`], [`distributed_row`]), and the change it
//! gets ([`undistributed`], [`relaxed`], [`viscosity_step_limit`]). Contract: a line of n nodes,
//! nodes 0 and n-1 fixed, unknowns 1..=n-2 in rows 0..n-2 of a banded matrix of half bandwidth
//! bw (row i-1 holds column j at j + bw - i).

/// Which smoother.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Smoother {
    /// Whole-line relaxation (default): one banded solve per sweep.
    #[default]
    Line,
    /// The classic point-by-point Gauss-Seidel / distributive Jacobi sweep.
    Point,
}

/// Relaxation constants.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RelaxParams {
    /// Which smoother: whole-line relaxation (default) or the classic point smoother.
    pub smoother: Smoother,
    /// Under-relaxation of the line smoother.
    pub omega_line: f64,
    /// Under-relaxation of the point smoother's Gauss-Seidel updates.
    pub omega_gs: f64,
    /// Under-relaxation of the point smoother's distributive Jacobi updates.
    pub omega_ja: f64,
    /// xi = min(eps at the node's faces along x)/h^2 below which a node is relaxed in
    /// distributed variables (distributive Jacobi in the point smoother).
    pub xi_threshold: f64,
    /// Half bandwidth of the line system (kernel terms kept exactly within it).
    pub band: usize,
    /// Freeze eps in the line system (Picard) instead of the exact local derivatives.
    pub picard: bool,
    /// The fraction of its pressure by which a node may change in one sweep even where the
    /// viscosity step limit is smaller ([`relaxed`]; 0: the viscosity limit alone). The line
    /// contact uses 1/4: a one-node pressure spike that must rise on a finer grid then does
    /// so in a few sweeps instead of by 2/alpha_bar per sweep. The point contact keeps 0: at
    /// L = 20 on 513^2 the larger steps make its cycles diverge.
    pub relative_step: f64,
    /// Line contacts: Newton windows at the outlet spike after each sweep
    /// ([`crate::solve::line::spike`]); `None` (the default) runs none.
    pub spike_newton: Option<SpikeNewton>,
}

/// Settings of the line smoother's Newton windows at the outlet spike
/// ([`crate::solve::line::spike::spike_newton`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SpikeNewton {
    /// A node opens a window where its |r| exceeds this factor times the mean |r| over the
    /// pressurised nodes.
    pub factor: f64,
    /// Newton steps per window and sweep, at most.
    pub iterations: usize,
    /// Levels with fewer points are left alone.
    pub min_points: usize,
}

impl Default for RelaxParams {
    fn default() -> Self {
        RelaxParams {
            smoother: Smoother::Line,
            omega_line: 0.5,
            omega_gs: 0.6,
            omega_ja: 0.3,
            xi_threshold: 100.0,
            band: 4,
            picard: false,
            relative_step: 0.0,
            spike_newton: None,
        }
    }
}

/// How a node of a line enters the banded system.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// Pressurised: its equation L = f is relaxed.
    Active,
    /// Cavitated: its row is dP = -P (the complementarity condition sets P = 0).
    Cavitated,
    /// Held fixed (boundary, or a frozen coarse node): its row is dP = 0.
    Frozen,
}

/// The kind of a node from its residual r = f - L and diagonal d = dL/dP: frozen when `frozen`,
/// cavitated when its Newton point value P + r/d is <= 0 (d < 0) or P <= 0 (d >= 0), else active.
#[inline]
pub fn node_kind(frozen: bool, p: f64, r: f64, d: f64) -> Kind {
    if frozen {
        Kind::Frozen
    } else if (d < 0.0 && p + r / d <= 0.0) || (d >= 0.0 && p <= 0.0) {
        Kind::Cavitated
    } else {
        Kind::Active
    }
}

/// xi = min(eps_{c-1/2}, eps_{c+1/2})/h^2 along x at storage index c (h2 = h^2).
#[inline]
pub fn xi(eps: &[f64], c: usize, h2: f64) -> f64 {
    0.5 * (eps[c - 1] + eps[c]).min(eps[c] + eps[c + 1]) / h2
}

/// Whether node i of a line (`kind` over all its nodes) is distributed: it and both neighbours
/// are active and `low_xi()` holds (evaluated only then).
#[inline]
pub fn distributed(kind: &[Kind], i: usize, low_xi: impl FnOnce() -> bool) -> bool {
    i >= 1
        && i + 1 < kind.len()
        && kind[i - 1] == Kind::Active
        && kind[i] == Kind::Active
        && kind[i + 1] == Kind::Active
        && low_xi()
}

/// The row of a cavitated or frozen node (`a_row` the 2 bw + 1 band entries of its row, all
/// written): dP = -P resp. dP = 0.
#[inline]
pub fn pinned_row(a_row: &mut [f64], rhs: &mut f64, bw: usize, kind: Kind, p: f64) {
    a_row.fill(0.0);
    a_row[bw] = 1.0;
    *rhs = if kind == Kind::Cavitated { -p } else { 0.0 };
}

/// The band of the row of active node i of a line whose last unknown is `last` (= n - 2), in the
/// distributed variables: column j gets J(i, j) - (J(i, j-1) + J(i, j+1))/2 where `jset[j]`, else
/// J(i, j), for |j - i| <= bw; `ent(j)` = J(i, j), 0 outside the unknowns. All 2 bw + 1 entries
/// of `a_row` are written (0 for the columns outside the unknowns), so the band need not be
/// cleared between solves.
#[inline]
pub fn distributed_row(
    a_row: &mut [f64],
    i: usize,
    bw: usize,
    last: usize,
    jset: &[bool],
    ent: impl Fn(usize) -> f64,
) {
    let (first, end) = (i.saturating_sub(bw).max(1), (i + bw).min(last));
    a_row[..first + bw - i].fill(0.0);
    a_row[end + bw - i + 1..].fill(0.0);
    for j in first..=end {
        let mut v = ent(j);
        if jset[j] {
            v -= 0.5 * (ent(j - 1) + ent(j + 1));
        }
        a_row[j + bw - i] = v;
    }
}

/// The change of P at node i from the solution dQ (`dq[i - 1]`) in the distributed variables:
/// dQ_i - (dQ_{i-1} [if jset[i-1]] + dQ_{i+1} [if jset[i+1]])/2.
#[inline]
pub fn undistributed(dq: &[f64], jset: &[bool], i: usize) -> f64 {
    let mut dp = dq[i - 1];
    if jset[i - 1] {
        dp -= 0.5 * dq[i - 2];
    }
    if jset[i + 1] {
        dp -= 0.5 * dq[i];
    }
    dp
}

/// The new P of a node: 0 when cavitated, `old` when frozen, else old + omega dp with the change
/// clamped to +-max(max_dp, relative old) ([`RelaxParams::relative_step`]), projected on P >= 0.
#[inline]
pub fn relaxed(kind: Kind, old: f64, omega: f64, dp: f64, max_dp: f64, relative: f64) -> f64 {
    match kind {
        Kind::Cavitated => 0.0,
        Kind::Frozen => old,
        Kind::Active => {
            let lim = max_dp.max(relative * old);
            (old + (omega * dp).clamp(-lim, lim)).max(0.0)
        }
    }
}

/// The largest change of P per sweep that changes a Barus viscosity by at most e^2: 2/alpha_bar
/// (infinite when alpha_bar = 0). Far from the solution a full Newton change is not to be trusted.
#[inline]
pub fn viscosity_step_limit(alpha_bar: f64) -> f64 {
    if alpha_bar > 0.0 {
        2.0 / alpha_bar
    } else {
        f64::INFINITY
    }
}

/// The kernel row `row` (values at offsets |d| = 0, 1, ...) mirrored into `out` for offsets
/// d = -reach..=reach, at index reach + d (0 beyond the row), so that a Jacobian row's window
/// reads it in order.
pub fn mirror_kernel(row: &[f64], reach: usize, out: &mut Vec<f64>) {
    out.clear();
    out.extend((0..=2 * reach).map(|q| row.get(q.abs_diff(reach)).copied().unwrap_or(0.0)));
}
