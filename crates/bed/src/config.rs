//! The coupling's settings.

/// Settings of the coupling.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BedConfig {
    /// Skin of the boundary candidate lists \[m\], finite and > 0 (a tenth of a grain diameter
    /// is a good start).
    pub skin: f64,
}
