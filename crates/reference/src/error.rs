//! Typed errors of the reference solvers: every bad input is reported, never a panic or a NaN.

use thiserror::Error;

/// Errors returned by the closed forms, FASTSIM and the boundary-element solver.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum RefError {
    /// A physical parameter is outside its valid range (or not finite).
    #[error("invalid parameter `{name}` = {value}: {expected}")]
    InvalidParameter {
        /// Name of the parameter, as documented on the function or struct.
        name: &'static str,
        /// The value that was given.
        value: f64,
        /// The valid range, in words.
        expected: &'static str,
    },
    /// A discretisation parameter (grid size, number of steps, ...) is out of range.
    #[error("invalid discretisation `{name}` = {value}: {expected}")]
    InvalidGrid {
        /// Name of the parameter.
        name: &'static str,
        /// The value that was given.
        value: usize,
        /// The valid range, in words.
        expected: &'static str,
    },
    /// An iterative solver did not reach its tolerance within its iteration budget.
    #[error("{solver} did not converge in {iterations} iterations (residual {residual:e})")]
    NoConvergence {
        /// Which solver (e.g. "steady Gauss-Seidel").
        solver: &'static str,
        /// Iterations spent.
        iterations: usize,
        /// Last residual (solver specific, documented there).
        residual: f64,
    },
}

/// Checks that `value` is finite and within `[lo, hi]`; otherwise an [`RefError::InvalidParameter`].
pub(crate) fn check_range(
    name: &'static str,
    value: f64,
    lo: f64,
    hi: f64,
    expected: &'static str,
) -> Result<f64, RefError> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(RefError::InvalidParameter {
            name,
            value,
            expected,
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub(crate) fn check_positive(name: &'static str, value: f64) -> Result<f64, RefError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(RefError::InvalidParameter {
            name,
            value,
            expected: "finite and > 0",
        })
    }
}

/// Checks that `value` is finite (any sign).
pub(crate) fn check_finite(name: &'static str, value: f64) -> Result<f64, RefError> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(RefError::InvalidParameter {
            name,
            value,
            expected: "finite",
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn checks_reject_nan_inf_and_out_of_range() {
        assert!(check_positive("g", 0.0).is_err());
        assert!(check_positive("g", f64::NAN).is_err());
        assert!(check_positive("g", f64::INFINITY).is_err());
        assert_eq!(check_positive("g", 2.0), Ok(2.0));
        assert!(check_range("nu", 0.6, 0.0, 0.5, "[0, 0.5]").is_err());
        assert!(check_range("nu", -0.1, 0.0, 0.5, "[0, 0.5]").is_err());
        assert_eq!(check_range("nu", 0.5, 0.0, 0.5, "[0, 0.5]"), Ok(0.5));
        assert!(check_finite("xi", f64::NEG_INFINITY).is_err());
        let msg = check_positive("a", -1.0).unwrap_err().to_string();
        assert!(msg.contains("`a`"), "{msg}");
    }
}
