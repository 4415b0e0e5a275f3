use ehlmap::params::PointCase;
use ehlmap::solver::point::{solve_point, PointSolveParams};
fn main() {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let case = PointCase::new(a[0], a[1], a[2]).unwrap();
    let mut p = PointSolveParams::default();
    p.mg.grid = a[3] as usize;
    if let Ok(v) = std::env::var("N0") {
        p.mg.domain.n0 = v.parse().unwrap();
    }
    if let Ok(v) = std::env::var("DOM") {
        let f: Vec<f64> = v.split(',').map(|x| x.parse().unwrap()).collect();
        p.mg.domain.inlet_lh = f[0];
        p.mg.domain.outlet_lh = f[1];
        p.mg.domain.side_lh = f[2];
    }
    p.fallback = a.get(4).map_or(true, |v| *v > 0.0);
    let s = solve_point(&case, &p);
    let o = &s.outputs;
    println!("M {} L {} D {} grid {} H_c {:.5} H_min {:.5} Pmax {:.4} load_err {:.2e} {} [{}] wu {:.1} {:.2}s",
        a[0], a[1], a[2], o.grid, o.h_c, o.h_min, o.p_max, o.load_error, o.status, o.reason, o.work_units, o.wall_s);
}
