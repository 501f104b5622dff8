//! Wheels and spin in the rigid regime through the public API (issue #17, part 3).

use creep_rapier::{CreepMaterial, CreepSettings, CreepWorld, Fidelity, PluginError};
use rapier3d::prelude::*;

/// A driven rubber wheel (a cylinder turned to roll on its round face) on a box: its contact
/// takes the creep path (not `coulomb_unsupported` as before wheels), with and without a crown;
/// a bad crown radius is a typed error.
#[test]
fn a_cylinder_on_a_box_is_a_wheel() {
    for crown in [None, Some(0.2)] {
        let mut world = CreepWorld::new(1.0 / 240.0, CreepSettings::default()).unwrap();
        world.physics.integration_parameters.num_solver_iterations = 1;
        let rubber =
            CreepMaterial::new(creep_law::Material::rubber()).with_fidelity(Fidelity::Creep);
        world.insert(
            RigidBodyBuilder::fixed().translation(Vector::new(0.0, -0.1, 0.0)),
            ColliderBuilder::cuboid(10.0, 0.1, 10.0).friction(0.9),
            Some(rubber),
        );
        let (body, wheel) = world.insert(
            RigidBodyBuilder::dynamic()
                .translation(Vector::new(0.0, 0.05, 0.0))
                .rotation(Vector::new(std::f32::consts::FRAC_PI_2, 0.0, 0.0))
                .linvel(Vector::new(0.1, 0.0, 0.0))
                .angvel(Vector::new(0.0, 0.0, -2.0))
                .enabled_rotations(true, false, true)
                .can_sleep(false),
            ColliderBuilder::cylinder(0.02, 0.05).friction(0.9),
            Some(rubber),
        );
        assert!(matches!(
            world.hooks.set_wheel_crown(wheel, Some(-1.0)),
            Err(PluginError::Setting { .. })
        ));
        world.hooks.set_wheel_crown(wheel, crown).unwrap();
        world.physics.bodies[body].add_torque(Vector::new(0.0, 0.0, -0.005), true);
        let mut creep_steps = 0;
        for _ in 0..60 {
            let counts = world.step().unwrap();
            assert_eq!(counts.coulomb_unsupported, 0, "{counts:?}");
            creep_steps += usize::from(counts.creep > 0);
        }
        assert!(
            creep_steps > 50,
            "crown {crown:?}: creep on {creep_steps} steps"
        );
        let v = world.physics.bodies[body].linvel();
        assert!(v.is_finite() && v.x > 0.0, "{v:?}");
    }
}
