//! The triaxial test on the creep-dem engine ([`creep_dem::Dem`], f64, the exact
//! Cattaneo-Mindlin tier [`creep_dem::Exact`] with Kuhn's creep): the same packing as
//! [`Specimen::generate`] (moved into the engine by [`dem_engine`]), the same walls (planes at the
//! inner faces, frictionless), the same protocol ([`compact_dem`], [`shear_dem`]: the code of
//! [`super::compact`] and [`super::shear`]) and the same measurements.

use creep_dem::checkpoint::{CheckpointError, CheckpointReader, CheckpointWriter};
use creep_dem::{ContactLoad, Dem, Exact, MaterialTable};
use creep_law::pair::PairConstants;
use creep_law::{CreepModel, Vec2, Vec3};

use super::params::TriaxialParams;
use super::protocol::{CompactionSummary, Host, ShearRun, compact_on, shear_on};
use super::specimen::{Specimen, dem_engine};
use super::stress::{CREEPING, Stress};
use crate::SceneError;

fn dem_err(e: creep_dem::DemError) -> SceneError {
    SceneError::Parameter(format!("DEM engine: {e}"))
}

/// The material table of the test: balls (material 0) with friction `mu` and Kuhn's creep or
/// none, walls (material 1) frictionless against the balls (Rapier's `Min` rule with the
/// walls' 0 in the compliant regime).
pub(super) fn table(p: &TriaxialParams, mu: f64, creep: bool) -> Result<MaterialTable, SceneError> {
    let ball = p.material.with_friction(mu)?;
    let wall = p.material.with_friction(0.0)?;
    let model = creep.then_some(CreepModel::Kuhn);
    let mut t = MaterialTable::new(&[ball, wall], p.restitution, model, None).map_err(dem_err)?;
    t.set_pair(
        0,
        1,
        PairConstants::new(&ball, &wall, 0.0, p.restitution, model, None)?,
    )
    .map_err(dem_err)?;
    Ok(t)
}

/// The shears' neighbour skin as a fraction of the mean diameter. The generation and the
/// compaction keep [`dem_engine`]'s 0.02 (the peers' in `bench/peers`, as `creep bench dem`),
/// so the compacted packing is the one they always gave, bit for bit; each shear's copy then
/// sets this skin ([`creep_dem::Dem::set_skin`]). With 0.02 the shears rebuilt the list every
/// 8.8 steps (1,169 rebuilds in 10,269 steps), with 0.1 every ~48 (216), while the longer list
/// adds 0.2 % to a step's instructions (exact tier, 4,096 packing: 3.69 -> 4.28 entries per
/// particle); docs/results/triaxial-shear-skin. The physics is the same; the shears' results
/// differ at the rounding level (the list's order, and so the order of each particle's force
/// sum, follows the rebuilds).
pub const SHEAR_SKIN: f64 = 0.1;

/// A packing in its box of six servo walls, in the creep-dem engine. Wall `k` is on axis
/// `k / 2`, on the low side for even `k` (as [`Specimen`]'s).
#[derive(Debug, Clone)]
pub struct DemSpecimen {
    dem: Dem<Exact>,
    params: TriaxialParams,
    steps: usize,
    /// Creep and slip dissipation at the last [`Host::reset_energy`] \[J\].
    energy0: (f64, f64),
}

impl DemSpecimen {
    /// Generates the loose packing of [`Specimen::generate`] (same seed, same balls) in the
    /// engine, frictionless for the compaction.
    pub fn generate(params: TriaxialParams) -> Result<Self, SceneError> {
        Self::from_specimen(&Specimen::generate(params)?)
    }

    /// The balls and walls of a Rapier specimen (positions, velocities, wall speeds; e.g. one
    /// compacted by [`super::compact`]) moved into the engine, frictionless, with fresh contact
    /// histories (a frictionless packing's histories hold no tangential force): the two engines
    /// can then shear the same packing.
    pub fn from_specimen(rapier: &Specimen) -> Result<Self, SceneError> {
        let params = *rapier.params();
        let mut dem = dem_engine::<Exact>(rapier, false, false)?;
        dem.set_table(table(&params, 0.0, false)?)
            .map_err(dem_err)?;
        Ok(Self {
            dem,
            params,
            steps: rapier.steps(),
            energy0: (0.0, 0.0),
        })
    }

    /// The engine.
    pub fn engine(&self) -> &Dem<Exact> {
        &self.dem
    }

    /// Writes the specimen (engine, step count, energy reference) into a checkpoint payload.
    pub(super) fn write_checkpoint(&self, w: &mut CheckpointWriter) {
        self.dem.write_checkpoint(w);
        w.usize(self.steps);
        w.f64(self.energy0.0);
        w.f64(self.energy0.1);
    }

    /// Reads a specimen written by [`DemSpecimen::write_checkpoint`], with the parameters and
    /// the material table of its phase.
    pub(super) fn read_checkpoint(
        r: &mut CheckpointReader<'_>,
        params: TriaxialParams,
        table: MaterialTable,
    ) -> Result<Self, CheckpointError> {
        let dem = Dem::read_checkpoint(r, table, false)?;
        Ok(Self {
            dem,
            params,
            steps: r.usize()?,
            energy0: (r.f64()?, r.f64()?),
        })
    }

    /// The parameters.
    pub fn params(&self) -> &TriaxialParams {
        &self.params
    }

    /// Number of balls.
    pub fn len(&self) -> usize {
        self.dem.len()
    }

    /// Whether there are no balls.
    pub fn is_empty(&self) -> bool {
        self.dem.is_empty()
    }

    /// The stresses of the module docs from the loads the contacts carry
    /// ([`Dem::for_each_contact_load`]: the forces of [`Dem::for_each_contact_force`] with
    /// `dt = 0` without running the tangential law, cheap enough for every step); with
    /// `love_too` false the walls' entries only (the wall contacts alone; the Love-Weber tensor
    /// then holds only their share and is not a stress).
    fn measure(&self, love_too: bool) -> Stress {
        let dims = self.dims();
        let volume = dims[0] * dims[1] * dims[2];
        let mut st = Stress {
            dims,
            ..Stress::default()
        };
        let love = &mut st.love;
        let mut add = |arm: Vec3, f: Vec3| {
            let (a, f) = ([arm.x, arm.y, arm.z], [f.x, f.y, f.z]);
            for i in 0..3 {
                for j in 0..3 {
                    love[i][j] -= a[i] * f[j] / volume;
                }
            }
        };
        let each = |c: ContactLoad| {
            let f = c.force_p;
            match c.wall {
                None => add(c.x_q - c.x_p, f),
                Some(k) => {
                    // The ball is q and gets -f; the wall gets f.
                    add(c.point - c.x_q, -f);
                    st.each[k] += side(k) * comp(f, k / 2);
                    st.stiffness[k] += 1.5 * c.normal_force / c.overlap;
                }
            }
        };
        if love_too {
            self.dem.for_each_contact_load(each);
        } else {
            self.dem.for_each_wall_contact_load(each);
        }
        for axis in 0..3 {
            let area = dims[(axis + 1) % 3] * dims[(axis + 2) % 3];
            st.each[2 * axis] /= area;
            st.each[2 * axis + 1] /= area;
            st.walls[axis] = 0.5 * (st.each[2 * axis] + st.each[2 * axis + 1]);
        }
        st
    }

    /// Box dimensions between the walls' planes \[m\].
    fn dims(&self) -> [f64; 3] {
        let w = self.dem.walls();
        std::array::from_fn(|a| comp(w[2 * a + 1].point, a) - comp(w[2 * a].point, a))
    }
}

/// Component `a` of `v`.
fn comp(v: Vec3, a: usize) -> f64 {
    [v.x, v.y, v.z][a]
}

/// Wall `k`'s side: +1 for the high wall of its axis.
fn side(k: usize) -> f64 {
    if k % 2 == 1 { 1.0 } else { -1.0 }
}

impl Host for DemSpecimen {
    fn params(&self) -> &TriaxialParams {
        &self.params
    }

    /// The stresses of the module docs from the loads the contacts carry
    /// ([`DemSpecimen::measure`]).
    fn stress(&self) -> Stress {
        self.measure(true)
    }

    /// The walls' entries only ([`DemSpecimen::measure`]).
    fn wall_stress(&self) -> Stress {
        self.measure(false)
    }

    fn set_wall_speeds(&mut self, outward: [f64; 6]) -> Result<(), SceneError> {
        for (k, v) in outward.into_iter().enumerate() {
            let mut vel = [0.0; 3];
            vel[k / 2] = side(k) * v;
            let vel = Vec3::new(vel[0], vel[1], vel[2]);
            self.dem.set_wall_velocity(k, vel).map_err(dem_err)?;
        }
        Ok(())
    }

    fn step(&mut self) -> Result<(), SceneError> {
        self.dem.step().map_err(dem_err)?;
        self.steps += 1;
        Ok(())
    }

    fn steps(&self) -> usize {
        self.steps
    }

    fn len(&self) -> usize {
        self.dem.len()
    }

    /// The shares from one more step's increments at the current velocities
    /// ([`Dem::for_each_contact_force`] with the engine's time step; the compliant regime
    /// reports those of the last step).
    fn contact_shares(&self) -> (usize, usize, usize, usize) {
        let (mut n, mut sliding, mut rolling, mut creeping) = (0, 0, 0, 0);
        self.dem.for_each_contact_force(self.dem.config().dt, |c| {
            if c.wall.is_some() {
                return;
            }
            let f = &c.forces;
            n += 1;
            sliding += usize::from(f.sliding);
            let creep_ratio = if f.slide_length > 0.0 {
                f.creep_displacement.length() / f.slide_length
            } else if f.creep_displacement != Vec2::ZERO {
                f64::INFINITY
            } else {
                0.0
            };
            creeping += usize::from(creep_ratio >= CREEPING);
            rolling += usize::from(f.v_roll.length() > f.v_disp.length());
        });
        (n, sliding, rolling, creeping)
    }

    fn solids(&self) -> f64 {
        self.dem
            .radii()
            .iter()
            .map(|r| 4.0 / 3.0 * std::f64::consts::PI * r * r * r)
            .sum()
    }

    fn kinetic_energy(&self) -> f64 {
        self.dem.kinetic_energy()
    }

    fn shear_copy(&self, creep: bool) -> Result<Self, SceneError> {
        let mut s = self.clone();
        s.dem
            .set_table(table(&self.params, self.params.mu, creep)?)
            .map_err(dem_err)?;
        s.dem
            .set_time_step(self.params.shear_time_step())
            .map_err(dem_err)?;
        s.dem
            .set_skin(SHEAR_SKIN * self.params.mean_diameter())
            .map_err(dem_err)?;
        Ok(s)
    }

    fn reset_energy(&mut self) {
        let e = self.dem.energy();
        self.energy0 = (e.creep, e.slip);
    }

    fn dissipation(&self) -> (f64, f64) {
        let e = self.dem.energy();
        (e.creep - self.energy0.0, e.slip - self.energy0.1)
    }

    fn rebuilds(&self) -> Option<usize> {
        Some(self.dem.counts().rebuilds)
    }
}

/// [`super::compact`] on the creep-dem engine.
pub fn compact_dem(
    specimen: &mut DemSpecimen,
    max_steps: usize,
    progress: &mut dyn FnMut(f64),
) -> Result<CompactionSummary, SceneError> {
    compact_on(specimen, max_steps, progress, &mut |_| {})
}

/// [`super::shear`] on the creep-dem engine.
pub fn shear_dem(
    specimen: &DemSpecimen,
    creep: bool,
    progress: &mut dyn FnMut(f64),
) -> Result<ShearRun, SceneError> {
    shear_on(specimen, creep, progress, &mut |_, _| {})
}
