//! The C ABI and the reference driver, without LAMMPS.
#![allow(unsafe_code)] // calls the C ABI as C++ would

use creep_lammps::driver::{Packing, Sim};
use creep_lammps::ffi::{
    CREEP_LAMMPS_ROLLING_NONE, CREEP_LAMMPS_TIER_EXACT, CREEP_LAMMPS_TIER_SPRING, CreepLammpsModel,
    CreepLammpsSettings, creep_lammps_compute, creep_lammps_compute_at, creep_lammps_history_len,
    creep_lammps_model_free, creep_lammps_model_new,
};
use creep_lammps::{Body, Contact, ContactOutput, Model, Settings, Tier, WallContact};
use std::ffi::{CStr, c_char};

fn settings(tier: u32, e: f64) -> CreepLammpsSettings {
    CreepLammpsSettings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: e,
        friction: 0.5,
        tier,
        creep: 1,
        rolling: CREEP_LAMMPS_ROLLING_NONE,
        rolling_friction: 0.0,
        rolling_damping: 0.0,
    }
}

fn model(tier: u32) -> *mut CreepLammpsModel {
    let mut err = [0 as c_char; 256];
    // SAFETY: valid settings and error buffer.
    let m = unsafe { creep_lammps_model_new(&settings(tier, 0.5), err.as_mut_ptr(), err.len()) };
    assert!(!m.is_null());
    m
}

fn sphere(x: [f64; 3], v: [f64; 3], w: [f64; 3]) -> Body {
    Body {
        x,
        v,
        omega: w,
        radius: 1e-3,
        mass: 2500.0 * 4.0 / 3.0 * std::f64::consts::PI * 1e-9,
    }
}

#[test]
fn bad_coefficients_are_refused_with_a_reason() {
    let mut err = [0 as c_char; 256];
    // SAFETY: valid settings and error buffer.
    let m = unsafe { creep_lammps_model_new(&settings(0, 0.0), err.as_mut_ptr(), err.len()) };
    assert!(m.is_null());
    // SAFETY: NUL-terminated by the callee.
    let msg = unsafe { CStr::from_ptr(err.as_ptr()) }.to_string_lossy();
    assert!(msg.contains("restitution"), "{msg}");
    // SAFETY: as above.
    let m = unsafe { creep_lammps_model_new(&settings(7, 0.5), err.as_mut_ptr(), err.len()) };
    assert!(m.is_null());
    assert_eq!(creep_lammps_history_len(7), 0);
}

#[test]
fn batch_matches_single_calls_and_keeps_history() {
    let m = model(CREEP_LAMMPS_TIER_EXACT);
    let stride = creep_lammps_history_len(CREEP_LAMMPS_TIER_EXACT);
    assert_eq!(stride, Tier::Exact.history_len());
    // Two overlapping pairs sliding tangentially, one pair apart.
    let contacts = [
        Contact {
            p: sphere([0.0; 3], [0.0; 3], [0.0; 3]),
            q: sphere([1.998e-3, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0; 3]),
        },
        Contact {
            p: sphere([0.0; 3], [0.0; 3], [0.0, 0.0, 3.0]),
            q: sphere([0.0, 0.0, 1.999e-3], [0.002, 0.0, 0.0], [0.0; 3]),
        },
        Contact {
            p: sphere([0.0; 3], [0.0; 3], [0.0; 3]),
            q: sphere([2.5e-3, 0.0, 0.0], [0.0; 3], [0.0; 3]),
        },
    ];
    let models = [m as *const CreepLammpsModel; 3];
    let mut hist = vec![0.0; 3 * stride];
    let mut out = [ContactOutput::default(); 3];
    let mut err = [0 as c_char; 256];
    for _ in 0..3 {
        // SAFETY: buffers sized for 3 contacts.
        let rc = unsafe {
            creep_lammps_compute(
                models.as_ptr(),
                1e-6,
                3,
                contacts.as_ptr(),
                hist.as_mut_ptr(),
                stride,
                out.as_mut_ptr(),
                err.as_mut_ptr(),
                err.len(),
            )
        };
        assert_eq!(rc, 0);
    }
    assert_eq!(out[0].touching, 1);
    assert_eq!(out[2].touching, 0);
    assert!(hist[2 * stride..].iter().all(|&h| h == 0.0));
    // Normal: Hertz along -x on p; tangential: q slides +y relative to p, so Q on p is +y.
    assert!(
        out[0].force_p[0] < 0.0 && out[0].force_p[1] > 0.0,
        "{:?}",
        out[0]
    );
    // The same contacts through the safe API, one at a time, give the same numbers.
    // SAFETY: m is live.
    let s = Settings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier: Tier::Exact,
        creep: true,
        rolling: None,
    };
    let safe = Model::new(&s).expect("model");
    for (k, c) in contacts.iter().enumerate() {
        let mut h = vec![0.0; stride];
        let mut o = ContactOutput::default();
        for _ in 0..3 {
            o = safe.step(c, &mut h, 1e-6).expect("step");
        }
        assert_eq!(o, out[k]);
        assert_eq!(h, hist[k * stride..(k + 1) * stride]);
    }
    // A wrong stride and a corrupt history are errors, not NaN.
    // SAFETY: as above.
    let rc = unsafe {
        creep_lammps_compute(
            models.as_ptr(),
            1e-6,
            3,
            contacts.as_ptr(),
            hist.as_mut_ptr(),
            stride - 1,
            out.as_mut_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 1);
    hist[10] = f64::NAN;
    // SAFETY: as above.
    let rc = unsafe {
        creep_lammps_compute(
            models.as_ptr(),
            1e-6,
            3,
            contacts.as_ptr(),
            hist.as_mut_ptr(),
            stride,
            out.as_mut_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 1);
    // SAFETY: NUL-terminated by the callee.
    let msg = unsafe { CStr::from_ptr(err.as_ptr()) }.to_string_lossy();
    assert!(msg.contains("contact 0"), "{msg}");
    // Mixed tiers in one batch are refused.
    let spring = model(CREEP_LAMMPS_TIER_SPRING);
    let mixed = [m as *const CreepLammpsModel, spring];
    let mut hist = vec![0.0; 2 * stride];
    // SAFETY: as above, 2 contacts.
    let rc = unsafe {
        creep_lammps_compute(
            mixed.as_ptr(),
            1e-6,
            2,
            contacts.as_ptr(),
            hist.as_mut_ptr(),
            stride,
            out.as_mut_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 1);
    // SAFETY: created above, freed once.
    unsafe {
        creep_lammps_model_free(m);
        creep_lammps_model_free(spring);
    }
}

#[test]
fn data_file_round_trips_and_driver_conserves_momentum() {
    let mut p = Packing::lattice(4, 1e-3, 2500.0, 1e-3, 4e-4);
    p.add_shear(100.0);
    let text = p.write_data("test");
    let q = Packing::read_data(&text).expect("parse");
    assert_eq!(q.x, p.x);
    assert_eq!(q.v, p.v);
    assert_eq!(q.radius, p.radius);
    assert!(Packing::read_data("title\n\n3 atoms\n").is_err());
    let mut q = q;
    q.periodic = true;
    let model = Model::new(&Settings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier: Tier::Exact,
        creep: true,
        rolling: None,
    })
    .expect("model");
    let momentum = |s: &Sim| {
        let p = &s.packing;
        (0..3)
            .map(|a| (0..p.tag.len()).map(|i| p.mass[i] * p.v[i][a]).sum::<f64>())
            .collect::<Vec<_>>()
    };
    let (mut sim, th) = Sim::new(q, model, 5e-6).expect("sim");
    // 64 spheres on a periodic 4^3 lattice: 3 squeezed neighbours each.
    assert_eq!(th.contacts, 192);
    assert!(th.pressure > 0.0);
    let m0 = momentum(&sim);
    for _ in 0..20 {
        sim.step().expect("step");
    }
    let m1 = momentum(&sim);
    let scale: f64 = sim.packing.mass.iter().sum::<f64>() * 1e-1;
    for a in 0..3 {
        assert!((m1[a] - m0[a]).abs() < 1e-12 * scale, "{m0:?} {m1:?}");
    }
}

#[test]
fn sphere_on_a_wall_is_pushed_off_it_with_hertz() {
    let m = Model::new(&Settings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier: Tier::Exact,
        creep: true,
        rolling: None,
    })
    .expect("model");
    let delta = 1e-6;
    let c = WallContact {
        point: [0.0, 0.0, -1.0],
        normal: [0.0, 0.0, 1.0],
        wall_velocity: [0.0; 3],
        sphere: sphere([0.0, 0.0, -1.0 + 1e-3 - delta], [0.0; 3], [0.0; 3]),
    };
    let mut h = vec![0.0; Tier::Exact.history_len()];
    let o = m.step_wall(&c, &mut h, 1e-6).expect("step");
    assert_eq!(o.touching, 1);
    // Hertz against a half-space: P = (4/3) E* sqrt(R) delta^1.5, E* = E / (2 (1 - nu^2)) for
    // two bodies of one material (creep-law's convention), R = the sphere's radius.
    let e_star = 69.6e6 / (2.0 * (1.0 - 0.04));
    let p = 4.0 / 3.0 * e_star * (1e-3f64).sqrt() * delta.powf(1.5);
    assert!(
        (-o.force_p[2] - p).abs() < 1e-6 * p,
        "{} vs {p}",
        -o.force_p[2]
    );
    let mut bad = c;
    bad.normal = [0.0, 0.0, 2.0];
    let mut out = [ContactOutput::default()];
    let e = Model::compute_walls(
        &[&m],
        1e-6,
        &[bad],
        &mut h,
        Tier::Exact.history_len(),
        &mut out,
    );
    assert!(e.is_err());
}

#[test]
fn in_place_batch_equals_the_contiguous_one_and_checks_offsets() {
    let m = model(CREEP_LAMMPS_TIER_EXACT);
    let stride = creep_lammps_history_len(CREEP_LAMMPS_TIER_EXACT);
    let contacts = [
        Contact {
            p: sphere([0.0; 3], [0.0; 3], [0.0; 3]),
            q: sphere([1.998e-3, 0.0, 0.0], [0.0, 0.01, 0.0], [0.0; 3]),
        },
        Contact {
            p: sphere([0.0; 3], [0.0; 3], [0.0, 0.0, 3.0]),
            q: sphere([0.0, 0.0, 1.999e-3], [0.002, 0.0, 0.0], [0.0; 3]),
        },
    ];
    let models = [m as *const CreepLammpsModel; 2];
    let mut err = [0 as c_char; 256];
    // Contiguous: contact k at k * stride.
    let mut flat = vec![0.0; 2 * stride];
    let mut out_flat = [ContactOutput::default(); 2];
    // In place: a store of 4 slots, contact 0 in slot 3, contact 1 in slot 1 (others untouched).
    let mut store = vec![7.0; 4 * stride];
    store[3 * stride..].fill(0.0);
    store[stride..2 * stride].fill(0.0);
    let offsets = [3 * stride, stride];
    let mut out_at = [ContactOutput::default(); 2];
    for _ in 0..3 {
        // SAFETY: buffers sized for 2 contacts, store of 4 * stride doubles.
        let (a, b) = unsafe {
            (
                creep_lammps_compute(
                    models.as_ptr(),
                    1e-6,
                    2,
                    contacts.as_ptr(),
                    flat.as_mut_ptr(),
                    stride,
                    out_flat.as_mut_ptr(),
                    err.as_mut_ptr(),
                    err.len(),
                ),
                creep_lammps_compute_at(
                    models.as_ptr(),
                    1e-6,
                    2,
                    contacts.as_ptr(),
                    store.as_mut_ptr(),
                    store.len(),
                    offsets.as_ptr(),
                    stride,
                    out_at.as_mut_ptr(),
                    err.as_mut_ptr(),
                    err.len(),
                ),
            )
        };
        assert_eq!((a, b), (0, 0));
    }
    assert_eq!(out_flat, out_at);
    assert_eq!(store[3 * stride..], flat[..stride]);
    assert_eq!(store[stride..2 * stride], flat[stride..]);
    assert!(
        store[..stride]
            .iter()
            .chain(&store[2 * stride..3 * stride])
            .all(|&h| h == 7.0)
    );
    assert!(flat.iter().any(|&h| h != 0.0), "the histories were written");
    // A row that leaves the store is an error with the contact named, not an access past it.
    let bad = [3 * stride + 1, 0];
    // SAFETY: as above.
    let rc = unsafe {
        creep_lammps_compute_at(
            models.as_ptr(),
            1e-6,
            2,
            contacts.as_ptr(),
            store.as_mut_ptr(),
            store.len(),
            bad.as_ptr(),
            stride,
            out_at.as_mut_ptr(),
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 1);
    // SAFETY: NUL-terminated by the callee.
    let msg = unsafe { CStr::from_ptr(err.as_ptr()) }.to_string_lossy();
    assert!(msg.contains("contact 0") && msg.contains("offset"), "{msg}");
    // SAFETY: created above, freed once.
    unsafe { creep_lammps_model_free(m) };
}
