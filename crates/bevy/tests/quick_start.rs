//! The README's quick start, as written: its lines are `examples/quick_start.rs` (checked here
//! against the README), run headless with `MinimalPlugins` in place of `DefaultPlugins`.

use bevy::prelude::*;
use bevy_rapier3d::prelude::*;
use creep_bevy::prelude::*;

#[allow(dead_code)] // its `main` is the example's
#[path = "../examples/quick_start.rs"]
mod quick_start;

/// The example's code, from its first `use` to its end.
fn quick_start_code() -> &'static str {
    let example = include_str!("../examples/quick_start.rs");
    let start = example
        .find("use bevy::prelude::*;")
        .expect("the example starts its code with `use bevy::prelude::*;`");
    example[start..].trim_end()
}

#[test]
fn the_readme_shows_the_quick_start_as_compiled() {
    let readme = include_str!("../README.md");
    assert!(
        readme.contains(quick_start_code()),
        "README.md's quick start differs from examples/quick_start.rs:\n{}",
        quick_start_code()
    );
}

/// The quick start's app without a window: `MinimalPlugins` and `TransformPlugin` (both in
/// `DefaultPlugins`), its physics and its scene; or, with `rapier_solver`, the same physics
/// with the opt-out `CreepFrictionPlugin::with_rapier_solver`.
fn quick_start_app(rapier_solver: bool) -> App {
    let mut app = App::new();
    app.add_plugins((MinimalPlugins, TransformPlugin));
    if rapier_solver {
        app.add_plugins((
            CreepRapierPlugin::default(),
            CreepFrictionPlugin::default().with_rapier_solver(),
        ))
        .insert_resource(TimestepMode::Fixed {
            dt: 1.0 / 60.0,
            substeps: 1,
        });
    } else {
        app.add_plugins(quick_start::physics);
    }
    app.add_systems(Startup, quick_start::scene);
    // `App::run` does this; an app updated by hand must.
    app.finish();
    app.cleanup();
    app
}

const R: f32 = 0.1;
const G: f32 = 9.81;

/// Mechanical energy per unit mass of a uniform ball of radius `R` \[J/kg\]:
/// `(v^2 + (2/5) R^2 w^2)/2 + g y` (solid sphere, I = 2/5 m R^2).
fn energy(v: &Velocity, y: f32) -> f64 {
    let (v2, w2) = (
        f64::from(v.linear.length_squared()),
        f64::from(v.angular.length_squared()),
    );
    let r = f64::from(R);
    0.5 * (v2 + 0.4 * r * r * w2) + f64::from(G) * f64::from(y)
}

struct Run {
    /// Smallest energy over the run, over the launch energy.
    energy_kept: f64,
    /// Largest |y - R| over the run \[m\].
    height_error: f32,
    /// Speed and rim speed `|w| R` at the end [m/s].
    end: (f32, f32),
    /// Solver substeps of the context.
    substeps: usize,
    /// The plugin's warnings.
    warnings: Vec<CreepWarning>,
}

fn run(rapier_solver: bool, steps: usize) -> Run {
    let mut app = quick_start_app(rapier_solver);
    app.update();
    let ball = {
        let mut q = app
            .world_mut()
            .query_filtered::<Entity, (With<Velocity>, With<CreepMaterial>)>();
        q.single(app.world()).expect("the quick start's one ball")
    };
    let launch = energy(
        &Velocity {
            linear: Vec3::new(5.0, 0.0, 0.0),
            angular: Vec3::new(0.0, 0.0, -50.0),
        },
        R,
    );
    let (mut energy_kept, mut height_error) = (f64::INFINITY, 0.0f32);
    let mut end = (0.0, 0.0);
    // The first update above took the first step.
    for i in 0..steps {
        if i > 0 {
            app.update();
        }
        let y = app.world().get::<Transform>(ball).unwrap().translation.y;
        let v = *app.world().get::<Velocity>(ball).unwrap();
        energy_kept = energy_kept.min(energy(&v, y) / launch);
        height_error = height_error.max((y - R).abs());
        end = (v.linear.length(), v.angular.length() * R);
    }
    let mut q = app.world_mut().query::<&RapierContextSimulation>();
    let substeps = q
        .single(app.world())
        .unwrap()
        .integration_parameters
        .num_solver_iterations;
    let s = app.world().resource::<CreepFriction>();
    assert_eq!(s.steps(), steps as u64);
    Run {
        energy_kept,
        height_error,
        end,
        substeps,
        warnings: s.warnings().to_vec(),
    }
}

#[test]
fn quick_start_ball_rolls_at_5_m_s_for_10_s_keeping_energy_and_height() {
    let r = run(false, 600);
    println!(
        "quick start, 10 s at 1/60 s: energy kept {:.6}, largest |y - R| {:.3e} m, end v {:.4} \
         m/s, w R {:.4} m/s, {} substep(s)",
        r.energy_kept, r.height_error, r.end.0, r.end.1, r.substeps
    );
    assert_eq!(r.substeps, 1, "the plugin's default: one solver substep");
    assert!(r.warnings.is_empty(), "{:?}", r.warnings);
    assert!(r.energy_kept >= 0.999, "energy kept {}", r.energy_kept);
    assert!(r.height_error <= 1e-4, "|y - R| up to {} m", r.height_error);
    // Rolling, not sliding: the rim speed is the speed within the creepage of steel.
    assert!((r.end.0 - r.end.1).abs() <= 1e-3 * r.end.0, "{:?}", r.end);
}

#[test]
fn rapier_solver_is_the_named_opt_out_and_warns_once() {
    // Rapier's four substeps: the same ball floats and slides (what the default avoids), and
    // the plugin says so once, naming the setting.
    let r = run(true, 60);
    println!(
        "with_rapier_solver, 1 s at 1/60 s: energy kept {:.4}, largest |y - R| {:.3e} m, \
         end v {:.4} m/s, w R {:.4} m/s, {} substeps",
        r.energy_kept, r.height_error, r.end.0, r.end.1, r.substeps
    );
    assert_eq!(r.substeps, 4, "Rapier's default kept");
    assert!(r.energy_kept < 0.95, "energy kept {}", r.energy_kept);
    assert_eq!(r.warnings.len(), 1, "{:?}", r.warnings);
    assert!(
        matches!(r.warnings[0], CreepWarning::RotationGap { substeps: 4, .. }),
        "{:?}",
        r.warnings
    );
    let text = r.warnings[0].to_string();
    assert!(
        text.contains("num_solver_iterations") && text.contains("with_rapier_solver"),
        "{text}"
    );
}
