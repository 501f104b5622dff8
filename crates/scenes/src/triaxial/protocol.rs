//! The protocols: isotropic compaction and drained shear at constant lateral stress.

use super::TriaxialRow;
use super::params::TriaxialParams;
use super::report::row;
use super::specimen::Specimen;
use super::stress::Stress;
use crate::SceneError;

/// Summary of the isotropic compaction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CompactionSummary {
    /// Steps taken.
    pub steps: usize,
    /// Solid fraction reached [-].
    pub solid_fraction: f64,
    /// Mean wall stress \[Pa\].
    pub p_walls: f64,
    /// Mean stress from the contacts \[Pa\].
    pub p_contacts: f64,
    /// Largest deviation of a wall's stress from `p0`, relative [-].
    pub max_wall_error: f64,
    /// Mean coordination number [-].
    pub coordination: f64,
    /// Neighbour-list rebuilds during the compaction (`None` on an engine without a list).
    pub rebuilds: Option<usize>,
}

/// Compacts the specimen isotropically to `p0` (frictionless balls, all walls servo-controlled),
/// until every wall is within 1 % of `p0` and the contact stress agrees with the walls' within
/// 1 % for 200 consecutive steps; `progress(fraction)` is called as it goes (the fraction is an
/// estimate: the steps are not known in advance). Errors if it has not settled after
/// `max_steps`.
pub fn compact(
    specimen: &mut Specimen,
    max_steps: usize,
    progress: &mut dyn FnMut(f64),
) -> Result<CompactionSummary, SceneError> {
    compact_observed(specimen, max_steps, progress, &mut |_| {})
}

/// [`compact`], calling `observe` with the specimen after every step (e.g. to draw it: the
/// desktop demo `triaxial_view`).
pub fn compact_observed(
    specimen: &mut Specimen,
    max_steps: usize,
    progress: &mut dyn FnMut(f64),
    observe: &mut dyn FnMut(&Specimen),
) -> Result<CompactionSummary, SceneError> {
    compact_on(specimen, max_steps, progress, observe)
}

/// [`compact_observed`] on either engine (the one protocol of both).
pub(super) fn compact_on<E: Host>(
    specimen: &mut E,
    max_steps: usize,
    progress: &mut dyn FnMut(f64),
    observe: &mut dyn FnMut(&E),
) -> Result<CompactionSummary, SceneError> {
    let mut state = CompactLoop::start(specimen);
    loop {
        if let Some(sum) = state.advance(specimen, max_steps, progress, observe)? {
            return Ok(sum);
        }
    }
}

/// The compaction's loop between two steps: what a run needs to continue (with the
/// specimen), so that a stopped run resumes it exactly (`DemRun`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct CompactLoop {
    /// Steps taken.
    pub(super) i: usize,
    /// Consecutive settled steps.
    pub(super) settled_for: usize,
    /// The stress after the last step (the servo's next input).
    pub(super) last: Stress,
}

impl CompactLoop {
    pub(super) fn start<E: Host>(specimen: &E) -> Self {
        Self {
            i: 0,
            settled_for: 0,
            last: specimen.wall_stress(),
        }
    }

    /// One step of the compaction: `Some(summary)` once it has settled; an error if it has not
    /// after `max_steps`.
    pub(super) fn advance<E: Host>(
        &mut self,
        specimen: &mut E,
        max_steps: usize,
        progress: &mut dyn FnMut(f64),
        observe: &mut dyn FnMut(&E),
    ) -> Result<Option<CompactionSummary>, SceneError> {
        let p0 = specimen.params().confining_pressure;
        if self.i >= max_steps {
            let p_walls = self.last.walls.iter().sum::<f64>() / 3.0;
            return Err(SceneError::Parameter(format!(
                "triaxial: the isotropic compaction did not settle in {max_steps} steps (mean wall stress {p_walls:.4e} Pa against p0 = {p0:.4e} Pa)"
            )));
        }
        let i = self.i;
        self.i += 1;
        let rate = specimen.params().strain_rate();
        let dt = specimen.params().time_step();
        // The stress after a step is the next servo input (stress() is a pure function of the
        // state), so it is measured once per step. The servo reads only the walls' entries; the
        // contact (Love-Weber) stress matters only in steps where every wall is within 1 % of
        // p0 (otherwise the settling count restarts whatever it is), so it is measured only
        // then: the same decisions, bit for bit, as measuring it every step, without a pass
        // over every contact in the steps where the walls are still off (the stress of the
        // walls' contacts is the same sum, in the same order, either way:
        // `Host::wall_stress`).
        let s = self.last;
        let mut v = [0.0; 6];
        // Fast while nothing touches (a gas: up to 20 eps_dot), then at most 5 eps_dot.
        let cap = if s.walls.iter().all(|&w| w < 0.05 * p0) {
            20.0
        } else {
            5.0
        };
        for (k, vk) in v.iter_mut().enumerate() {
            *vk = s.servo(k, p0, dt, cap * rate * s.dims[k / 2] / 2.0);
        }
        specimen.set_wall_speeds(v)?;
        specimen.step()?;
        observe(specimen);
        self.last = specimen.wall_stress();
        let last = &mut self.last;
        let wall_err = last
            .each
            .iter()
            .map(|&w| (w / p0 - 1.0).abs())
            .fold(0.0, f64::max);
        let p_walls = last.walls.iter().sum::<f64>() / 3.0;
        let mut p_love = f64::NAN;
        if wall_err < 0.01 {
            *last = specimen.stress();
            p_love = (last.love[0][0] + last.love[1][1] + last.love[2][2]) / 3.0;
        }
        let agree = (p_love / p_walls - 1.0).abs();
        // `agree` is NaN (and the comparison false) when the contact stress was not measured.
        if wall_err < 0.01 && agree < 0.01 {
            self.settled_for += 1;
        } else {
            self.settled_for = 0;
        }
        if i.is_multiple_of(200) {
            let est = (p_walls / p0).clamp(0.0, 1.0) * 0.9 + 0.1 * self.settled_for as f64 / 200.0;
            progress(est);
        }
        if self.settled_for >= 200 {
            specimen.set_wall_speeds([0.0; 6])?;
            progress(1.0);
            let (n, ..) = specimen.contact_shares();
            let dims = self.last.dims;
            return Ok(Some(CompactionSummary {
                steps: i + 1,
                solid_fraction: specimen.solids() / (dims[0] * dims[1] * dims[2]),
                p_walls,
                p_contacts: p_love,
                max_wall_error: wall_err,
                coordination: 2.0 * n as f64 / specimen.len() as f64,
                rebuilds: specimen.rebuilds(),
            }));
        }
        Ok(None)
    }
}

/// The record of one shear.
#[derive(Debug, Clone, PartialEq)]
pub struct ShearRun {
    /// Whether Kuhn's creep term was on.
    pub creep: bool,
    /// The rows, from the start of the shear.
    pub rows: Vec<TriaxialRow>,
    /// Steps taken.
    pub steps: usize,
    /// Largest relative difference of the contact stress (p and q) from the walls' over the
    /// rows after 1 % axial strain (quasi-static check) [-].
    pub max_stress_mismatch: f64,
    /// Energy dissipated by creep over the shear \[J\].
    pub creep_dissipation: f64,
    /// Energy dissipated by slip over the shear \[J\].
    pub slip_dissipation: f64,
    /// Neighbour-list rebuilds during the shear (`None` on an engine without a list).
    pub rebuilds: Option<usize>,
}

/// Shears a copy of the compacted `specimen` (drained, constant lateral stress, module docs)
/// to the final axial strain, with creep-friction on or off; `progress(fraction)` is called
/// as it goes.
pub fn shear(
    specimen: &Specimen,
    creep: bool,
    progress: &mut dyn FnMut(f64),
) -> Result<ShearRun, SceneError> {
    shear_observed(specimen, creep, progress, &mut |_, _| {})
}

/// [`shear`], calling `observe` with the sheared copy before every step and at the end, with
/// the row when one was recorded there (e.g. to draw it: the desktop demo `triaxial_view`).
pub fn shear_observed(
    specimen: &Specimen,
    creep: bool,
    progress: &mut dyn FnMut(f64),
    observe: &mut dyn FnMut(&Specimen, Option<&TriaxialRow>),
) -> Result<ShearRun, SceneError> {
    shear_on(specimen, creep, progress, observe)
}

/// [`shear_observed`] on either engine (the one protocol of both).
pub(super) fn shear_on<E: Host>(
    specimen: &E,
    creep: bool,
    progress: &mut dyn FnMut(f64),
    observe: &mut dyn FnMut(&E, Option<&TriaxialRow>),
) -> Result<ShearRun, SceneError> {
    let (mut s, mut state) = ShearLoop::start(specimen, creep)?;
    while !state.advance(&mut s, progress, observe)? {}
    Ok(state.finish(&s, specimen))
}

/// The shear's loop between two steps: what a run needs to continue (with the sheared
/// copy), so that a stopped run resumes it exactly (`DemRun`).
#[derive(Debug, Clone, PartialEq)]
pub(super) struct ShearLoop {
    pub(super) creep: bool,
    /// Iteration (steps of the shear after the first one at rest).
    pub(super) i: usize,
    /// Height and volume of the box after the first step at rest.
    pub(super) h0: f64,
    pub(super) v0: f64,
    /// Volume of the balls.
    pub(super) solids: f64,
    pub(super) total_steps: usize,
    pub(super) record_every: usize,
    pub(super) rows: Vec<TriaxialRow>,
    pub(super) mismatch: f64,
}

impl ShearLoop {
    /// The copy of the compacted `specimen` to shear, after its first step at rest, and the
    /// loop's start.
    pub(super) fn start<E: Host>(specimen: &E, creep: bool) -> Result<(E, Self), SceneError> {
        // A copy with the balls' friction on (the walls stay frictionless) and creep on or off.
        let mut s = specimen.shear_copy(creep)?;
        let params = *s.params();
        let rate = params.strain_rate();
        let dt = params.shear_time_step();
        // One step at rest, so that the fresh regime has found its contacts.
        s.set_wall_speeds([0.0; 6])?;
        s.step()?;
        let s0 = s.stress();
        let h0 = s0.dims[1];
        let v0 = s0.dims[0] * s0.dims[1] * s0.dims[2];
        let solids = s.solids();
        let total_steps = (params.axial_strain / (rate * dt)).ceil() as usize;
        let record_every = (total_steps as f64
            / (params.axial_strain * 100.0 * params.rows_per_percent as f64))
            .max(1.0) as usize;
        s.reset_energy();
        Ok((
            s,
            Self {
                creep,
                i: 0,
                h0,
                v0,
                solids,
                total_steps,
                record_every,
                rows: Vec::new(),
                mismatch: 0.0,
            },
        ))
    }

    /// One iteration of the shear (a row when due, then a step): `true` when the shear is
    /// over (no step taken then).
    pub(super) fn advance<E: Host>(
        &mut self,
        s: &mut E,
        progress: &mut dyn FnMut(f64),
        observe: &mut dyn FnMut(&E, Option<&TriaxialRow>),
    ) -> Result<bool, SceneError> {
        let params = *s.params();
        let p0 = params.confining_pressure;
        let rate = params.strain_rate();
        // The lateral servo's gain is per `servo_time`, not per step (its stress lag would grow
        // with the step: `TriaxialParams::servo_time`).
        let servo_time = params.servo_time();
        let (i, h0) = (self.i, self.h0);
        let st = s.wall_stress();
        let eps_a = (h0 - st.dims[1]) / h0;
        let last = i == self.total_steps || eps_a >= params.axial_strain;
        if i.is_multiple_of(self.record_every) || last {
            let row = row(s, &s.stress(), eps_a, self.v0, self.solids);
            if eps_a > 0.01 {
                let dp = (row.p_contacts / row.p - 1.0).abs();
                let dq = ((row.q_contacts - row.q) / row.p).abs();
                self.mismatch = self.mismatch.max(dp).max(dq);
            }
            self.rows.push(row);
            progress(i as f64 / self.total_steps as f64);
            observe(s, self.rows.last());
        } else {
            observe(s, None);
        }
        if last {
            return Ok(true);
        }
        let mut v = [0.0; 6];
        for (k, vk) in v.iter_mut().enumerate() {
            *vk = if k / 2 == 1 {
                -0.5 * rate * h0
            } else {
                st.servo(k, p0, servo_time, 5.0 * rate * st.dims[k / 2] / 2.0)
            };
        }
        s.set_wall_speeds(v)?;
        s.step()?;
        self.i += 1;
        Ok(false)
    }

    /// The record of the finished shear of the copy `s` of `specimen`.
    pub(super) fn finish<E: Host>(self, s: &E, specimen: &E) -> ShearRun {
        let (creep_dissipation, slip_dissipation) = s.dissipation();
        let rebuilds = s
            .rebuilds()
            .zip(specimen.rebuilds())
            .map(|(a, b)| a.saturating_sub(b));
        ShearRun {
            creep: self.creep,
            steps: s.steps() - specimen.steps(),
            rows: self.rows,
            max_stress_mismatch: self.mismatch,
            creep_dissipation,
            slip_dissipation,
            rebuilds,
        }
    }
}

/// What the protocol needs of an engine: the Rapier compliant regime ([`Specimen`]) or
/// creep-dem ([`super::DemSpecimen`]). Wall `k` is on axis `k / 2`, on the low side for even
/// `k`.
pub(super) trait Host: Sized {
    /// The parameters.
    fn params(&self) -> &TriaxialParams;
    /// Wall and contact stresses of the current state.
    fn stress(&self) -> Stress;
    /// [`Host::stress`] where only the walls' entries (`dims`, `walls`, `each`, `stiffness`)
    /// are needed: the servo's input.
    fn wall_stress(&self) -> Stress {
        self.stress()
    }
    /// Sets each wall's outward speed [m/s].
    fn set_wall_speeds(&mut self, outward: [f64; 6]) -> Result<(), SceneError>;
    /// One time step.
    fn step(&mut self) -> Result<(), SceneError>;
    /// Steps taken since generation.
    fn steps(&self) -> usize;
    /// Number of balls.
    fn len(&self) -> usize;
    /// Ball-ball contacts: (contacts, sliding, rolling, creeping).
    fn contact_shares(&self) -> (usize, usize, usize, usize);
    /// Volume of the balls [m^3].
    fn solids(&self) -> f64;
    /// Kinetic energy of the balls \[J\].
    fn kinetic_energy(&self) -> f64;
    /// A copy for the shear: the balls' friction `mu`, creep on or off.
    fn shear_copy(&self, creep: bool) -> Result<Self, SceneError>;
    /// Starts the dissipation count.
    fn reset_energy(&mut self);
    /// Creep and slip dissipation since [`Host::reset_energy`] \[J\].
    fn dissipation(&self) -> (f64, f64);
    /// Neighbour-list rebuilds since generation, for an engine with a list.
    fn rebuilds(&self) -> Option<usize> {
        None
    }
}

impl Host for Specimen {
    fn params(&self) -> &TriaxialParams {
        Specimen::params(self)
    }
    fn stress(&self) -> Stress {
        Specimen::stress(self)
    }
    fn set_wall_speeds(&mut self, outward: [f64; 6]) -> Result<(), SceneError> {
        Specimen::set_wall_speeds(self, outward);
        Ok(())
    }
    fn step(&mut self) -> Result<(), SceneError> {
        Specimen::step(self)
    }
    fn steps(&self) -> usize {
        Specimen::steps(self)
    }
    fn len(&self) -> usize {
        Specimen::len(self)
    }
    fn contact_shares(&self) -> (usize, usize, usize, usize) {
        Specimen::contact_shares(self)
    }
    fn solids(&self) -> f64 {
        Specimen::solids(self)
    }
    fn kinetic_energy(&self) -> f64 {
        Specimen::kinetic_energy(self)
    }
    fn shear_copy(&self, creep: bool) -> Result<Self, SceneError> {
        let mut s = self.clone_fresh(creep)?;
        // Friction on the balls (the walls stay frictionless by their Min combine rule).
        for &(_, c) in &s.balls {
            if let Some(co) = s.world.physics.colliders.get_mut(c) {
                co.set_friction(s.params.mu as f32);
            }
        }
        // The shears' step, and the compliant regime's Rayleigh check at its fraction.
        s.world.physics.integration_parameters.dt = s.params.shear_time_step() as f32;
        let settings = *s.world.compliant().settings();
        s.world
            .compliant_mut()
            .set_settings(creep_rapier::CompliantSettings {
                rayleigh_fraction: s.params.shear_rayleigh_fraction,
                ..settings
            })?;
        Ok(s)
    }
    fn reset_energy(&mut self) {
        self.world.compliant_mut().reset_energy();
    }
    fn dissipation(&self) -> (f64, f64) {
        let e = self.world.compliant().energy();
        (e.creep, e.slip)
    }
}
