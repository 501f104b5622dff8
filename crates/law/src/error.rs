//! Typed errors for invalid inputs. Every constructor that takes user data validates it and
//! returns one of these instead of panicking or producing NaN at step time.

/// An invalid parameter given to a creep-law constructor.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum LawError {
    /// A value that must be finite and strictly positive was not.
    #[error("{name} must be finite and > 0 (got {value}) [{unit}]")]
    NotPositive {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// SI unit of the parameter.
        unit: &'static str,
    },
    /// A value that must be >= 0 (infinity allowed where documented) was negative or NaN.
    #[error("{name} must be >= 0 and not NaN (got {value}) [{unit}]")]
    Negative {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// SI unit of the parameter.
        unit: &'static str,
    },
    /// Poisson's ratio outside the range this crate supports.
    #[error("Poisson ratio nu must be in (-1, 0.5] (got {0})")]
    PoissonRatio(f64),
    /// A radius that is neither positive and finite nor a plane.
    #[error("radius must be finite and > 0, or a plane (got {0}) [m]")]
    Radius(f64),
    /// Two planes cannot be in Hertz contact.
    #[error("a contact needs at least one curved surface: both surfaces are planes")]
    TwoPlanes,
    /// A value outside its documented range.
    #[error("{name} = {value} is outside its valid range {range}")]
    OutOfRange {
        /// Parameter name.
        name: &'static str,
        /// Value given.
        value: f64,
        /// The valid range, in words.
        range: &'static str,
    },
}

/// Checks `value` is finite and strictly positive.
pub(crate) fn positive(
    name: &'static str,
    value: f64,
    unit: &'static str,
) -> Result<f64, LawError> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(LawError::NotPositive { name, value, unit })
    }
}

/// Checks `value >= 0` and not NaN (`+inf` passes).
pub(crate) fn non_negative(
    name: &'static str,
    value: f64,
    unit: &'static str,
) -> Result<f64, LawError> {
    if value >= 0.0 {
        Ok(value)
    } else {
        Err(LawError::Negative { name, value, unit })
    }
}

/// Checks `value` is finite and `>= 0`.
pub(crate) fn finite_non_negative(
    name: &'static str,
    value: f64,
    unit: &'static str,
) -> Result<f64, LawError> {
    if value.is_finite() && value >= 0.0 {
        Ok(value)
    } else {
        Err(LawError::Negative { name, value, unit })
    }
}
