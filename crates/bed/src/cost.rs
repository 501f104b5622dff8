//! The coupling's cost against the bed alone, measured interleaved (`creep run wheel-on-sand
//! --cost`).

use std::time::Instant;

use creep_dem::Cheap;
use creep_law::Material;
use rapier3d::glamx::{Quat, Vec3 as FVec3};
use rapier3d::prelude::*;

use crate::scene::{BedSpec, surface_height};
use crate::{Bed, BedConfig, BedError};

fn median(v: &mut [f64]) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// What [`coupling_cost`] measured.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CostReport {
    /// Grains.
    pub grains: usize,
    /// Rounds (each: one block of the bed alone, one block coupled).
    pub rounds: usize,
    /// DEM steps per block.
    pub steps: usize,
    /// Median seconds per DEM step, the bed alone.
    pub alone: f64,
    /// Median seconds per DEM step, coupled (sub-steps with the boundary, Rapier's step).
    pub coupled: f64,
    /// Grain-wheel contacts at the end.
    pub contacts: usize,
    /// Candidate-list refreshes.
    pub refreshes: usize,
}

impl CostReport {
    /// The CSV header of [`CostReport::csv_row`] (seconds per DEM step; `ratio` coupled / alone).
    pub const CSV_HEADER: &'static str = "grains,rounds,steps_per_block,bed_alone_s_per_step,coupled_s_per_step,ratio,wheel_contacts,refreshes";

    /// The report as one CSV row under [`CostReport::CSV_HEADER`].
    pub fn csv_row(&self) -> String {
        format!(
            "{},{},{},{:.4e},{:.4e},{:.4},{},{}",
            self.grains,
            self.rounds,
            self.steps,
            self.alone,
            self.coupled,
            self.coupled / self.alone,
            self.contacts,
            self.refreshes
        )
    }
}

/// Settles a bed of `counts` grains (gravity 100 m/s^2 so that it settles in a few thousand
/// steps), then steps two copies in alternating blocks of 1,000 DEM steps, `rounds` times: the
/// engine alone (`Dem::step`) and the engine with a rigid cylinder (a wheel in Rapier, driven
/// at 2 rad/s and 20 % slip, free vertically) through [`Bed::step`] and Rapier's step.
pub fn coupling_cost(counts: [usize; 3], rounds: usize) -> Result<CostReport, BedError> {
    if rounds == 0 {
        return Err(BedError::Parameter {
            name: "rounds",
            value: 0.0,
            why: "at least one round",
        });
    }
    let spec = BedSpec {
        counts,
        gravity: 100.0,
        ..BedSpec::default()
    };
    let wheel_mat = Material::new(79.3e6, 0.29, 0.5, 1000.0).map_err(creep_dem::DemError::from)?;
    let mut dem = spec.engine::<Cheap>(wheel_mat)?;
    spec.settle(&mut dem, 30_000)?;
    let top = surface_height(&dem);
    let (lx, lz) = spec.footprint();
    let r = spec.radius;
    let k = 20;
    let dt_rigid = dem.config().dt * k as f64;

    let mut world = PhysicsWorld {
        gravity: FVec3::new(0.0, -spec.gravity as f32, 0.0),
        ..Default::default()
    };
    world.integration_parameters.dt = dt_rigid as f32;
    let rw = 8.0 * r;
    let wheel = world.bodies.insert(
        RigidBodyBuilder::dynamic()
            .translation(FVec3::new(
                (0.5 * lx) as f32,
                (top + rw + 0.02 * r) as f32,
                (0.5 * lz) as f32,
            ))
            .can_sleep(false)
            .build(),
    );
    let ch = world.colliders.insert_with_parent(
        ColliderBuilder::cylinder((3.0 * r) as f32, rw as f32)
            .rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2).to_scaled_axis())
            .density(1000.0)
            .build(),
        wheel,
        &mut world.bodies,
    );
    let mut alone = dem.clone();
    let mut bed = Bed::new(dem, BedConfig { skin: 0.2 * r })?;
    bed.add_boundary(ch, 1, &world.bodies, &world.colliders)?;
    // Let the wheel land before timing.
    for _ in 0..100 {
        bed.step(dt_rigid, &mut world.bodies)?;
        world.step();
        for _ in 0..k {
            alone.step()?;
        }
    }
    let games = 50;
    let (mut ta, mut tb) = (Vec::new(), Vec::new());
    for _ in 0..rounds {
        let t = Instant::now();
        for _ in 0..games * k {
            alone.step()?;
        }
        ta.push(t.elapsed().as_secs_f64() / (games * k) as f64);
        let t = Instant::now();
        for _ in 0..games {
            // Driven at 2 rad/s and 20 % slip (the candidate lists refresh as it moves).
            let rb = &mut world.bodies[wheel];
            let vy = rb.linvel().y;
            rb.set_linvel(FVec3::new((2.0 * rw * 0.8) as f32, vy, 0.0), true);
            rb.set_angvel(FVec3::new(0.0, 0.0, -2.0), true);
            bed.step(dt_rigid, &mut world.bodies)?;
            world.step();
        }
        tb.push(t.elapsed().as_secs_f64() / (games * k) as f64);
    }
    let ex = bed.boundaries().exchange(0).unwrap_or_default();
    Ok(CostReport {
        grains: bed.dem().len(),
        rounds,
        steps: games * k,
        alone: median(&mut ta),
        coupled: median(&mut tb),
        contacts: ex.contacts,
        refreshes: bed.boundaries().refreshes(),
    })
}
