//! Scratch: formula bound vs truth at midpoints. args: fit.json [line|point-data DIR]
use ehlmap::model::case::{Case, LineCase, PointCase};
use ehlmap::report::surrogate::FittedFormula;
use ehlmap::report::FitReport;
use ehlmap::strategy::formula::FilmFormula;
use ehlmap::strategy::solve_case::{solve, SolveParams};

fn main() {
    let a: Vec<String> = std::env::args().collect();
    let r: FitReport = serde_json::from_str(&std::fs::read_to_string(&a[1]).unwrap()).unwrap();
    let f = FittedFormula::from_report(&r, &a[1]).unwrap();
    let mut stats = vec![];
    if a[2] == "line" {
        let ms: Vec<f64> = (0..16)
            .map(|k| 1.0f64 * 3000f64.powf(k as f64 / 15.0))
            .collect();
        let ls = [0.0, 0.5, 1.0, 2.0, 4.0, 8.0, 12.0, 16.0, 20.0];
        for w in ms.windows(2) {
            for lw in ls.windows(2) {
                for (fm, fl) in [(0.25, 0.75), (0.75, 0.25)] {
                    let (m, l) = (w[0] * (w[1] / w[0]).powf(fm), lw[0] + fl * (lw[1] - lw[0]));
                    let case = Case::Line(LineCase::new(m, l).unwrap());
                    let Ok(ff) = f.films(&case) else { continue };
                    let p = SolveParams {
                        accuracy: Some(0.002),
                        full_model: true,
                        ..Default::default()
                    };
                    let s = solve(&case, &p).outputs;
                    let ec = (ff.h_c / s.h_c - 1.0).abs();
                    let em = (ff.h_min / s.h_min - 1.0).abs();
                    let re = s
                        .h_c_err
                        .unwrap_or(f64::NAN)
                        .max(s.h_min_err.unwrap_or(f64::NAN));
                    stats.push((m, l, 1.0, ec, em, ff.h_c_err, ff.h_min_err, re, ff.heldout));
                }
            }
        }
    } else {
        let rows = ehlmap::store::results::read_dataset(std::path::Path::new(&a[2])).unwrap();
        for row in rows {
            if row.status != ehlmap::store::results::RowStatus::Converged {
                continue;
            }
            let case = Case::Point(PointCase::new(row.m, row.l, row.d.unwrap()).unwrap());
            let Ok(ff) = f.films(&case) else { continue };
            let ec = (ff.h_c / row.h_c.unwrap() - 1.0).abs();
            let em = (ff.h_min / row.h_min.unwrap() - 1.0).abs();
            let re = row
                .h_c_err
                .unwrap_or(f64::NAN)
                .max(row.h_min_err.unwrap_or(f64::NAN));
            stats.push((
                row.m,
                row.l,
                row.d.unwrap(),
                ec,
                em,
                ff.h_c_err,
                ff.h_min_err,
                re,
                ff.heldout,
            ));
        }
    }
    let n = stats.len();
    let mut viol = 0;
    let mut viol_sure = 0;
    let mut ans = [0usize; 4];
    for s in &stats {
        let v = s.3 > s.5 || s.4 > s.6;
        let vs = s.3 - s.7 > s.5 || s.4 - s.7 > s.6;
        if v {
            viol += 1;
        }
        println!(
            "ROW {} {} {} {} {} {} {} {} {}",
            s.0, s.1, s.2, s.3, s.4, s.5, s.6, s.7, s.8
        );
        if vs {
            viol_sure += 1;
        }
        for (k, t) in [0.01, 0.02, 0.05, 0.1].iter().enumerate() {
            if s.8 < 0.5 * t && s.5.max(s.6) <= *t {
                ans[k] += 1;
            }
        }
    }
    let maxratio = stats
        .iter()
        .map(|s| (s.3 / s.5).max(s.4 / s.6))
        .fold(0.0, f64::max);
    println!("known {n}, bound violated {viol} (beyond the reference's own estimate {viol_sure}); worst true/bound {maxratio:.2}; answerable at 1/2/5/10 %: {ans:?}");
}
