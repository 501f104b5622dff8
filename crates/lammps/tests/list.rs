//! The pair style's fused step (`creep_lammps_compute_list`: the neighbour loop on the Rust
//! side) against the shim's former two passes (the C++ neighbour loop gathering the touching
//! pairs, then `creep_lammps_compute_pairs`): the same contacts in the same order through the
//! same kernel, so the same bits, the same slots and the same counts; and its checks of the
//! list.
#![allow(unsafe_code)] // calls the C ABI as C++ would

mod common;
use common::{Cluster, Store, model, xorshift};

use creep_lammps::ffi::{
    CREEP_LAMMPS_ROLLING_EPSD, CREEP_LAMMPS_ROLLING_NONE, CREEP_LAMMPS_TIER_EXACT,
    CREEP_LAMMPS_TIER_SPRING, CreepLammpsAtoms, CreepLammpsList, CreepLammpsModel,
    CreepLammpsSettings, creep_lammps_compute_list, creep_lammps_compute_pairs,
    creep_lammps_history_len, creep_lammps_model_free, creep_lammps_model_new,
    creep_lammps_store_len, creep_lammps_store_new, creep_lammps_store_save,
};
use creep_lammps::{
    Accumulators, HistoryStore, ListCounts, ListEntries, Model, ModelTable, PairForce, PairIndex,
    Settings, Tier, VecList, compute_list,
};
use std::ffi::{CStr, c_char};

/// LAMMPS' NEIGHMASK: the top bits of a neighbour index flag special bonds.
const NEIGHMASK: i32 = 0x1FFF_FFFF;

/// Eight spheres, 0..5 owned and 5..8 ghosts: a bent chain (i, i + 1 overlapping by ~1e-3 of
/// the diameter) whose ends drift apart and back (so contacts open and new ones close),
/// moving and spinning; deterministic pseudo-random.
fn cluster() -> Cluster {
    let mut rnd = xorshift(0x9e37_79b9_7f4a_7c15u64);
    let mut c = Cluster::default();
    for i in 0..8 {
        c.x.push([i as f64 * 1.998e-3, 1e-4 * rnd(), 1e-4 * rnd()]);
        // Atoms 2 and 6 move off along y: their contacts open during the run.
        let vy = if i == 2 || i == 6 { 5.0 } else { 0.01 * rnd() };
        c.v.push([0.01 * rnd(), vy, 0.01 * rnd()]);
        c.w.push([5.0 * rnd(), 5.0 * rnd(), 5.0 * rnd()]);
        let r = 1e-3 * (1.0 + 0.002 * rnd());
        c.r.push(r);
        c.m.push(2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r);
        c.kind.push(1 + i % 2);
    }
    c
}

/// A half list over the owned atoms: atom i lists i + 1 and i + 2 (the second one apart),
/// some with special-bond bits set; `swap` where the tags (here: i + j odd) say the neighbour
/// is body p.
fn half_list(nlocal: usize, nall: usize) -> (Vec<i32>, Vec<Vec<i32>>, Vec<u8>) {
    let ilist: Vec<i32> = (0..nlocal as i32).rev().collect(); // LAMMPS' order need not be sorted
    let mut neigh = vec![vec![]; nlocal];
    let mut swap = vec![];
    for &i in &ilist {
        for j in [i + 1, i + 2] {
            if (j as usize) < nall {
                let flag = if j % 3 == 0 { 1 << 30 } else { 0 };
                neigh[i as usize].push(j | flag);
                swap.push(u8::from((i + j) % 2 == 1));
            }
        }
    }
    (ilist, neigh, swap)
}

fn atoms(c: &Cluster, nlocal: usize, f: &mut [[f64; 3]], t: &mut [[f64; 3]]) -> CreepLammpsAtoms {
    CreepLammpsAtoms {
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
    }
}

fn message(err: &[c_char]) -> String {
    // SAFETY: NUL-terminated by the callee.
    unsafe { CStr::from_ptr(err.as_ptr()) }
        .to_string_lossy()
        .into_owned()
}

/// The fused call on the list; `Err` with the message.
#[allow(clippy::too_many_arguments)]
fn call_list(
    table: &[*const CreepLammpsModel],
    store: &Store,
    a: &CreepLammpsAtoms,
    ilist: &[i32],
    neigh: &[Vec<i32>],
    slot: &mut [i32],
    swap: &[u8],
    forces: Option<&mut [PairForce]>,
) -> Result<ListCounts, String> {
    let rows: Vec<*const i32> = neigh.iter().map(|n| n.as_ptr()).collect();
    let num: Vec<i32> = neigh.iter().map(|n| n.len() as i32).collect();
    let list = CreepLammpsList {
        inum: ilist.len(),
        ilist: ilist.as_ptr(),
        numneigh: num.as_ptr(),
        firstneigh: rows.as_ptr(),
        maxatom: neigh.len(),
        neighmask: NEIGHMASK,
        nentries: slot.len().min(swap.len()),
        slot: slot.as_mut_ptr(),
        swap: swap.as_ptr(),
    };
    let mut counts = ListCounts {
        contacts: 99,
        ..ListCounts::default()
    };
    let mut err = [0 as c_char; 256];
    let fp = forces.map_or(std::ptr::null_mut(), |b| b.as_mut_ptr());
    // SAFETY: every buffer sized as the contract says.
    let rc = unsafe {
        creep_lammps_compute_list(
            table.as_ptr(),
            2,
            store.0,
            a,
            &list,
            1e-6,
            fp,
            &mut counts,
            err.as_mut_ptr(),
            err.len(),
        )
    };
    if rc == 0 {
        Ok(counts)
    } else {
        Err(message(&err))
    }
}

fn saved(store: &Store, tier: u32) -> Vec<f64> {
    let stride = creep_lammps_history_len(tier);
    // SAFETY: a live store.
    let n = unsafe { creep_lammps_store_len(store.0) };
    let mut out = vec![0.0; n * stride];
    let mut err = [0 as c_char; 256];
    // SAFETY: `out` holds n * stride doubles.
    let rc = unsafe {
        creep_lammps_store_save(
            store.0,
            out.as_mut_ptr(),
            out.len(),
            stride,
            err.as_mut_ptr(),
            err.len(),
        )
    };
    assert_eq!(rc, 0, "{}", message(&err));
    out
}

/// [`model`] with rolling resistance `rolling` (`CREEP_LAMMPS_ROLLING_*`).
fn model_rolling(tier: u32, rolling: u32) -> *mut CreepLammpsModel {
    let s = CreepLammpsSettings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier,
        creep: 1,
        rolling,
        rolling_friction: 0.2,
        rolling_damping: 0.3,
    };
    let mut err = [0 as c_char; 256];
    // SAFETY: valid settings and error buffer.
    let m = unsafe { creep_lammps_model_new(&s, err.as_mut_ptr(), err.len()) };
    assert!(!m.is_null(), "{}", message(&err));
    m
}

fn list_equals_pairs(tier: u32) {
    list_equals_pairs_with(tier, CREEP_LAMMPS_ROLLING_EPSD);
}

fn list_equals_pairs_with(tier: u32, rolling: u32) {
    let m = model_rolling(tier, rolling);
    let m2 = model_rolling(tier, rolling);
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
    let mut c = cluster();
    let (nlocal, nall) = (5, c.x.len());
    let (ilist, neigh, swap) = half_list(nlocal, nall);
    let nentries = swap.len();
    let (sa, sb) = (
        Store(creep_lammps_store_new(tier)),
        Store(creep_lammps_store_new(tier)),
    );
    let (mut fa, mut ta) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    let (mut fb, mut tb) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    let (mut slot_a, mut slot_b) = (vec![-1i32; nentries], vec![-1i32; nentries]);
    let mut nslots_b = 0usize;
    let (mut opened, mut max_contacts) = (0, 0);
    for step in 0..40 {
        // A: the fused call.
        let mut forces = vec![PairForce::default(); nentries];
        let a = atoms(&c, nlocal, &mut fa, &mut ta);
        let counts = call_list(
            &table,
            &sa,
            &a,
            &ilist,
            &neigh,
            &mut slot_a,
            &swap,
            Some(&mut forces),
        )
        .unwrap();
        // B: the shim's former neighbour loop, then the batched call.
        let mut pairs = vec![];
        let mut owned = 0;
        let mut e = 0;
        for &i in &ilist {
            for &jraw in &neigh[i as usize] {
                let (iu, j) = (i as usize, (jraw & NEIGHMASK) as usize);
                let d2: f64 = (0..3).map(|k| (c.x[j][k] - c.x[iu][k]).powi(2)).sum();
                let rsum = c.r[iu] + c.r[j];
                if d2 >= rsum * rsum {
                    slot_b[e] = -1;
                } else {
                    if slot_b[e] < 0 {
                        slot_b[e] = nslots_b as i32;
                        nslots_b += 1;
                    }
                    let (p, q) = if swap[e] != 0 { (j, iu) } else { (iu, j) };
                    owned += usize::from(p < nlocal);
                    pairs.push(PairIndex {
                        p: p as i32,
                        q: q as i32,
                        slot: slot_b[e],
                    });
                }
                e += 1;
            }
        }
        let mut fp = vec![[0.0; 3]; pairs.len()];
        let mut touching = vec![0u8; pairs.len()];
        let mut dropped = 0;
        let b = atoms(&c, nlocal, &mut fb, &mut tb);
        let mut err = [0 as c_char; 256];
        // SAFETY: every buffer sized as the contract says.
        let rc = unsafe {
            creep_lammps_compute_pairs(
                table.as_ptr(),
                2,
                sb.0,
                &b,
                1e-6,
                pairs.len(),
                pairs.as_ptr(),
                nslots_b,
                fp.as_mut_ptr().cast(),
                touching.as_mut_ptr(),
                &mut dropped,
                err.as_mut_ptr(),
                err.len(),
            )
        };
        assert_eq!(rc, 0, "{}", message(&err));
        assert_eq!(dropped, 0);
        assert_eq!(
            counts,
            ListCounts {
                contacts: pairs.len(),
                owned_contacts: owned,
                dropped: 0,
                nslots: nslots_b,
            },
            "step {step}"
        );
        assert_eq!(slot_a, slot_b, "step {step}");
        for (k, pr) in pairs.iter().enumerate() {
            assert_eq!(
                forces[k],
                PairForce {
                    p: pr.p,
                    q: pr.q,
                    force_p: fp[k]
                },
                "step {step} contact {k}"
            );
        }
        assert_eq!((&fa, &ta), (&fb, &tb), "step {step}");
        assert_eq!(saved(&sa, tier), saved(&sb, tier), "step {step}");
        opened += slot_a.iter().filter(|&&s| s < 0).count();
        max_contacts = max_contacts.max(pairs.len());
        for i in 0..nall {
            for d in 0..3 {
                c.x[i][d] += 1e-6 * c.v[i][d];
            }
        }
    }
    // The run did what it is for: contacts on both sides of the swap, owned and ghost atoms,
    // entries apart (the i + 2 ones, and the chain opening at atoms 2 and 6).
    assert!(max_contacts >= 5, "{max_contacts}");
    assert!(opened > 0);
    assert!(fa.iter().all(|a| a.iter().any(|&x| x != 0.0)));
    // SAFETY: created above, freed once.
    unsafe {
        creep_lammps_model_free(m);
        creep_lammps_model_free(m2);
    }
}

#[test]
fn list_path_is_bitwise_the_pairs_path_spring() {
    list_equals_pairs(CREEP_LAMMPS_TIER_SPRING);
}

/// The spring tier without rolling resistance (the pair style's default).
#[test]
fn list_path_is_bitwise_the_pairs_path_spring_no_rolling() {
    list_equals_pairs_with(CREEP_LAMMPS_TIER_SPRING, CREEP_LAMMPS_ROLLING_NONE);
}

#[test]
fn list_path_is_bitwise_the_pairs_path_exact() {
    list_equals_pairs(CREEP_LAMMPS_TIER_EXACT);
}

#[test]
fn list_path_refuses_a_list_that_does_not_match() {
    let m = model(CREEP_LAMMPS_TIER_SPRING);
    let table: Vec<*const CreepLammpsModel> = vec![m; 9];
    let c = cluster();
    let (nlocal, nall) = (5, c.x.len());
    let (ilist, neigh, swap) = half_list(nlocal, nall);
    let store = Store(creep_lammps_store_new(CREEP_LAMMPS_TIER_SPRING));
    let (mut f, mut t) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    let a = atoms(&c, nlocal, &mut f, &mut t);
    let mut slot = vec![-1; swap.len()];
    // Entries shorter than the list.
    let e = call_list(
        &table,
        &store,
        &a,
        &ilist,
        &neigh,
        &mut slot[1..],
        &swap[1..],
        None,
    )
    .unwrap_err();
    assert!(e.contains("per-entry arrays"), "{e}");
    // A list atom outside the list's arrays.
    let mut bad_ilist = ilist.clone();
    bad_ilist[0] = 9;
    let e = call_list(
        &table, &store, &a, &bad_ilist, &neigh, &mut slot, &swap, None,
    )
    .unwrap_err();
    assert!(e.contains("neighbour list atom 9"), "{e}");
    // A neighbour outside the atom arrays.
    let mut bad = neigh.clone();
    bad[1][0] = 8;
    let e = call_list(&table, &store, &a, &ilist, &bad, &mut slot, &swap, None).unwrap_err();
    assert!(e.contains("atom index 8"), "{e}");
    // A slot outside the store (a new, empty store: the call above stepped the contacts
    // before the bad neighbour).
    let store = Store(creep_lammps_store_new(CREEP_LAMMPS_TIER_SPRING));
    let mut slot = vec![-1; swap.len()];
    slot[0] = 3;
    let e = call_list(&table, &store, &a, &ilist, &neigh, &mut slot, &swap, None).unwrap_err();
    assert!(e.contains("slot 3"), "{e}");
    // The good list goes through.
    let mut slot = vec![-1; swap.len()];
    let counts = call_list(&table, &store, &a, &ilist, &neigh, &mut slot, &swap, None).unwrap();
    assert!(counts.contacts >= 4 && counts.nslots == counts.contacts);
    // SAFETY: created above, freed once.
    unsafe { creep_lammps_model_free(m) };
}

#[test]
fn safe_list_api_checks_its_buffers() {
    let model = Model::new(&Settings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier: Tier::Spring,
        creep: true,
        rolling: None,
    })
    .unwrap();
    let c = cluster();
    let (nlocal, nall) = (5, c.x.len());
    let (ilist, neigh, swap) = half_list(nlocal, nall);
    let list = VecList {
        atoms: ilist,
        neighbours: neigh,
    };
    let table = ModelTable {
        ntypes: 2,
        model_of: |_| Some(&model),
    };
    let atoms = c.atoms();
    let (mut f, mut t) = (vec![[0.0; 3]; nlocal], vec![[0.0; 3]; nlocal]);
    let mut store = HistoryStore::new(Tier::Spring);
    let mut slot = vec![-1; swap.len()];
    let mut run = |forces: Option<&mut [PairForce]>, dt: f64, store: &mut HistoryStore| {
        compute_list(
            &table,
            store,
            &atoms,
            &mut Accumulators {
                force: &mut f,
                torque: &mut t,
            },
            &list,
            NEIGHMASK,
            ListEntries {
                slot: &mut slot,
                swap: &swap,
            },
            dt,
            forces,
        )
    };
    // A virial buffer shorter than the list, a bad time step: refused before anything is
    // stepped (the store stays empty).
    let mut short = vec![PairForce::default(); 2];
    let e = run(Some(&mut short), 1e-6, &mut store).unwrap_err();
    assert!(e.to_string().contains("output buffer"), "{e}");
    let e = run(None, f64::NAN, &mut store).unwrap_err();
    assert!(e.to_string().contains("time step"), "{e}");
    assert!(store.is_empty());
    // The same call with a long enough buffer goes through; the forces are those of the
    // contacts, in order, with p and q from the list (atom 4 lists 5 and 6, 5 is touching).
    let mut forces = vec![PairForce::default(); swap.len()];
    let counts = run(Some(&mut forces), 1e-6, &mut store).unwrap();
    assert_eq!(counts.nslots, store.len());
    assert!(counts.contacts >= 4);
    let first = forces[0];
    assert_eq!((first.p.min(first.q), first.p.max(first.q)), (4, 5));
    assert!(first.force_p.iter().any(|&x| x != 0.0));
    assert!(
        forces[counts.contacts..]
            .iter()
            .all(|f| *f == PairForce::default())
    );
}
