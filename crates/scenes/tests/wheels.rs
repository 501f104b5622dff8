//! The rigid regime's 3-D creep against closed forms: a ball spun about
//! the normal while rolling (Kalker's linear theory of spin creep), wheels.

use creep_rapier::Fidelity;
use creep_scenes::wheels_spin::{self, SpinParams};

/// The spin of a rolling rubber ball decays at Kalker's linear rate
/// `lambda = G a^4 (C33 + C23^2/C22) / (I V)` (module docs of `wheels_spin`; small spin,
/// `phi_n` ~ 3e-3): within 2 % (the non-linear law departs by about `phi_n`, the explicit
/// moment by `lambda dt / 2` ~ 0.4 %, the speed varies by under 1 %); its lateral creepage is
/// `eta = -(C23/C22) a phi` within 5 % (a slip of ~0.3 mm/s against the engine's f32
/// velocities); the Coulomb twin keeps its spin.
#[test]
fn spin_decays_at_kalkers_linear_rate() {
    let p = SpinParams::default();
    let th = p.theory().unwrap();
    assert!(th.phi_n < 0.01, "not small spin: {}", th.phi_n);
    let creep = wheels_spin::run(&p, Fidelity::Creep).unwrap();
    let (rate, speed) = creep.decay_rate(0.1);
    let expected = th.decay_rate * p.speed / speed;
    let err = rate / expected - 1.0;
    let eta = creep.eta_per_phi(0.1);
    eprintln!(
        "decay rate {rate:.5} 1/s, linear theory {expected:.5} (err {:+.3} %), mean speed {speed:.4}; eta/phi {eta:.4e} vs {:.4e}",
        100.0 * err,
        th.eta_per_phi
    );
    assert!(err.abs() < 0.02, "decay rate {rate} vs {expected}");
    assert!(
        (eta / th.eta_per_phi - 1.0).abs() < 0.05,
        "eta/phi {eta} vs {}",
        th.eta_per_phi
    );
    let coulomb = wheels_spin::run(&p, Fidelity::Coulomb).unwrap();
    let last = *coulomb.spin.last().unwrap();
    assert!((last / p.spin - 1.0).abs() < 1e-3, "Coulomb spin {last}");
}

use creep_reference::carter::Carter;
use creep_reference::steady3d::{Kind, table};
use creep_scenes::wheels::{self, WheelParams, crown_for_ratio, crowned_contact, moduli};

/// The boundary elements' pure longitudinal (or lateral) curve at `(a/b, nu)`: the force at
/// the creepage, linear
/// between the table's points (through the origin; `1` beyond the last, full slip).
fn bem_curve(kind: Kind, ab: f64, nu: f64, xi_n: f64) -> f64 {
    let k = if kind == Kind::Lateral { 1 } else { 0 };
    let mut pts: Vec<(f64, f64)> = table()
        .unwrap()
        .into_iter()
        .filter(|p| p.kind == kind && p.ab == ab && p.nu == nu)
        .map(|p| (p.creepage[k], p.load[k]))
        .collect();
    pts.insert(0, (0.0, 0.0));
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    for w in pts.windows(2) {
        if xi_n <= w[1].0 {
            let t = (xi_n - w[0].0) / (w[1].0 - w[0].0);
            return w[0].1 + t * (w[1].1 - w[0].1);
        }
    }
    pts.last().unwrap().1
}

/// Largest `|Q/(mu P) - reference|` of the driven line-contact wheel (rubber, R = 5 cm, 4 cm
/// wide, 0.1 m/s, 1/240 s) against Carter's curve `Q/(mu P) = 1 - (1 - xi/(mu a/R))^2`
/// (creep-reference `carter`) over the drive torques `shares` (of `mu m g R`); `xi` is the
/// creep run's creepage less its Coulomb twin's.
fn line_wheel_error(shares: &[f64]) -> f64 {
    let p = WheelParams::default();
    let (_, e_star) = moduli(&p).unwrap();
    let mu = p.material.friction();
    let mut worst = 0.0f64;
    for &share in shares {
        let row = wheels::driven(&p, share).unwrap();
        let s = row.force_ratio(mu);
        let carter = Carter::from_load(row.creep.p / p.width, p.radius, e_star, mu).unwrap();
        let s_ref = carter.force_ratio(row.creepage()).unwrap();
        assert_eq!(s_ref, wheels::reference_force_ratio(&p, &row).unwrap());
        eprintln!(
            "line: share {share}: Q/(mu P) {s:.4}, xi {:.5e} (creep {:.5e}, coulomb {:.5e}), Carter {s_ref:.4}, err {:+.4}, points {:.2}",
            row.creepage(),
            row.creep.xi,
            row.coulomb.xi,
            s - s_ref,
            row.creep.points
        );
        worst = worst.max((s - s_ref).abs());
    }
    worst
}

/// The same for the crowned wheel (crown radius for a/b = 0.5, nu = 0.5: a node of the
/// boundary-element table) against Kalker's exact theory (creep-reference's boundary elements,
/// `steady3d::table`).
fn crowned_wheel_error(shares: &[f64]) -> f64 {
    let mut p = WheelParams::default();
    p.crown = Some(crown_for_ratio(p.radius, 0.5).unwrap());
    let (g, _) = moduli(&p).unwrap();
    let mu = p.material.friction();
    let mut worst = 0.0f64;
    for &share in shares {
        let row = wheels::driven(&p, share).unwrap();
        let s = row.force_ratio(mu);
        let (a, b) = crowned_contact(&p, row.creep.p).unwrap();
        let xi_n = row.creepage() * g * a * b / (mu * row.creep.p);
        let s_ref = bem_curve(Kind::Longitudinal, 0.5, 0.5, xi_n);
        assert!((s_ref - wheels::reference_force_ratio(&p, &row).unwrap()).abs() < 1e-12);
        eprintln!(
            "crowned: share {share}: Q/(mu P) {s:.4}, xi_n {xi_n:.4} (a/b {:.4}; creep {:.4e}, coulomb {:.4e}), BEM {s_ref:.4}, err {:+.4}",
            a / b,
            row.creep.xi,
            row.coulomb.xi,
            s - s_ref
        );
        worst = worst.max((s - s_ref).abs());
    }
    worst
}

/// A driven line-contact wheel follows Carter within 2 % of `mu P` up to 0.7 `mu P`.
#[test]
fn driven_wheel_follows_carter() {
    let worst = line_wheel_error(&[0.1, 0.3, 0.5, 0.7]);
    assert!(worst < 0.02, "worst |Q/(mu P) - Carter| {worst}");
}

/// A driven crowned wheel follows Kalker's exact theory within 2 % of `mu P` up to 0.7 `mu P`.
#[test]
fn driven_crowned_wheel_follows_kalker() {
    let worst = crowned_wheel_error(&[0.1, 0.3, 0.5, 0.7]);
    assert!(worst < 0.02, "worst |Q/(mu P) - BEM| {worst}");
}

/// The range, up to 0.9 `mu P`: both wheels within 2 % of `mu P` of their closed forms.
/// Before the wheel's manifold became one patch contact (creep-rapier's wheel module) Rapier's
/// three friction points let the Coulomb twin itself slip from 0.8 `mu P` (creepage 9e-3 at 0.8,
/// 4e-2 at 0.9) and this missed by line -10.7 % / -9.6 %, crowned -3.6 % / -8.2 %; with the
/// patch contact the twin sticks (creepage -2.8e-3, the rolling-radius offset, at every load).
#[test]
fn driven_wheels_near_the_friction_limit() {
    let line = line_wheel_error(&[0.8, 0.9]);
    let crowned = crowned_wheel_error(&[0.8, 0.9]);
    assert!(
        line < 0.02 && crowned < 0.02,
        "line {line}, crowned {crowned}"
    );
}

/// Driven wheels (line contact and crowned, 0.5 `mu P`) rolling at 1 and 5 m/s (1/240 s: 4.8
/// and 24 degrees of turn a step) stay on the floor: on every measured step the normal force
/// is within 10 % of its mean, in the creep run and its Coulomb twin, and the traction against
/// creepage still meets Carter / the boundary elements within 2 % of `mu P` (measured: normal
/// force constant to 1e-4; creepage within 0.05 % of the 0.1 m/s run's). Before the wheel's
/// patch contact took its geometry from the floor's face (creep-rapier's wheel path,
/// `ExactPatch`), Rapier's narrow phase lost the rolling cylinder on the 1000 m floor from 0.5
/// m/s on: steps without contact and impacts of 2.3-27 times the weight, and at 5 m/s a line
/// contact's creepage read 0.246 instead of 8.7e-3.
#[test]
fn driven_wheels_stay_in_contact_at_speed() {
    let line = WheelParams::default();
    let crowned = WheelParams {
        crown: Some(crown_for_ratio(line.radius, 0.5).unwrap()),
        ..line
    };
    let mu = line.material.friction();
    for speed in [1.0, 5.0] {
        for base in [line, crowned] {
            let p = WheelParams { speed, ..base };
            let row = wheels::driven(&p, 0.5).unwrap();
            let s = row.force_ratio(mu);
            let s_ref = wheels::reference_force_ratio(&p, &row).unwrap();
            eprintln!(
                "{speed} m/s, crowned {}: Q/(mu P) {s:.4}, reference {s_ref:.4}, creepage {:.4e}, P per step {:.4}..{:.4} (twin {:.4}..{:.4}) of its mean",
                p.crown.is_some(),
                row.creepage(),
                row.creep.p_min / row.creep.p,
                row.creep.p_max / row.creep.p,
                row.coulomb.p_min / row.coulomb.p,
                row.coulomb.p_max / row.coulomb.p
            );
            for m in [&row.creep, &row.coulomb] {
                assert!(
                    m.p_min > 0.9 * m.p && m.p_max < 1.1 * m.p,
                    "{speed} m/s: normal force {}..{} of mean {}",
                    m.p_min,
                    m.p_max,
                    m.p
                );
            }
            assert!((s - s_ref).abs() < 0.02, "{speed} m/s: {s} vs {s_ref}");
        }
    }
}

/// A free crowned wheel pushed sideways (held upright, its heading held): the lateral force
/// against the lateral creepage (`tan` of the slip angle) has the linear slope of Kalker's
/// theory, `G a b C22` (Kalker 1990, Table E.3, via creep-law's `kalker3d`), within 2 %; below
/// the Coulomb limit it follows the boundary elements' pure lateral curve within 2 % of `mu P`.
/// Before the wheel's manifold became one patch contact (creep-rapier's wheel module) the
/// three-point contact slid well beyond the law's target (slip angle 0.075 rad at 0.3 `mu P`)
/// and the slope was off by +5.9 % / -2.4 %.
#[test]
fn slip_angle_lateral_force() {
    let mut p = WheelParams::default();
    p.crown = Some(crown_for_ratio(p.radius, 0.5).unwrap());
    let (g, _) = moduli(&p).unwrap();
    let mu = p.material.friction();
    let c22 = creep_law::kalker3d::coefficients(0.5, 0.5).unwrap().c22;
    let (mut worst_slope, mut worst_curve) = (0.0f64, 0.0f64);
    for share in [0.01, 0.02] {
        let m = wheels::lateral(&p, share).unwrap();
        let (a, b) = crowned_contact(&p, m.p).unwrap();
        let slope = m.qy / m.eta;
        let want = g * a * b * c22;
        eprintln!(
            "push {share}: slip angle {:.4e} rad, Fy/(mu P) {:.4}, slope {slope:.4e} vs G a b C22 {want:.4e} (err {:+.3} %), eta_n {:.4}",
            m.eta.atan(),
            m.qy / (mu * m.p),
            100.0 * (slope / want - 1.0),
            m.eta * g * a * b / (mu * m.p)
        );
        worst_slope = worst_slope.max((slope / want - 1.0).abs());
    }
    for share in [0.3, 0.6, 0.9] {
        let m = wheels::lateral(&p, share).unwrap();
        let (a, b) = crowned_contact(&p, m.p).unwrap();
        let s = m.qy.abs() / (mu * m.p);
        let eta_n = m.eta.abs() * g * a * b / (mu * m.p);
        let s_ref = bem_curve(Kind::Lateral, 0.5, 0.5, eta_n);
        eprintln!(
            "push {share}: slip angle {:.4e} rad, |Fy|/(mu P) {s:.4}, eta_n {eta_n:.4}, BEM {s_ref:.4}, err {:+.4}",
            m.eta.atan(),
            s - s_ref
        );
        worst_curve = worst_curve.max((s - s_ref).abs());
    }
    assert!(worst_slope < 0.02, "slope error {worst_slope}");
    assert!(worst_curve < 0.02, "lateral curve error {worst_curve}");
}

/// The same wheel pushed beyond `mu P` (by 1.05, 1.2 and 1.5 `mu m g`) slides sideways with
/// the floor's force at `mu P` within 2 %, in contact on every step: no measured step's normal
/// force leaves 0.9-1.1 of the mean (measured: |F|/(mu P) 1.0000 at all three pushes, normal
/// force within 1e-4 of its mean). Before the wheel's patch contact took its normal and
/// separation from the floor's face (creep-rapier's wheel path, `ExactPatch`), Rapier's
/// narrow phase lost the sliding cylinder on the 1000 m floor now and then (a wrong normal and
/// points separated by up to 1.4 mm while it overlapped; steps with no contact, then impulses
/// of 2-7 `m g dt`): 0.82, 0.999 and 0.9994 at 1.2, 1.05, 1.5 in the round that wrote this test,
/// 0.8901, 0.9997 and 0.9999 on the main branch it was fixed on (the impacts fall on different
/// steps as the code around them changes).
#[test]
fn slip_angle_saturation() {
    let mut p = WheelParams::default();
    p.crown = Some(crown_for_ratio(p.radius, 0.5).unwrap());
    let mu = p.material.friction();
    for push in [1.05, 1.2, 1.5] {
        let m = wheels::lateral(&p, push).unwrap();
        let f = m.qx.hypot(m.qy) / (mu * m.p);
        eprintln!(
            "push {push}: slip angle {:.4} rad, |F|/(mu P) {f:.4}, P per step {:.4}..{:.4} of its mean",
            m.eta.atan(),
            m.p_min / m.p,
            m.p_max / m.p
        );
        assert!((f - 1.0).abs() < 0.02, "push {push}: saturation {f}");
        assert!(
            m.p_min > 0.9 * m.p && m.p_max < 1.1 * m.p,
            "push {push}: normal force {}..{} of mean {}",
            m.p_min,
            m.p_max,
            m.p
        );
    }
}

/// Lateral creep of a ball (the law the wheels share, `creep_law::rigid`): a rolling
/// rubber ball (nu = 0.5) pushed sideways at its contact's height settles at the lateral
/// creepage of Kalker's linear theory, `Fy = G a^2 C22 eta` (Kalker 1990, Table E.3: C22 = 3.98
/// at a/b = 1, nu = 0.5; C11 = 5.20, so an isotropic law would miss by 23 %), within 2 % at
/// small force; pushed beyond `mu P` it slides sideways with the floor's force within 2 % of
/// `mu P`.
#[test]
fn ball_lateral_creep_follows_c22() {
    let p = SpinParams {
        material: wheels::wheel_rubber(),
        spin: 0.0,
        speed: 0.5,
        ..SpinParams::default()
    };
    let mu = p.material.friction();
    let pair = creep_law::PairMaterial::new(
        &p.material,
        &p.material,
        creep_law::Surface::Sphere(p.radius),
        creep_law::Surface::Plane,
    )
    .unwrap();
    let c22 = creep_law::kalker3d::coefficients(1.0, 0.5).unwrap().c22;
    let mut worst = 0.0f64;
    for share in [0.01, 0.02] {
        let m = wheels_spin::lateral_push(&p, share).unwrap();
        let (pn, fy, eta) = (m.p, m.qy, m.eta);
        let a = creep_law::hertz::contact_radius(&pair, pn);
        let slope = fy / eta;
        let want = pair.g * a * a * c22;
        eprintln!(
            "ball push {share}: Fy/(mu P) {:.4}, eta {eta:.4e}, slope {slope:.4e} vs G a^2 C22 {want:.4e} (err {:+.3} %), eta_n {:.4}",
            fy / (mu * pn),
            100.0 * (slope / want - 1.0),
            eta * pair.g * a * a / (mu * pn)
        );
        worst = worst.max((slope / want - 1.0).abs());
    }
    let m = wheels_spin::lateral_push(&p, 1.2).unwrap();
    let f = m.qx.hypot(m.qy) / (mu * m.p);
    eprintln!(
        "ball push 1.2: |F|/(mu P) {f:.4}, Fx/(mu P) {:.4}, Fy/(mu P) {:.4}, eta {:.4}",
        m.qx / (mu * m.p),
        m.qy / (mu * m.p),
        m.eta
    );
    assert!(worst < 0.02, "lateral slope error {worst}");
    assert!((f - 1.0).abs() < 0.02, "saturation {f}");
}

/// The documented recipe (a wheel on a revolute joint to a chassis, `CreepWorld::new`'s
/// defaults and nothing else; `driven_on_joint`): the driven line-contact wheel follows Carter
/// within 2 % of `mu P` from 0.2 to 0.9 `mu P`, at 1/240 s and at the game step 1/60 s, and
/// does not wobble sideways (the joint holds its axle).
#[test]
fn wheel_from_the_recipe_follows_carter() {
    for dt in [1.0 / 240.0, 1.0 / 60.0] {
        let p = WheelParams {
            dt,
            duration: if dt < 0.01 { 1.0 } else { 4.0 },
            ..WheelParams::default()
        };
        let (_, e_star) = moduli(&p).unwrap();
        let mu = p.material.friction();
        let mut worst = 0.0f64;
        for share in [0.2, 0.5, 0.7, 0.9] {
            let row = wheels::driven_on_joint(&p, share).unwrap();
            let s = row.force_ratio(mu);
            let carter = Carter::from_load(row.creep.p / p.width, p.radius, e_star, mu).unwrap();
            let s_ref = carter.force_ratio(row.creepage()).unwrap();
            eprintln!(
                "recipe dt {dt:.5}: share {share}: Q/(mu P) {s:.4}, xi {:.5e} (creep {:.5e}, coulomb {:.5e}), Carter {s_ref:.4}, err {:+.4}, vz {:.2e} / {:.2e}",
                row.creepage(),
                row.creep.xi,
                row.coulomb.xi,
                s - s_ref,
                row.creep.lateral_speed,
                row.coulomb.lateral_speed,
            );
            assert!(
                row.creep.lateral_speed < 1e-4 && row.coulomb.lateral_speed < 1e-4,
                "sideways wobble {row:?}"
            );
            worst = worst.max((s - s_ref).abs());
        }
        assert!(worst < 0.02, "dt {dt}: worst |Q/(mu P) - Carter| {worst}");
    }
}
