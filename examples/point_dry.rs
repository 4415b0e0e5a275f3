use ehlmap::params::PointCase;
use ehlmap::problem::point::PointPhysics;
use ehlmap::solver::fmg::fmg_solve;
use ehlmap::solver::point::PointMgParams;
use ehlmap::solver::point_mg::PointMultigrid;
fn main() {
    let a: Vec<f64> = std::env::args()
        .skip(1)
        .map(|s| s.parse().unwrap())
        .collect();
    let case = PointCase::new(100.0, 0.0, a[0]).unwrap();
    let phys = PointPhysics {
        dry: true,
        ..PointPhysics::from_case(&case)
    };
    let params = PointMgParams {
        grid: a[1] as usize,
        ..Default::default()
    };
    let mut mg = PointMultigrid::with_physics(&case, phys, &params);
    let info = fmg_solve(&mut mg);
    println!("{} {} h0 {}", info.status, info.reason, mg.h0);
}
