//! Small statistics shared by the scenes' timings and the CLI's benchmarks and reports (one
//! copy for the workspace).

/// The median of `values` (sorted in place by `f64::total_cmp`); for an even count the upper of
/// the two middle values, so the median is always a measured value. `None` when empty.
pub fn median(values: &mut [f64]) -> Option<f64> {
    values.sort_by(f64::total_cmp);
    values.get(values.len() / 2).copied()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn median_of_odd_even_and_empty() {
        assert_eq!(median(&mut [3.0, 1.0, 2.0]), Some(2.0));
        assert_eq!(median(&mut [4.0, 1.0, 3.0, 2.0]), Some(3.0));
        assert_eq!(median(&mut []), None);
    }
}
