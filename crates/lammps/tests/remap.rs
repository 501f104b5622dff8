//! `HistoryStore::remap` (the one-rank rebuild: the store reordered by slot references) against
//! `save` then `load` (the flat form, the path of every rank count): the same histories bit for
//! bit, so the same forces afterwards; and its refusal of a slot outside the store.

mod common;
use common::Cluster;
use creep_lammps::{
    Accumulators, HistoryStore, Model, ModelError, ModelTable, PairIndex, PairOutputs, Settings,
    Tier, compute_pairs,
};
use creep_law::rolling_torque::RollingModel;

/// A chain of `n` spheres along x, each overlapping the next by ~1e-3 of the diameter.
fn chain(n: usize) -> Cluster {
    let mut c = Cluster::default();
    for i in 0..n {
        let s = (i as f64 * 0.7).sin();
        c.x.push([i as f64 * 1.998e-3, 1e-5 * s, -1e-5 * s]);
        c.v.push([0.01 * s, 0.02 * (i as f64).cos(), 0.005]);
        c.w.push([5.0 * s, -3.0, 2.0 * (i as f64).cos()]);
        let r = 1e-3 * (1.0 + 2e-4 * s);
        c.r.push(r);
        c.m.push(2500.0 * 4.0 / 3.0 * std::f64::consts::PI * r * r * r);
        c.kind.push(1);
    }
    c
}

fn model(tier: Tier) -> Model {
    Model::new(&Settings {
        young_modulus: 69.6e6,
        poisson_ratio: 0.2,
        restitution: 0.5,
        friction: 0.5,
        tier,
        creep: true,
        rolling: Some(RollingModel::epsd(0.2, 0.3).unwrap()),
    })
    .unwrap()
}

/// Steps the chain's pairs (i, i + 1), pair k in slot `slot_of[k]`, and returns the forces on
/// the atoms.
fn step(
    m: &Model,
    store: &mut HistoryStore,
    c: &Cluster,
    slot_of: &[usize],
    dt: f64,
) -> Vec<[f64; 3]> {
    let n = c.x.len();
    let pairs: Vec<PairIndex> = (0..n - 1)
        .map(|i| PairIndex {
            p: i as i32,
            q: i as i32 + 1,
            slot: slot_of[i] as i32,
        })
        .collect();
    let (mut f, mut t) = (vec![[0.0; 3]; n], vec![[0.0; 3]; n]);
    let table = ModelTable {
        ntypes: 1,
        model_of: |k: usize| (k == 3).then_some(m),
    };
    let atoms = c.atoms();
    let mut acc = Accumulators {
        force: &mut f,
        torque: &mut t,
    };
    let dropped = compute_pairs(
        &table,
        store,
        &atoms,
        &mut acc,
        &pairs,
        store.len().max(n - 1),
        dt,
        PairOutputs::default(),
    )
    .unwrap();
    assert_eq!(dropped, 0);
    f
}

fn flat(store: &HistoryStore) -> Vec<u64> {
    let mut out = vec![0.0; store.len() * store.tier().history_len()];
    store.save(&mut out).unwrap();
    out.iter().map(|x| x.to_bits()).collect()
}

fn remap_is_save_then_load(tier: Tier) {
    let m = model(tier);
    let mut c = chain(9);
    let n = c.x.len() - 1;
    let mut slot_of: Vec<usize> = (0..n).collect();
    let mut store = HistoryStore::new(tier);
    let dt = 2e-6;
    for round in 0..6 {
        // Steps with the velocities reversed every few steps: loading, unloading, reloading
        // (the exact tier's Mindlin memory holds turning points).
        for s in 0..12 {
            if s % 4 == 3 {
                for v in c.v.iter_mut().chain(c.w.iter_mut()) {
                    for a in v.iter_mut() {
                        *a = -*a;
                    }
                }
            }
            step(&m, &mut store, &c, &slot_of, dt);
            for (x, v) in c.x.iter_mut().zip(&c.v) {
                for d in 0..3 {
                    x[d] += dt * v[d];
                }
            }
        }
        // A rebuild: the pairs in another order (a rotation by `round + 1`), and pair 0's
        // history taken twice (as an owned-owned pair's is, once under each atom's row).
        let order: Vec<usize> = (0..n).map(|k| (k + round + 1) % n).collect();
        let mut from: Vec<i32> = order.iter().map(|&k| slot_of[k] as i32).collect();
        from.push(slot_of[0] as i32);
        // The flat path: save, gather the rows, load.
        let stride = tier.history_len();
        let mut saved = vec![0.0; store.len() * stride];
        store.save(&mut saved).unwrap();
        let mut rows = Vec::new();
        for &s in &from {
            rows.extend_from_slice(&saved[s as usize * stride..][..stride]);
        }
        let mut loaded = HistoryStore::new(tier);
        loaded.load(&rows).unwrap();
        store.remap(&from).unwrap();
        assert_eq!(store, loaded, "round {round}");
        assert_eq!(flat(&store), flat(&loaded), "round {round}");
        // New slots of the pairs; both stores step on alike.
        for (new, &k) in order.iter().enumerate() {
            slot_of[k] = new;
        }
        let f_remap = step(&m, &mut store, &c, &slot_of, dt);
        let f_load = step(&m, &mut loaded, &c, &slot_of, dt);
        let bits =
            |f: &[[f64; 3]]| -> Vec<u64> { f.iter().flatten().map(|x| x.to_bits()).collect() };
        assert_eq!(bits(&f_remap), bits(&f_load), "round {round}");
        assert_eq!(flat(&store), flat(&loaded), "round {round}");
        assert!(
            f_remap.iter().any(|a| a[0] != 0.0),
            "the chain carries force"
        );
    }
}

#[test]
fn remap_is_save_then_load_exact() {
    remap_is_save_then_load(Tier::Exact);
}

#[test]
fn remap_is_save_then_load_spring() {
    remap_is_save_then_load(Tier::Spring);
}

#[test]
fn remap_refuses_a_slot_outside_the_store_and_changes_nothing() {
    let m = model(Tier::Exact);
    let c = chain(4);
    let mut store = HistoryStore::new(Tier::Exact);
    step(&m, &mut store, &c, &[0, 1, 2], 1e-6);
    let before = store.clone();
    for bad in [3, -1] {
        match store.remap(&[0, bad]) {
            Err(ModelError::Slot { index, slot, len }) => {
                assert_eq!((index, slot, len), (1, bad, 3));
            }
            other => panic!("slot {bad}: expected a slot error, got {other:?}"),
        }
        assert_eq!(store, before);
    }
    store.remap(&[]).unwrap();
    assert!(store.is_empty());
}
