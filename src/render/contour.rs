//! Iso-lines of a field on a rectangular grid by marching squares.
//!
//! Contract: `f` is row-major with x fastest (node (i, j) at `j * x.len() + i`). For each cell the
//! level crosses an edge where the corner values straddle it (`(f0 - c)(f1 - c) < 0`, or one of
//! them equals `c` and the other is above); the crossing is placed by linear interpolation along
//! the edge. Two crossings give one segment; four (a saddle) are paired by the sign of the cell
//! mean, the usual disambiguation. Segments are returned unordered.

/// One straight piece of an iso-line: two points (x, y).
pub type Segment = [(f64, f64); 2];

/// All segments of the iso-line `f = c`.
pub fn contour_segments(x: &[f64], y: &[f64], f: &[f64], c: f64) -> Vec<Segment> {
    let nx = x.len();
    let mut out = Vec::new();
    if nx < 2 || y.len() < 2 || f.len() != nx * y.len() {
        return out;
    }
    let at = |i: usize, j: usize| f[j * nx + i] - c;
    // a value exactly on the level counts as above it, so a crossing is never found twice
    let above = |v: f64| v >= 0.0;
    for j in 0..y.len() - 1 {
        for i in 0..nx - 1 {
            // corners counter-clockwise: (i,j), (i+1,j), (i+1,j+1), (i,j+1)
            let p = [
                (x[i], y[j]),
                (x[i + 1], y[j]),
                (x[i + 1], y[j + 1]),
                (x[i], y[j + 1]),
            ];
            let v = [at(i, j), at(i + 1, j), at(i + 1, j + 1), at(i, j + 1)];
            let mut cross = Vec::with_capacity(4);
            for e in 0..4 {
                let (a, b) = (e, (e + 1) % 4);
                if above(v[a]) != above(v[b]) {
                    let t = v[a] / (v[a] - v[b]);
                    cross.push((
                        p[a].0 + t * (p[b].0 - p[a].0),
                        p[a].1 + t * (p[b].1 - p[a].1),
                    ));
                }
            }
            match cross.len() {
                2 => out.push([cross[0], cross[1]]),
                4 => {
                    // Crossings lie on edges 0..3 in order. If the centre is on the side of
                    // corner 0, corner 0's region is cut off by edges 3 and 0 ... pair accordingly.
                    let centre = 0.25 * (v[0] + v[1] + v[2] + v[3]);
                    if above(centre) == above(v[0]) {
                        out.push([cross[0], cross[1]]);
                        out.push([cross[2], cross[3]]);
                    } else {
                        out.push([cross[3], cross[0]]);
                        out.push([cross[1], cross[2]]);
                    }
                }
                _ => {}
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn grid(n: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect()
    }

    #[test]
    fn paraboloid_contours_are_circles() {
        // f = x^2 + y^2 on [-2, 2]^2, h = 0.05: the level r^2 is the circle of radius r.
        let (n, h) = (81, 0.05);
        let x = grid(n, -2.0, 2.0);
        let mut f = vec![0.0; n * n];
        for j in 0..n {
            for i in 0..n {
                f[j * n + i] = x[i] * x[i] + x[j] * x[j];
            }
        }
        for r in [0.5f64, 1.0, 1.7] {
            let segs = contour_segments(&x, &x, &f, r * r);
            assert!(!segs.is_empty());
            let mut len = 0.0;
            for s in &segs {
                for (px, py) in s {
                    // linear interpolation of a quadratic along an edge: error <= h^2/(8 r) in r
                    let err = ((px * px + py * py).sqrt() - r).abs();
                    assert!(err <= h * h / (8.0 * r) + 1e-12, "r {r}: {err}");
                }
                len += ((s[1].0 - s[0].0).powi(2) + (s[1].1 - s[0].1).powi(2)).sqrt();
            }
            // the polygon is inscribed: its length is within 0.5 % below 2 pi r
            let rel = len / (2.0 * std::f64::consts::PI * r) - 1.0;
            assert!(rel < 1e-9 && rel > -5e-3, "r {r}: length off by {rel}");
        }
        // a level outside the range gives nothing
        assert!(contour_segments(&x, &x, &f, 9.0).is_empty());
    }

    #[test]
    fn saddle_cell_is_split_into_two_segments() {
        // f = x y on one cell [-1, 1]^2 at level 0.5: corners 1, -1, 1, -1 -> two segments
        // cutting off the corners (1, 1) and (-1, -1) (centre value 0 < 0.5).
        let x = [-1.0, 1.0];
        let f = [1.0, -1.0, -1.0, 1.0];
        let s = contour_segments(&x, &x, &f, 0.5);
        assert_eq!(s.len(), 2);
        for seg in &s {
            // both ends of each segment are near the same corner (x y > 0 quadrant)
            assert!(
                seg[0].0 * seg[1].0 > 0.0 && seg[0].1 * seg[1].1 > 0.0,
                "{seg:?}"
            );
        }
    }
}
