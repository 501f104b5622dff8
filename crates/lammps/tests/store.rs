//! The pair style's hot path (`creep_lammps_compute_pairs` over a history store) against the
//! per-contact path (`Model::compute_at` on flat histories): the same law on the same values,
//! so the same bits; and its checks.
#![allow(unsafe_code)] // calls the C ABI as C++ would

mod common;
use common::{Cluster, Store, model, xorshift};

use creep_lammps::ffi::{
    CREEP_LAMMPS_TIER_EXACT, CREEP_LAMMPS_TIER_SPRING, CreepLammpsAtoms, CreepLammpsModel,
    creep_lammps_compute_pairs, creep_lammps_history_len, creep_lammps_model_free,
    creep_lammps_store_len, creep_lammps_store_load, creep_lammps_store_new,
    creep_lammps_store_save,
};
use creep_lammps::{Body, Contact, ContactOutput, Model, PairIndex, Settings, Tier};
use creep_law::rolling_torque::RollingModel;
use std::ffi::{CStr, c_char};

/// A small cluster: atoms 0..4 owned, 4..6 ghosts (copies at other places), moving and
/// spinning; every pair within touching distance is a contact. Deterministic pseudo-random.
fn cluster() -> Cluster {
    let mut rnd = xorshift(0x2545_f491_4f6c_dd1du64);
    let n: usize = 6;
    let mut c = Cluster::default();
    for i in 0..n {
        // A chain along x with overlaps ~1e-3 of the diameter, bent a little.
        c.x.push([i as f64 * 1.998e-3, 1e-4 * rnd(), 1e-4 * rnd()]);
        c.v.push([0.01 * rnd(), 0.01 * rnd(), 0.01 * rnd()]);
        c.w.push([5.0 * rnd(), 5.0 * rnd(), 5.0 * rnd()]);
        let r = 1e-3 * (1.0 + 0.002 * rnd());
        c.r.push(r);
        c.m.push(2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r);
        c.kind.push(1 + (i % 2) as i32);
    }
    c
}

fn body(c: &Cluster, i: usize) -> Body {
    Body {
        x: c.x[i],
        v: c.v[i],
        omega: c.w[i],
        radius: c.r[i],
        mass: c.m[i],
    }
}

#[allow(clippy::too_many_arguments)]
fn call(
    table: &[*const CreepLammpsModel],
    store: &Store,
    c: &mut Cluster,
    nlocal: usize,
    f: &mut [[f64; 3]],
    t: &mut [[f64; 3]],
    pairs: &[PairIndex],
    nslots: usize,
    force_p: Option<&mut [[f64; 3]]>,
    dropped: &mut usize,
) -> Result<(), String> {
    let atoms = CreepLammpsAtoms {
        nlocal,
        nall: c.x.len(),
        x: c.x.as_ptr().cast(),
        v: c.v.as_ptr().cast(),
        omega: c.w.as_ptr().cast(),
        radius: c.r.as_ptr(),
        rmass: c.m.as_ptr(),
        type_: c.kind.as_ptr(),
        f: f.as_mut_ptr().cast(),
        torque: t.as_mut_ptr().cast(),
    };
    let mut touching = vec![9u8; pairs.len()];
    let mut err = [0 as c_char; 256];
    let fp = force_p.map_or(std::ptr::null_mut(), |b| b.as_mut_ptr().cast::<f64>());
    // SAFETY: every buffer sized as the contract says.
    let rc = unsafe {
        creep_lammps_compute_pairs(
            table.as_ptr(),
            2,
            store.0,
            &atoms,
            1e-6,
            pairs.len(),
            pairs.as_ptr(),
            nslots,
            fp,
            touching.as_mut_ptr(),
            dropped,
            err.as_mut_ptr(),
            err.len(),
        )
    };
    if rc == 0 {
        assert!(touching.iter().all(|&b| b <= 1), "touching written");
        Ok(())
    } else {
        // SAFETY: NUL-terminated by the callee.
        Err(unsafe { CStr::from_ptr(err.as_ptr()) }
            .to_string_lossy()
            .into_owned())
    }
}

/// The pairs of the chain (i, i + 1), p the lower index, with slots in reverse order; pair 4-5
/// is between two ghosts (no force lands anywhere).
fn chain_pairs() -> Vec<PairIndex> {
    (0..5)
        .map(|i| PairIndex {
            p: i,
            q: i + 1,
            slot: 4 - i,
        })
        .collect()
}

fn bitwise_equal_to_compute_at(tier: u32) {
    let m = model(tier);
    let m2 = model(tier);
    // Types 1 and 2; the 1-2 pair has its own model (same coefficients).
    let table: Vec<*const CreepLammpsModel> = vec![
        std::ptr::null(),
        std::ptr::null(),
        std::ptr::null(),
        std::ptr::null(),
        m,
        m2,
        std::ptr::null(),
        m2,
        m,
    ];
    // The same coefficients as a safe-API model (every type pair has these).
    let reference = Model::new(&Settings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier: if tier == CREEP_LAMMPS_TIER_EXACT {
            Tier::Exact
        } else {
            Tier::Spring
        },
        creep: true,
        rolling: Some(RollingModel::epsd(0.2, 0.3).unwrap()),
    })
    .unwrap();
    let mut c = cluster();
    let nlocal = 4;
    let pairs = chain_pairs();
    let store = Store(creep_lammps_store_new(tier));
    let stride = creep_lammps_history_len(tier);
    let mut flat = vec![0.0; pairs.len() * stride];
    let (mut f, mut t) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    let (mut fr, mut tr) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    for step in 0..20 {
        let mut fp = vec![[0.0; 3]; pairs.len()];
        let mut dropped = 7;
        call(
            &table,
            &store,
            &mut c,
            nlocal,
            &mut f,
            &mut t,
            &pairs,
            5,
            Some(&mut fp),
            &mut dropped,
        )
        .unwrap();
        assert_eq!(dropped, 0);
        // The reference: the contacts one by one through Model::compute_at, accumulated as
        // the shim did before.
        let contacts: Vec<Contact> = pairs
            .iter()
            .map(|pr| Contact {
                p: body(&c, pr.p as usize),
                q: body(&c, pr.q as usize),
            })
            .collect();
        let offsets: Vec<usize> = pairs.iter().map(|pr| pr.slot as usize * stride).collect();
        let models: Vec<&Model> = pairs.iter().map(|_| &reference).collect();
        let mut out = vec![ContactOutput::default(); pairs.len()];
        Model::compute_at(
            &models, 1e-6, &contacts, &mut flat, &offsets, stride, &mut out,
        )
        .unwrap();
        for (k, (pr, o)) in pairs.iter().zip(&out).enumerate() {
            assert_eq!(fp[k], o.force_p, "step {step} contact {k}");
            let (p, q) = (pr.p as usize, pr.q as usize);
            if p < nlocal {
                for d in 0..3 {
                    fr[p][d] += o.force_p[d];
                    tr[p][d] += o.torque_p[d];
                }
            }
            if q < nlocal {
                for d in 0..3 {
                    fr[q][d] -= o.force_p[d];
                    tr[q][d] += o.torque_q[d];
                }
            }
        }
        assert_eq!((&f, &t), (&fr, &tr), "step {step}");
        // The store's histories are the flat ones, bit for bit.
        let mut saved = vec![0.0; pairs.len() * stride];
        let mut err = [0 as c_char; 256];
        // SAFETY: `saved` holds len * stride doubles.
        let rc = unsafe {
            creep_lammps_store_save(
                store.0,
                saved.as_mut_ptr(),
                saved.len(),
                stride,
                err.as_mut_ptr(),
                err.len(),
            )
        };
        assert_eq!(rc, 0);
        assert_eq!(saved, flat, "step {step}");
        // Move the atoms on (explicit Euler is enough to change the geometry).
        for i in 0..c.x.len() {
            for d in 0..3 {
                c.x[i][d] += 1e-6 * c.v[i][d];
            }
        }
        // Every few steps, a neighbour-list build: the histories out through their flat form
        // and back (what the shim does), which must change nothing.
        if step % 7 == 6 {
            // SAFETY: `saved` holds 5 histories.
            let rc = unsafe {
                creep_lammps_store_load(
                    store.0,
                    5,
                    saved.as_ptr(),
                    stride,
                    err.as_mut_ptr(),
                    err.len(),
                )
            };
            assert_eq!(rc, 0);
        }
    }
    assert!(
        f.iter().all(|a| a.iter().any(|&x| x != 0.0)),
        "every owned atom got a force"
    );
    // SAFETY: created above, freed once.
    unsafe {
        creep_lammps_model_free(m);
        creep_lammps_model_free(m2);
    }
}

#[test]
fn store_path_is_bitwise_the_per_contact_path_exact() {
    bitwise_equal_to_compute_at(CREEP_LAMMPS_TIER_EXACT);
}

#[test]
fn store_path_is_bitwise_the_per_contact_path_spring() {
    bitwise_equal_to_compute_at(CREEP_LAMMPS_TIER_SPRING);
}

#[test]
fn store_grows_with_virgin_slots_and_refuses_bad_input() {
    let m = model(CREEP_LAMMPS_TIER_SPRING);
    let mx = model(CREEP_LAMMPS_TIER_EXACT);
    let mut table: Vec<*const CreepLammpsModel> = vec![m; 9];
    let mut c = cluster();
    let nlocal = 4;
    let store = Store(creep_lammps_store_new(CREEP_LAMMPS_TIER_SPRING));
    assert!(creep_lammps_store_new(9).is_null());
    let (mut f, mut t) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    let mut dropped = 0;
    let ok = [PairIndex {
        p: 0,
        q: 1,
        slot: 2,
    }];
    call(
        &table,
        &store,
        &mut c,
        nlocal,
        &mut f,
        &mut t,
        &ok,
        3,
        None,
        &mut dropped,
    )
    .unwrap();
    // SAFETY: live store.
    assert_eq!(unsafe { creep_lammps_store_len(store.0) }, 3);
    let mut bad = |pairs: &[PairIndex], table: &[*const CreepLammpsModel], c: &mut Cluster| {
        call(
            table,
            &store,
            c,
            nlocal,
            &mut f,
            &mut t,
            pairs,
            3,
            None,
            &mut dropped,
        )
        .unwrap_err()
    };
    let e = bad(
        &[PairIndex {
            p: 0,
            q: 6,
            slot: 0,
        }],
        &table,
        &mut c,
    );
    assert!(e.contains("atom index 6"), "{e}");
    let e = bad(
        &[PairIndex {
            p: -1,
            q: 1,
            slot: 0,
        }],
        &table,
        &mut c,
    );
    assert!(e.contains("atom index -1"), "{e}");
    let e = bad(
        &[PairIndex {
            p: 0,
            q: 1,
            slot: 3,
        }],
        &table,
        &mut c,
    );
    assert!(e.contains("slot 3"), "{e}");
    let e = bad(
        &[PairIndex {
            p: 0,
            q: 1,
            slot: -2,
        }],
        &table,
        &mut c,
    );
    assert!(e.contains("slot -2"), "{e}");
    c.kind[1] = 3;
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("atom type 3"), "{e}");
    c.kind[1] = 2;
    table[5] = std::ptr::null();
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("no model"), "{e}");
    table[5] = mx;
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("same tangential tier"), "{e}");
    table[5] = m;
    c.r[0] = -1.0;
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("radius"), "{e}");
    c.r[0] = 1e-3;
    c.x[1][0] = f64::NAN;
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("not finite"), "{e}");
    c.x[1][0] = 1.998e-3;
    c.v[0][2] = f64::INFINITY;
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("not finite"), "{e}");
    c.v[0][2] = 0.0;
    c.w[1][1] = f64::NAN;
    let e = bad(&ok, &table, &mut c);
    assert!(e.contains("not finite"), "{e}");
    c.w[1][1] = 0.0;
    // Coincident centres: dropped, counted, the slot virgin again.
    c.x[1] = c.x[0];
    call(
        &table,
        &store,
        &mut c,
        nlocal,
        &mut f,
        &mut t,
        &ok,
        3,
        None,
        &mut dropped,
    )
    .unwrap();
    assert_eq!(dropped, 1);
    // A corrupt flat history is refused on load, with the slot named, and empties the store.
    let stride = creep_lammps_history_len(CREEP_LAMMPS_TIER_SPRING);
    let mut flat = vec![0.0; 2 * stride];
    flat[stride + 2] = f64::NAN;
    let mut err = [0 as c_char; 256];
    // SAFETY: `flat` holds 2 histories.
    let rc = unsafe {
        creep_lammps_store_load(
            store.0,
            2,
            flat.as_ptr(),
            stride,
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 1);
    // SAFETY: NUL-terminated by the callee.
    let msg = unsafe { CStr::from_ptr(err.as_ptr()) }.to_string_lossy();
    assert!(msg.contains("contact 1"), "{msg}");
    // SAFETY: live store.
    assert_eq!(unsafe { creep_lammps_store_len(store.0) }, 0);
    // The wrong stride is refused.
    // SAFETY: as above.
    let rc = unsafe {
        creep_lammps_store_load(
            store.0,
            1,
            flat.as_ptr(),
            stride + 1,
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 1);
    // SAFETY: created above, freed once.
    unsafe {
        creep_lammps_model_free(m);
        creep_lammps_model_free(mx);
    }
}
