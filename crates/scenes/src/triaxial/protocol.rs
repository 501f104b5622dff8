//! The protocols: isotropic compaction and drained shear at constant lateral stress.

use super::TriaxialRow;
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
    let p0 = specimen.params.confining_pressure;
    let rate = specimen.params.strain_rate();
    let dt = specimen.params.time_step();
    let mut settled_for = 0;
    let mut last = Stress::default();
    for i in 0..max_steps {
        let s = specimen.stress();
        let mut v = [0.0; 6];
        // Fast while nothing touches (a gas: up to 20 eps_dot), then at most 5 eps_dot.
        let cap = if s.walls.iter().all(|&w| w < 0.05 * p0) {
            20.0
        } else {
            5.0
        };
        for (k, w) in specimen.walls.iter().enumerate() {
            v[k] = s.servo(k, p0, dt, cap * rate * s.dims[w.axis] / 2.0);
        }
        specimen.set_wall_speeds(v);
        specimen.step()?;
        observe(specimen);
        last = specimen.stress();
        let wall_err = last
            .each
            .iter()
            .map(|&w| (w / p0 - 1.0).abs())
            .fold(0.0, f64::max);
        let p_love = (last.love[0][0] + last.love[1][1] + last.love[2][2]) / 3.0;
        let p_walls = last.walls.iter().sum::<f64>() / 3.0;
        let agree = (p_love / p_walls - 1.0).abs();
        if wall_err < 0.01 && agree < 0.01 {
            settled_for += 1;
        } else {
            settled_for = 0;
        }
        if i % 200 == 0 {
            let est = (p_walls / p0).clamp(0.0, 1.0) * 0.9 + 0.1 * settled_for as f64 / 200.0;
            progress(est);
        }
        if settled_for >= 200 {
            specimen.set_wall_speeds([0.0; 6]);
            progress(1.0);
            let (n, ..) = specimen.contact_shares();
            let dims = last.dims;
            return Ok(CompactionSummary {
                steps: i + 1,
                solid_fraction: specimen.solids() / (dims[0] * dims[1] * dims[2]),
                p_walls,
                p_contacts: p_love,
                max_wall_error: wall_err,
                coordination: 2.0 * n as f64 / specimen.len() as f64,
            });
        }
    }
    let p_walls = last.walls.iter().sum::<f64>() / 3.0;
    Err(SceneError::Parameter(format!(
        "triaxial: the isotropic compaction did not settle in {max_steps} steps (mean wall stress {p_walls:.4e} Pa against p0 = {p0:.4e} Pa)"
    )))
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
    let mut s = specimen.clone_fresh(creep)?;
    let params = s.params;
    let p0 = params.confining_pressure;
    let rate = params.strain_rate();
    let dt = params.time_step();
    // Friction on the balls (the walls stay frictionless by their Min combine rule).
    for &(_, c) in &s.balls {
        if let Some(co) = s.world.physics.colliders.get_mut(c) {
            co.set_friction(params.mu as f32);
        }
    }
    // One step at rest, so that the fresh regime has found its contacts.
    s.set_wall_speeds([0.0; 6]);
    s.step()?;
    let s0 = s.stress();
    let h0 = s0.dims[1];
    let v0 = s0.dims[0] * s0.dims[1] * s0.dims[2];
    let solids = s.solids();
    let total_steps = (params.axial_strain / (rate * dt)).ceil() as usize;
    let record_every = (total_steps as f64
        / (params.axial_strain * 100.0 * params.rows_per_percent as f64))
        .max(1.0) as usize;
    let mut rows = Vec::new();
    let mut mismatch = 0f64;
    s.world.compliant.reset_energy();
    for i in 0..=total_steps {
        let st = s.stress();
        let eps_a = (h0 - st.dims[1]) / h0;
        let last = i == total_steps || eps_a >= params.axial_strain;
        if i % record_every == 0 || last {
            let row = row(&s, &st, eps_a, v0, solids);
            if eps_a > 0.01 {
                let dp = (row.p_contacts / row.p - 1.0).abs();
                let dq = ((row.q_contacts - row.q) / row.p).abs();
                mismatch = mismatch.max(dp).max(dq);
            }
            rows.push(row);
            progress(i as f64 / total_steps as f64);
            observe(&s, rows.last());
        } else {
            observe(&s, None);
        }
        if last {
            break;
        }
        let mut v = [0.0; 6];
        for (k, w) in s.walls.iter().enumerate() {
            v[k] = if w.axis == 1 {
                -0.5 * rate * h0
            } else {
                st.servo(k, p0, dt, 5.0 * rate * st.dims[w.axis] / 2.0)
            };
        }
        s.set_wall_speeds(v);
        s.step()?;
    }
    let e = s.world.compliant.energy();
    Ok(ShearRun {
        creep,
        steps: s.steps - specimen.steps,
        rows,
        max_stress_mismatch: mismatch,
        creep_dissipation: e.creep,
        slip_dissipation: e.slip,
    })
}
