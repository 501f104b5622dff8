//! The test's parameters, their ranges and the TOML file they are read from and written back
//! to (`crates/cli/assets/triaxial.toml`; a run's `params.toml`).

use creep_law::Material;
use serde::{Deserialize, Serialize};

use crate::SceneError;

/// Parameters of the triaxial test (SI units).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TriaxialParams {
    /// Spheres per lattice side (`n^3` spheres), in `[2, 40]`.
    pub n_per_side: usize,
    /// Mean radius \[m\], > 0.
    pub radius: f64,
    /// Half-width of the uniform radius distribution relative to the mean, in `[0, 0.5]`.
    pub radius_spread: f64,
    /// Ball (and wall) material: shear modulus, Poisson's ratio, density.
    pub material: Material,
    /// Ball-ball friction coefficient of the shear, in `[0, 10]`.
    pub mu: f64,
    /// Restitution coefficient of every contact (sets the normal damping), in `[0.05, 1]`.
    pub restitution: f64,
    /// Confining pressure `p0` \[Pa\], > 0.
    pub confining_pressure: f64,
    /// Inertial number of the shear (sets the axial strain rate), in `(0, 0.1]`.
    pub inertial_number: f64,
    /// Final axial strain [-], in `(0, 0.5]`.
    pub axial_strain: f64,
    /// Time step of the generation and the compaction as a fraction of the smallest ball's
    /// Rayleigh time, in `(0, 0.3]` (the packing depends on it: docs/results/triaxial-timestep).
    pub rayleigh_fraction: f64,
    /// Time step of the shears as a fraction of the smallest ball's Rayleigh time, in
    /// `(0, 0.3]`. Default 0.3: from the packing compacted at 0.2 the shears at 0.3 reproduce
    /// those at 0.2 within 0.07 deg and 0.25 % (peak and dilatancy angles, wall and contact
    /// stresses at the peak) in 0.7 of the CPU time (docs/results/triaxial-timestep); a stated
    /// speed-accuracy choice.
    pub shear_rayleigh_fraction: f64,
    /// Seed of the packing's generator ([`super::GENERATOR`]), in `[0, 2^63 - 1]` (TOML's
    /// integers are signed 64-bit).
    pub seed: u64,
    /// Rows recorded per 1 % of axial strain (>= 1).
    pub rows_per_percent: usize,
}

impl Default for TriaxialParams {
    /// The default test: 4,096 softened-glass spheres of mean radius 1 mm (radii +-20 %),
    /// G = 29 MPa, nu = 0.2, rho = 2,500 kg/m^3, mu = 0.5, e = 0.5, p0 = 100 kPa, I = 8e-4,
    /// 20 % axial strain, dt = 0.2 T_R in the generation and the compaction, 0.3 T_R in the
    /// shears (the repository's `crates/cli/assets/triaxial.toml`).
    fn default() -> Self {
        Self {
            n_per_side: 16,
            radius: 1e-3,
            radius_spread: 0.2,
            material: Material::new(29e6, 0.2, 0.5, 2500.0).expect("valid constants"),
            mu: 0.5,
            restitution: 0.5,
            confining_pressure: 100e3,
            inertial_number: 8e-4,
            axial_strain: 0.2,
            rayleigh_fraction: 0.2,
            shear_rayleigh_fraction: 0.3,
            seed: 2011,
            rows_per_percent: 4,
        }
    }
}

impl TriaxialParams {
    /// The `--quick` size for smoke tests: 7^3 = 343 spheres, the shear to 10 % at I = 5e-3
    /// (outside the quasi-static range: a smoke test, not a result).
    pub fn quick() -> Self {
        Self {
            n_per_side: 7,
            inertial_number: 5e-3,
            axial_strain: 0.1,
            rows_per_percent: 2,
            ..Self::default()
        }
    }

    /// Checks every parameter's range.
    pub fn validate(&self) -> Result<(), SceneError> {
        let check = |name: &str, v: f64, lo: f64, hi: f64, open_lo: bool| {
            let ok = v.is_finite() && v <= hi && if open_lo { v > lo } else { v >= lo };
            if ok {
                Ok(())
            } else {
                let bracket = if open_lo { "(" } else { "[" };
                Err(SceneError::Parameter(format!(
                    "triaxial: {name} = {v} must be in {bracket}{lo}, {hi}]"
                )))
            }
        };
        check("n_per_side", self.n_per_side as f64, 2.0, 40.0, false)?;
        check("radius [m]", self.radius, 0.0, 10.0, true)?;
        check("radius_spread", self.radius_spread, 0.0, 0.5, false)?;
        check("mu", self.mu, 0.0, 10.0, false)?;
        check("restitution", self.restitution, 0.05, 1.0, false)?;
        check(
            "confining_pressure [Pa]",
            self.confining_pressure,
            0.0,
            1e9,
            true,
        )?;
        check("inertial_number", self.inertial_number, 0.0, 0.1, true)?;
        check("axial_strain", self.axial_strain, 0.0, 0.5, true)?;
        check("rayleigh_fraction", self.rayleigh_fraction, 0.0, 0.3, true)?;
        check(
            "shear_rayleigh_fraction",
            self.shear_rayleigh_fraction,
            0.0,
            0.3,
            true,
        )?;
        check(
            "rows_per_percent",
            self.rows_per_percent as f64,
            1.0,
            1e3,
            false,
        )?;
        if i64::try_from(self.seed).is_err() {
            return Err(SceneError::Parameter(format!(
                "triaxial: seed = {} must be in [0, 2^63 - 1]",
                self.seed
            )));
        }
        Ok(())
    }

    /// Mean diameter \[m\].
    pub fn mean_diameter(&self) -> f64 {
        2.0 * self.radius
    }

    /// Axial strain rate of the shear [1/s]: `I / (d sqrt(rho / p0))`.
    pub fn strain_rate(&self) -> f64 {
        self.inertial_number
            / (self.mean_diameter() * (self.material.density() / self.confining_pressure).sqrt())
    }

    /// Time step of the generation and the compaction \[s\]: `rayleigh_fraction` of the
    /// smallest ball's Rayleigh time.
    pub fn time_step(&self) -> f64 {
        let r_min = self.radius * (1.0 - self.radius_spread);
        self.rayleigh_fraction * creep_law::hertz::rayleigh_time_step(&self.material, r_min)
    }

    /// Time step of the shears \[s\]: `shear_rayleigh_fraction` of the smallest ball's
    /// Rayleigh time.
    pub fn shear_time_step(&self) -> f64 {
        let r_min = self.radius * (1.0 - self.radius_spread);
        self.shear_rayleigh_fraction * creep_law::hertz::rayleigh_time_step(&self.material, r_min)
    }

    /// The time over which the shear's servo removes its share of a wall's stress error \[s\]:
    /// the time step at [`SERVO_RAYLEIGH_FRACTION`] of the smallest ball's Rayleigh time,
    /// whatever the run's step, so that the lateral walls' stress lag behind a dilating packing
    /// (`~ 1.5 v tau / (alpha delta)` of p0, `Stress::servo`) does not grow with the step.
    /// Equal to [`TriaxialParams::time_step`], bit for bit, at the default 0.2. (The
    /// compaction's servo keeps its gain per step: its packing is the default's only at the
    /// default step anyway, docs/results/triaxial-timestep.)
    pub fn servo_time(&self) -> f64 {
        let r_min = self.radius * (1.0 - self.radius_spread);
        SERVO_RAYLEIGH_FRACTION * creep_law::hertz::rayleigh_time_step(&self.material, r_min)
    }
}

/// The Rayleigh fraction whose time step is the shear servo's time
/// ([`TriaxialParams::servo_time`]): the default step's.
pub const SERVO_RAYLEIGH_FRACTION: f64 = 0.2;

/// The engine a triaxial test runs on (`engine = "dem"` or `"rapier"` in the TOML file).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum TriaxialEngine {
    /// creep-dem ([`super::DemSpecimen`]): f64, neighbour lists, the exact tangential tier;
    /// the default (it agrees with the Rapier regime sheared from the same packing: the user
    /// guide, docs/guide, "The DEM engine and the talk's triaxial test").
    #[default]
    Dem,
    /// The compliant regime of creep-rapier ([`super::Specimen`]).
    Rapier,
}

impl std::str::FromStr for TriaxialEngine {
    type Err = SceneError;
    fn from_str(s: &str) -> Result<Self, SceneError> {
        match s.trim() {
            "dem" => Ok(Self::Dem),
            "rapier" => Ok(Self::Rapier),
            other => Err(SceneError::Parameter(format!(
                "triaxial: engine `{other}` must be `dem` or `rapier`"
            ))),
        }
    }
}

impl TriaxialEngine {
    /// `dem` or `rapier`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dem => "dem",
            Self::Rapier => "rapier",
        }
    }
}

/// A triaxial parameters file (`crates/cli/assets/triaxial.toml`, a run's `params.toml`): the
/// engine and the test's parameters.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct TriaxialConfig {
    /// The engine the test runs on.
    pub engine: TriaxialEngine,
    /// The test's parameters (validated).
    pub params: TriaxialParams,
}

impl TriaxialConfig {
    /// Reads a TOML text: keys not given keep their defaults ([`TriaxialConfig::default`]);
    /// an unknown key, a wrong type or a value out of range is a [`SceneError::Parameter`]
    /// naming the key.
    pub fn from_toml(text: &str) -> Result<Self, SceneError> {
        let file: ConfigFile = toml::from_str(text)
            .map_err(|e| SceneError::Parameter(format!("triaxial parameters: {e}")))?;
        file.config()
    }

    /// The TOML text of these parameters (every key; [`TriaxialConfig::from_toml`] reads it
    /// back to the same values: floats are written with Rust's shortest round-trip form).
    pub fn to_toml(&self) -> Result<String, SceneError> {
        self.params.validate()?;
        toml::to_string(&ConfigFile::from(*self))
            .map_err(|e| SceneError::Parameter(format!("triaxial parameters: {e}")))
    }
}

/// The file's flat form: the material's constants are keys of their own.
#[derive(Debug, Clone, Copy, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
struct ConfigFile {
    engine: TriaxialEngine,
    n_per_side: usize,
    radius: f64,
    radius_spread: f64,
    shear_modulus: f64,
    poisson_ratio: f64,
    density: f64,
    mu: f64,
    restitution: f64,
    confining_pressure: f64,
    inertial_number: f64,
    axial_strain: f64,
    rayleigh_fraction: f64,
    shear_rayleigh_fraction: f64,
    seed: u64,
    rows_per_percent: usize,
}

impl Default for ConfigFile {
    fn default() -> Self {
        Self::from(TriaxialConfig::default())
    }
}

impl From<TriaxialConfig> for ConfigFile {
    fn from(c: TriaxialConfig) -> Self {
        let p = c.params;
        Self {
            engine: c.engine,
            n_per_side: p.n_per_side,
            radius: p.radius,
            radius_spread: p.radius_spread,
            shear_modulus: p.material.shear_modulus(),
            poisson_ratio: p.material.poisson_ratio(),
            density: p.material.density(),
            mu: p.mu,
            restitution: p.restitution,
            confining_pressure: p.confining_pressure,
            inertial_number: p.inertial_number,
            axial_strain: p.axial_strain,
            rayleigh_fraction: p.rayleigh_fraction,
            shear_rayleigh_fraction: p.shear_rayleigh_fraction,
            seed: p.seed,
            rows_per_percent: p.rows_per_percent,
        }
    }
}

impl ConfigFile {
    /// The validated configuration (the material's checks, then every range).
    fn config(self) -> Result<TriaxialConfig, SceneError> {
        let params = TriaxialParams {
            n_per_side: self.n_per_side,
            radius: self.radius,
            radius_spread: self.radius_spread,
            material: Material::new(
                self.shear_modulus,
                self.poisson_ratio,
                self.mu,
                self.density,
            )?,
            mu: self.mu,
            restitution: self.restitution,
            confining_pressure: self.confining_pressure,
            inertial_number: self.inertial_number,
            axial_strain: self.axial_strain,
            rayleigh_fraction: self.rayleigh_fraction,
            shear_rayleigh_fraction: self.shear_rayleigh_fraction,
            seed: self.seed,
            rows_per_percent: self.rows_per_percent,
        };
        params.validate()?;
        Ok(TriaxialConfig {
            engine: self.engine,
            params,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_unknown_key_is_an_error_naming_it() {
        let e = TriaxialConfig::from_toml("mu = 0.4\ncolour = \"blue\"\n").unwrap_err();
        assert!(matches!(e, SceneError::Parameter(_)), "{e:?}");
        assert!(e.to_string().contains("colour"), "{e}");
    }

    #[test]
    fn keys_not_given_keep_the_defaults() {
        let c = TriaxialConfig::from_toml("mu = 0.4\nengine = \"dem\"\nseed = 7").unwrap();
        assert_eq!(c.engine, TriaxialEngine::Dem);
        assert_eq!(c.params.mu, 0.4);
        assert_eq!(c.params.seed, 7);
        assert_eq!(c.params.radius, TriaxialParams::default().radius);
        assert_eq!(
            TriaxialConfig::from_toml("").unwrap(),
            TriaxialConfig::default()
        );
    }

    #[test]
    fn written_parameters_read_back_the_same() {
        let c = TriaxialConfig {
            engine: TriaxialEngine::Dem,
            params: TriaxialParams {
                radius: 1.234_567_890_123e-3,
                inertial_number: 0.01 + 0.02,
                seed: i64::MAX as u64,
                ..TriaxialParams::quick()
            },
        };
        let text = c.to_toml().unwrap();
        assert_eq!(TriaxialConfig::from_toml(&text).unwrap(), c, "{text}");
        // Every key is written.
        for key in [
            "engine",
            "shear_modulus",
            "density",
            "seed",
            "rows_per_percent",
        ] {
            assert!(text.contains(&format!("{key} = ")), "{key}: {text}");
        }
    }

    #[test]
    fn wrong_types_and_out_of_range_values_are_errors() {
        for text in [
            "seed = -1",
            "n_per_side = 2.5",
            "engine = \"lammps\"",
            "mu = \"high\"",
            "radius_spread = 0.9",
        ] {
            assert!(TriaxialConfig::from_toml(text).is_err(), "{text}");
        }
        assert!(TriaxialConfig::from_toml("seed = 1").is_ok());
        let big = TriaxialConfig {
            params: TriaxialParams {
                seed: u64::MAX,
                ..TriaxialParams::default()
            },
            ..TriaxialConfig::default()
        };
        assert!(big.to_toml().is_err());
    }
}
