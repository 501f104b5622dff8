//! The creep-model tiers through `CreepState::update` with a `CreepLaw` per model: Kuhn's tier
//! is `CreepLaw::kuhn` whether the contact radius is given or Hertz's, the
//! limits of the fitted tiers (pure sliding = Cattaneo-Mindlin, steady rolling = the fitted
//! steady law), and the state's contract (`Copy + Default + PartialEq`, rotation).

use creep_law::{
    CreepInput, CreepLaw, CreepModel, CreepState, Material, MindlinState, PairMaterial, SteadyLaw,
    Surface, Vec2, hertz,
};

fn pair() -> PairMaterial {
    let m = Material::steel();
    PairMaterial::new(&m, &m, Surface::Sphere(0.01), Surface::Plane).unwrap()
}

fn assert_state_traits<T: Copy + Default + PartialEq>() {}

#[test]
fn kuhn_tier_is_kuhns_update_bit_for_bit() {
    assert_state_traits::<CreepState>();
    let pair = pair();
    let (mut a, mut b) = (CreepState::new(), CreepState::new());
    for i in 0..300 {
        let t = i as f64;
        let du = Vec2::new((0.1 * t).sin(), (0.07 * t).cos()) * 3e-7;
        let dr = Vec2::new(2e-6 * (0.05 * t).cos().abs(), 1e-6);
        let p = 100.0 + 40.0 * (0.03 * t).sin();
        let x = a.update(&CreepLaw::kuhn(pair), CreepInput::new(p, du, dr));
        let radius = hertz::contact_radius(&pair, p);
        let y = b.update(
            &CreepLaw::new(pair, CreepModel::default()),
            CreepInput::new(p, du, dr).with_radius(radius),
        );
        assert_eq!(x, y);
        assert_eq!(a, b);
    }
}

#[test]
fn fitted_tiers_without_rolling_are_cattaneo_mindlin() {
    let pair = pair();
    for model in [CreepModel::Fitted, CreepModel::FittedTransient] {
        let mut c = CreepState::new();
        let mut m = MindlinState::new();
        for i in 0..100 {
            let du = Vec2::new((i as f64).sin(), (0.3 * i as f64).cos()) * 2e-7;
            let p = 100.0 + 50.0 * (0.1 * i as f64).sin();
            let a = c.update(
                &CreepLaw::new(pair, model),
                CreepInput::new(p, du, Vec2::ZERO),
            );
            let b = m.update(&pair, p, du);
            assert_eq!(a.q, b.q);
            assert_eq!(a.creep_dissipation, 0.0);
            assert_eq!(c.mindlin(), &m);
        }
    }
}

#[test]
fn fitted_tiers_roll_to_the_fitted_steady_force() {
    // Roll at held creepage xi(s) of the fitted law: the force converges to s mu P for both
    // fitted tiers (the transient one's lag has filled after many contact radii).
    let pair = pair();
    let p = 100.0;
    let a = hertz::contact_radius(&pair, p);
    let mu_p = pair.mu * p;
    let law = SteadyLaw::new(CreepModel::Fitted, pair.nu);
    for model in [CreepModel::Fitted, CreepModel::FittedTransient] {
        for s_target in [0.2, 0.6, 0.9] {
            let xi = law.creepage_for_force(s_target * mu_p, mu_p, pair.g, a);
            let mut st = CreepState::new();
            st.update(
                &CreepLaw::new(pair, model),
                CreepInput::new(p, Vec2::ZERO, Vec2::ZERO),
            );
            let dr = a / 50.0;
            for _ in 0..3000 {
                st.update(
                    &CreepLaw::new(pair, model),
                    CreepInput::new(p, Vec2::new(xi * dr, 0.0), Vec2::new(dr, 0.0)),
                );
            }
            let s = st.force().x / mu_p;
            assert!((s - s_target).abs() < 1e-6, "{model} {s_target}: {s}");
            if model == CreepModel::FittedTransient {
                let lag = st.lag();
                assert!((lag[1].x / xi - 1.0).abs() < 1e-6, "{:?}", lag);
            }
        }
    }
}

#[test]
fn transient_tier_starts_below_the_steady_rate_at_held_force() {
    let pair = pair();
    let p = 100.0;
    let a = hertz::contact_radius(&pair, p);
    let mu_p = pair.mu * p;
    let law = SteadyLaw::new(CreepModel::Fitted, pair.nu);
    let mut st = CreepState::new();
    st.update(
        &CreepLaw::new(pair, CreepModel::FittedTransient),
        CreepInput::new(p, Vec2::ZERO, Vec2::ZERO),
    );
    // Load to 0.6 mu P by a shift, no rolling.
    let ds = 3.0 * mu_p / (16.0 * pair.g_star * a);
    let d = ds * (1.0 - 0.4f64.powf(2.0 / 3.0));
    st.update(
        &CreepLaw::new(pair, CreepModel::FittedTransient),
        CreepInput::new(p, Vec2::new(d, 0.0), Vec2::ZERO),
    );
    let f = law.creepage_for_force(st.force().length(), mu_p, pair.g, a);
    let dr = a / 100.0;
    let mut prev = 0.0;
    for i in 0..1000 {
        let mut probe = st;
        let c = probe
            .update(
                &CreepLaw::new(pair, CreepModel::FittedTransient),
                CreepInput::new(p, Vec2::ZERO, Vec2::new(dr, 0.0)),
            )
            .creep_displacement;
        st.update(
            &CreepLaw::new(pair, CreepModel::FittedTransient),
            CreepInput::new(p, c, Vec2::new(dr, 0.0)),
        );
        let rate = c.x / dr / f;
        if i == 0 {
            assert!((rate - creep_law::transient_law::INITIAL_FRACTION).abs() < 1e-12);
        }
        assert!(rate >= prev && rate <= 1.0 + 1e-12, "{i}: {rate}");
        prev = rate;
    }
    assert!((prev - 1.0).abs() < 1e-9, "{prev}");
    assert!((st.force().x / mu_p - 0.6).abs() < 1e-9);
}

#[test]
fn transform_rotates_the_lag_with_the_memory() {
    let pair = pair();
    let p = 100.0;
    let mut st = CreepState::new();
    st.update(
        &CreepLaw::new(pair, CreepModel::FittedTransient),
        CreepInput::new(p, Vec2::ZERO, Vec2::ZERO),
    );
    st.update(
        &CreepLaw::new(pair, CreepModel::FittedTransient),
        CreepInput::new(p, Vec2::new(1e-6, 0.0), Vec2::ZERO),
    );
    for _ in 0..10 {
        st.update(
            &CreepLaw::new(pair, CreepModel::FittedTransient),
            CreepInput::new(p, Vec2::ZERO, Vec2::new(1e-6, 0.0)),
        );
    }
    let lag = st.lag();
    assert!(lag[0].x > 0.0);
    st.transform([[0.0, -1.0], [1.0, 0.0]]);
    assert_eq!(st.lag()[0], Vec2::new(-lag[0].y, lag[0].x));
    assert!((st.force().y - lag[0].x.signum() * st.force().length()).abs() < 1e-9);
    // Opening the contact clears the lag.
    st.update(
        &CreepLaw::new(pair, CreepModel::FittedTransient),
        CreepInput::new(0.0, Vec2::ZERO, Vec2::new(1e-6, 0.0)),
    );
    assert_eq!(st.lag(), [Vec2::ZERO; 2]);
}
