//! Restitution-based normal damping of the Hertz contact: the pure functions live in creep-law
//! ([`creep_law::pair::damping`], Tsuji, Tanaka & Ishida 1992 with the damping coefficient solved
//! for the restitution with the no-tension cut-off); this module re-exports them and maps the
//! error of [`damping_coefficient`] to the plugin's [`PluginError::Restitution`].

use crate::error::PluginError;

pub use creep_law::pair::damping::{
    MIN_RESTITUTION, alpha_without_cutoff, restitution_for_damping,
};

/// The damping coefficient `alpha` [-] whose impact, with the no-tension cut-off, rebounds with
/// restitution `e` [-] (`MIN_RESTITUTION <= e <= 1`; `e = 1` gives 0): creep-law's
/// [`creep_law::pair::damping::damping_coefficient`].
pub fn damping_coefficient(e: f64) -> Result<f64, PluginError> {
    creep_law::pair::damping::damping_coefficient(e).map_err(|_| PluginError::Restitution(e))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_with_cutoff_and_errors() {
        for e in [0.1, 0.5, 0.9] {
            let a = damping_coefficient(e).unwrap();
            assert!((restitution_for_damping(a, true) / e - 1.0).abs() < 1e-6);
            assert!(a > alpha_without_cutoff(e));
        }
        assert_eq!(damping_coefficient(0.0), Err(PluginError::Restitution(0.0)));
        assert!(damping_coefficient(1.1).is_err());
        assert!(damping_coefficient(f64::NAN).is_err());
        assert_eq!(damping_coefficient(1.0), Ok(0.0));
    }
}
