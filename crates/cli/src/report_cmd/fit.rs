//! Power-law fits for the report: the observed order of a time-step convergence study and the
//! growth exponent of a cost, both the slope of a least-squares line through `(ln x, ln y)`.

/// A fitted power law `y = c x^k`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PowerFit {
    /// The exponent `k` (the slope in log-log) [-].
    pub exponent: f64,
    /// The prefactor `c` (units of y over units of x^k).
    pub prefactor: f64,
    /// Coefficient of determination of the line in log-log, in [0, 1] (1 for exact data) [-].
    pub r2: f64,
    /// Number of points the fit used.
    pub points: usize,
}

/// Least squares of `ln y = ln c + k ln x` over the points with `x > 0` and `y > 0` finite
/// (others are skipped; pass `|error|` for errors of either sign). `None` with fewer than two
/// usable points or a single distinct x: never a NaN.
pub fn power_fit(points: &[(f64, f64)]) -> Option<PowerFit> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    let n = logs.len();
    if n < 2 {
        return None;
    }
    let nf = n as f64;
    let (mx, my) = logs
        .iter()
        .fold((0.0, 0.0), |(a, b), (x, y)| (a + x / nf, b + y / nf));
    let sxx: f64 = logs.iter().map(|(x, _)| (x - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|(x, y)| (x - mx) * (y - my)).sum();
    let syy: f64 = logs.iter().map(|(_, y)| (y - my).powi(2)).sum();
    if sxx <= 1e-300 || sxx.is_nan() {
        return None;
    }
    let k = sxy / sxx;
    let r2 = if syy > 0.0 {
        (sxy * sxy / (sxx * syy)).clamp(0.0, 1.0)
    } else {
        1.0
    };
    let fit = PowerFit {
        exponent: k,
        prefactor: (my - k * mx).exp(),
        r2,
        points: n,
    };
    (fit.exponent.is_finite() && fit.prefactor.is_finite()).then_some(fit)
}

/// The local orders between consecutive points, `ln(y1/y0) / ln(x1/x0)` (`None` where a point
/// is unusable, as in [`power_fit`]).
pub fn local_orders(points: &[(f64, f64)]) -> Vec<Option<f64>> {
    points
        .windows(2)
        .map(|w| power_fit(w).map(|f| f.exponent))
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn exact_power_laws_are_recovered() {
        for (c, k) in [(3.0, 2.0), (0.5, -1.5), (1e-4, 1.0), (2.0, 0.0)] {
            let pts: Vec<(f64, f64)> = [1.0 / 30.0, 1.0 / 60.0, 1.0 / 120.0, 1.0 / 960.0]
                .iter()
                .map(|&x| (x, c * f64::powf(x, k)))
                .collect();
            let f = power_fit(&pts).unwrap();
            assert!((f.exponent - k).abs() < 1e-12, "{f:?}");
            assert!((f.prefactor / c - 1.0).abs() < 1e-10, "{f:?}");
            assert!((f.r2 - 1.0).abs() < 1e-12 && f.points == 4);
            for o in local_orders(&pts) {
                assert!((o.unwrap() - k).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn scattered_data_has_r2_below_one() {
        let pts = [(1.0, 1.0), (2.0, 5.0), (4.0, 9.0), (8.0, 70.0)];
        let f = power_fit(&pts).unwrap();
        assert!(f.exponent > 1.0 && f.exponent < 3.0 && f.r2 < 1.0 && f.r2 > 0.5);
    }

    #[test]
    fn bad_points_are_skipped_and_too_few_give_none() {
        let f = power_fit(&[
            (1.0, 2.0),
            (0.0, 1.0),
            (2.0, f64::NAN),
            (4.0, 8.0),
            (8.0, -1.0),
        ])
        .unwrap();
        assert!((f.exponent - 1.0).abs() < 1e-12 && f.points == 2);
        assert!(power_fit(&[(1.0, 1.0)]).is_none());
        assert!(power_fit(&[(1.0, 1.0), (1.0, 2.0)]).is_none());
        assert!(power_fit(&[]).is_none());
        assert_eq!(
            local_orders(&[(1.0, 1.0), (2.0, 0.0), (4.0, 4.0)]),
            [None, None]
        );
    }
}
