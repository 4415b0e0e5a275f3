//! Tests of the point Jacobian rows (`super`): against finite differences of the residual, the
//! diagonal against the dense Jacobian's, and rows assembled on two threads against one.

use super::*;

#[test]
fn jacobian_matches_finite_differences() {
    let phys = PointPhysics::piezoviscous_compressible();
    let mk = || PointLevel::new(&phys, -3.0, 1.5, 2.5, 16, 12);
    let mut lv = mk();
    let fill = |lv: &mut PointLevel| {
        for j in 1..lv.ny - 1 {
            for i in 1..lv.nx - 1 {
                let c = lv.at(i, j);
                let (x, y) = (lv.x[i], lv.y[j] / phys.k);
                lv.p[c] = (1.0 - x * x - y * y).max(0.0).sqrt() + 0.05 + 0.01 * i as f64;
            }
        }
    };
    fill(&mut lv);
    let h0 = 0.3;
    lv.update_film(&phys, h0);
    let unknowns = lv.unknowns();
    let jac = lv.dense_jacobian(&phys, &unknowns);
    let e = 1e-7;
    let m = unknowns.len();
    for q in [20usize, 61, 62, 75, 100] {
        let mut plus = mk();
        fill(&mut plus);
        plus.p[unknowns[q]] += e;
        plus.update_film(&phys, h0);
        for r in [5usize, 47, 61, 62, 63, 76, 47 + 15, 120] {
            let c = unknowns[r];
            let fd = (plus.reynolds(&phys, c % lv.nx, c / lv.nx)
                - lv.reynolds(&phys, c % lv.nx, c / lv.nx))
                / e;
            let an = jac[(r, q)];
            assert!(
                (fd - an).abs() <= 1e-4 * (1.0 + an.abs()),
                "row {r} col {q}: fd {fd} an {an}"
            );
        }
    }
    // The row's entries computed together are entry() to the bit.
    let mut out = vec![f64::NAN; lv.nx];
    let mut win = KernelWindow::default();
    win.fill(&lv.kernel, lv.nx, 7);
    for (i, j) in [(1usize, 1usize), (2, 5), (7, 6), (14, 10)] {
        let row = PointJacRow::new(&lv.rows(), &phys, i, j);
        let (lo, hi) = (i.saturating_sub(5).max(1), (i + 5).min(lv.nx - 2));
        row.row_entries(&win, lo, hi, &mut out);
        for (k, &o) in out.iter().enumerate().take(hi + 1).skip(lo) {
            assert_eq!(o.to_bits(), row.entry(&lv.kernel, lv.nx, k, j).to_bits());
        }
        let d = row.entry(&lv.kernel, lv.nx, i, j);
        assert_eq!(row.diagonal(&win).to_bits(), d.to_bits());
        // A row built from the row's nodal derivatives gives the same row entries.
        let mut derivs = RowDerivatives::default();
        derivs.fill(&lv.rows(), &phys, j, i.saturating_sub(2)..=i + 1);
        let in_row = PointJacRow::in_row(&lv.rows(), &phys, i, j, &derivs);
        assert_eq!(in_row.diagonal(&win).to_bits(), d.to_bits());
        let mut out2 = vec![f64::NAN; lv.nx];
        in_row.row_entries(&win, lo, hi, &mut out2);
        for k in lo..=hi {
            assert_eq!(out2[k].to_bits(), out[k].to_bits());
        }
    }
    // So are the whole dense rows of the Jacobian.
    for (r, &c) in unknowns.iter().enumerate() {
        let row = PointJacRow::new(&lv.rows(), &phys, c % lv.nx, c / lv.nx);
        for (q, &cc) in unknowns.iter().enumerate() {
            let e = row.entry(&lv.kernel, lv.nx, cc % lv.nx, cc / lv.nx);
            assert_eq!(jac[(r, q)].to_bits(), e.to_bits(), "row {r} col {q}");
        }
    }
    let mut plus = mk();
    fill(&mut plus);
    plus.update_film(&phys, h0 + e);
    for r in [5usize, 61, 120] {
        let c = unknowns[r];
        let fd = (plus.reynolds(&phys, c % lv.nx, c / lv.nx)
            - lv.reynolds(&phys, c % lv.nx, c / lv.nx))
            / e;
        assert!(
            (fd - jac[(r, m)]).abs() <= 1e-4 * (1.0 + fd.abs()),
            "H0 row {r}"
        );
    }
}

/// A 16 x 12-cell level with pressures (zero in the outlet), its film at H0 = 0.3, with
/// the far field or without.
fn loaded_level(phys: &PointPhysics, far: bool) -> PointLevel {
    let mut lv = PointLevel::new(phys, -3.0, 1.5, 2.5, 16, 12);
    if far {
        lv = lv.with_far_field(phys.d, (4.5 / 16.0, 5.0 / 12.0), phys.coef * phys.load);
    }
    for j in 1..lv.ny - 1 {
        for i in 1..lv.nx - 1 {
            let c = lv.at(i, j);
            let (x, y) = (lv.x[i], lv.y[j] / phys.k);
            lv.p[c] = (1.0 - x * x - y * y).max(0.0).sqrt();
        }
    }
    lv.update_film(phys, 0.3);
    lv
}

#[test]
fn the_diagonal_alone_is_the_dense_jacobians_to_the_bit() {
    let phys = PointPhysics::piezoviscous_compressible();
    let mut far_terms = 0;
    for far in [false, true] {
        let lv = loaded_level(&phys, far);
        let u = lv.unknowns();
        let jac = lv.dense_jacobian(&phys, &u);
        let diag = lv.jacobian_diagonal(&phys, &u);
        assert_eq!(diag.len(), u.len());
        let rows = lv.rows();
        for (r, (d, &c)) in diag.iter().zip(&u).enumerate() {
            assert_eq!(d.to_bits(), jac[(r, r)].to_bits(), "far {far}, row {r}");
            let own = PointJacRow::new(&rows, &phys, c % lv.nx, c / lv.nx).entry(
                &lv.kernel,
                lv.nx,
                c % lv.nx,
                c / lv.nx,
            );
            far_terms += usize::from(*d != own);
        }
        if !far {
            assert_eq!(far_terms, 0);
        }
    }
    // The far field adds to the diagonal of the rows next to the boundary.
    assert!(far_terms > 0);
}

#[test]
fn rows_assembled_on_two_threads_are_those_of_one() {
    let phys = PointPhysics::piezoviscous_compressible();
    let mut lv = loaded_level(&phys, true);
    lv.parallel_jacobian = true;
    let u = lv.unknowns();
    // Above the parallel threshold, so that two threads do share the rows.
    assert!(u.len() >= crate::solve::newton::PARALLEL_JACOBIAN_ROWS);
    let on = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .expect("a pool")
            .install(|| {
                (
                    lv.dense_jacobian(&phys, &u),
                    lv.jacobian_diagonal(&phys, &u),
                )
            })
    };
    let (one, two) = (on(1), on(2));
    assert_eq!(one.0, two.0);
    assert!(one
        .1
        .iter()
        .zip(&two.1)
        .all(|(a, b)| a.to_bits() == b.to_bits()));
}
