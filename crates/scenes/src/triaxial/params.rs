//! The test's parameters, their ranges and the `key = value` config file.

use creep_law::Material;

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
    /// Time step as a fraction of the smallest Rayleigh time, in `(0, 0.3]`.
    pub rayleigh_fraction: f64,
    /// Seed of the packing's generator.
    pub seed: u64,
    /// Rows recorded per 1 % of axial strain (>= 1).
    pub rows_per_percent: usize,
}

impl Default for TriaxialParams {
    /// The default test: 4,096 softened-glass spheres of mean radius 1 mm (radii +-20 %),
    /// G = 29 MPa, nu = 0.2, rho = 2,500 kg/m^3, mu = 0.5, e = 0.5, p0 = 100 kPa, I = 8e-4,
    /// 20 % axial strain, dt = 0.2 T_R (the repository's `assets/triaxial.conf`).
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
            "rows_per_percent",
            self.rows_per_percent as f64,
            1.0,
            1e3,
            false,
        )?;
        Ok(())
    }

    /// Parameters from a `key = value` text (the form of the repository's
    /// `assets/triaxial.conf`; `#` starts a comment); keys not given keep their defaults.
    pub fn from_conf(text: &str) -> Result<Self, SceneError> {
        let mut p = Self::default();
        let (mut g, mut nu, mut rho) = (
            p.material.shear_modulus(),
            p.material.poisson_ratio(),
            p.material.density(),
        );
        for (i, line) in text.lines().enumerate() {
            let line = line.split('#').next().unwrap_or("").trim();
            if line.is_empty() {
                continue;
            }
            let bad = |why: &str| {
                SceneError::Parameter(format!("triaxial config line {}: {why}: `{line}`", i + 1))
            };
            let (key, value) = line
                .split_once('=')
                .ok_or_else(|| bad("expected key = value"))?;
            let (key, value) = (key.trim(), value.trim());
            let num = || value.parse::<f64>().map_err(|_| bad("not a number"));
            let int = || value.parse::<u64>().map_err(|_| bad("not a whole number"));
            match key {
                "n_per_side" => p.n_per_side = int()? as usize,
                "radius" => p.radius = num()?,
                "radius_spread" => p.radius_spread = num()?,
                "shear_modulus" => g = num()?,
                "poisson_ratio" => nu = num()?,
                "density" => rho = num()?,
                "mu" => p.mu = num()?,
                "restitution" => p.restitution = num()?,
                "confining_pressure" => p.confining_pressure = num()?,
                "inertial_number" => p.inertial_number = num()?,
                "axial_strain" => p.axial_strain = num()?,
                "rayleigh_fraction" => p.rayleigh_fraction = num()?,
                "seed" => p.seed = int()?,
                "rows_per_percent" => p.rows_per_percent = int()? as usize,
                // The engine is the runner's choice ([`TriaxialEngine::from_conf`]); checked here.
                "engine" => {
                    value.parse::<TriaxialEngine>()?;
                }
                _ => return Err(bad("unknown key")),
            }
        }
        p.material = Material::new(g, nu, p.mu, rho)?;
        p.validate()?;
        Ok(p)
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

    /// Time step \[s\]: `rayleigh_fraction` of the smallest ball's Rayleigh time.
    pub fn time_step(&self) -> f64 {
        let r_min = self.radius * (1.0 - self.radius_spread);
        self.rayleigh_fraction * creep_law::hertz::rayleigh_time_step(&self.material, r_min)
    }
}

/// The engine a triaxial test runs on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum TriaxialEngine {
    /// creep-dem ([`super::DemSpecimen`]): f64, neighbour lists, the exact tangential tier.
    Dem,
    /// The compliant regime of creep-rapier ([`super::Specimen`]); the default until a full
    /// creep-dem run reproduces its published results.
    #[default]
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
    /// The `engine = dem|rapier` key of a config text (the form of
    /// [`TriaxialParams::from_conf`]); the default ([`TriaxialEngine::Dem`]) when absent.
    pub fn from_conf(text: &str) -> Result<Self, SceneError> {
        let mut engine = Self::default();
        for line in text.lines() {
            let line = line.split('#').next().unwrap_or("").trim();
            if let Some((key, value)) = line.split_once('=')
                && key.trim() == "engine"
            {
                engine = value.parse()?;
            }
        }
        Ok(engine)
    }

    /// `dem` or `rapier`.
    pub fn name(self) -> &'static str {
        match self {
            Self::Dem => "dem",
            Self::Rapier => "rapier",
        }
    }
}
