//! A driven rigid wheel (a Rapier cylinder) on a granular bed: sinkage, drawbar pull and
//! driving torque against time at a prescribed slip ratio.
//!
//! The wheel's spin `w` and forward speed `v = w R (1 - s)` (`s` the slip ratio of a driven
//! wheel, Wong 2008, *Theory of Ground Vehicles*, §2.2) are prescribed each game step; its
//! vertical motion is free (its weight against the bed), so the sinkage is the scene's
//! answer. Drawbar pull: the grains' force on the wheel along the travel direction (+x);
//! torque: the driving torque that keeps the spin, i.e. minus the grains' torque about the
//! axle along the spin.

use creep_dem::TangentialLaw;
use creep_law::{Material, Vec3};
use rapier3d::glamx::{Quat, Vec3 as FVec3};
use rapier3d::prelude::*;

use crate::BedError;
use crate::scene::{BedSpec, highest_under, surface_height};

/// The wheel scene's settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelOnSand {
    /// The bed (its `counts[0]` along the travel).
    pub bed: BedSpec,
    /// Wheel radius in grain radii [-].
    pub radius_factor: f64,
    /// Wheel width in grain radii [-].
    pub width_factor: f64,
    /// Wheel density \[kg/m^3\].
    pub density: f64,
    /// Slip ratio `s = 1 - v/(w R)` [-], in `[0, 1)`... (`1`: spinning in place).
    pub slip: f64,
    /// Spin \[rad/s\].
    pub spin: f64,
    /// DEM steps per game step.
    pub substeps: usize,
    /// Steps to settle the bed (at most).
    pub settle_steps: usize,
    /// Game steps the wheel sinks in at rest before driving.
    pub sink_steps: usize,
    /// Game steps driven.
    pub drive_steps: usize,
}

impl WheelOnSand {
    /// A bed of about `grains` grains (4 layers, 6 across) and the default wheel.
    pub fn with_grains(grains: usize, slip: f64) -> Self {
        let nx = (grains / 24).max(8);
        Self {
            bed: BedSpec {
                counts: [nx, 4, 6],
                ..BedSpec::default()
            },
            radius_factor: 8.0,
            width_factor: 6.0,
            density: 1000.0,
            slip,
            spin: 2.0,
            substeps: 20,
            settle_steps: 40_000,
            sink_steps: 200,
            drive_steps: 400,
        }
    }
}

/// One row of the wheel's output.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct WheelRow {
    /// Time since the drive started \[s\].
    pub t: f64,
    /// Slip ratio [-].
    pub slip: f64,
    /// Sinkage: bed surface minus the wheel's lowest point \[m\].
    pub sinkage: f64,
    /// Drawbar pull: the grains' force on the wheel along +x \[N\].
    pub drawbar_pull: f64,
    /// Driving torque \[N m\].
    pub torque: f64,
}

/// Runs the wheel scene; `row` is called after every driven game step.
pub fn wheel_on_sand<T: TangentialLaw>(
    s: &WheelOnSand,
    mut row: impl FnMut(WheelRow),
) -> Result<usize, BedError> {
    if !(s.slip.is_finite() && (0.0..=1.0).contains(&s.slip)) {
        return Err(BedError::Parameter {
            name: "slip",
            value: s.slip,
            why: "must be in [0, 1]",
        });
    }
    let b = s.bed;
    let wheel_mat =
        Material::new(79.3e6, 0.29, 0.5, s.density).map_err(creep_dem::DemError::from)?;
    let mut dem = b.engine::<T>(wheel_mat)?;
    b.settle(&mut dem, s.settle_steps)?;
    let top = surface_height(&dem);
    let grains = dem.len();
    let dt_rigid = dem.config().dt * s.substeps as f64;
    let (_, lz) = b.footprint();
    let rw = s.radius_factor * b.radius;
    let half_w = 0.5 * s.width_factor * b.radius;

    let start = highest_under(
        &dem,
        Vec3::new(1.5 * rw, 0.0, 0.5 * lz),
        Vec3::new(rw + b.radius, 0.0, half_w + b.radius),
    );
    // Rapier's cylinder is about y: turn it about x so that its axis is z.
    let (mut world, wheel, mut bed) = b.coupled_world(
        dem,
        dt_rigid,
        FVec3::new(
            (1.5 * rw) as f32,
            (start + rw + 0.02 * b.radius) as f32,
            (0.5 * lz) as f32,
        ),
        ColliderBuilder::cylinder(half_w as f32, rw as f32)
            .rotation(Quat::from_rotation_x(std::f32::consts::FRAC_PI_2).to_scaled_axis())
            .density(s.density as f32)
            .build(),
    )?;
    let set = |world: &mut PhysicsWorld, v: f64, w: f64| {
        let rb = &mut world.bodies[wheel];
        let vy = rb.linvel().y;
        rb.set_linvel(FVec3::new(v as f32, vy, 0.0), true);
        rb.set_angvel(FVec3::new(0.0, 0.0, -w as f32), true);
    };
    for _ in 0..s.sink_steps {
        set(&mut world, 0.0, 0.0);
        bed.step(dt_rigid, &mut world.bodies)?;
        world.step();
    }
    let v = s.spin * rw * (1.0 - s.slip);
    for k in 0..s.drive_steps {
        set(&mut world, v, s.spin);
        bed.step(dt_rigid, &mut world.bodies)?;
        let e = bed.boundaries().exchange(0).unwrap_or_default();
        world.step();
        let y = f64::from(world.bodies[wheel].translation().y);
        row(WheelRow {
            t: (k + 1) as f64 * dt_rigid,
            slip: s.slip,
            sinkage: top - (y - rw),
            drawbar_pull: e.mean_force.x,
            torque: e.mean_torque.z,
        });
    }
    Ok(grains)
}
