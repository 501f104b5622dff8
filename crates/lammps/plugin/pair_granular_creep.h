// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// pair_style granular/creep: Kuhn's creep-friction contact law (Hertz + damping from the
// restitution + Cattaneo-Mindlin with Kuhn's creep) evaluated by the Rust crate creep-lammps
// through its C ABI (creep_lammps.h), one call per step over the whole neighbour list.
#ifndef CREEP_PAIR_GRANULAR_CREEP_H
#define CREEP_PAIR_GRANULAR_CREEP_H

#include "pair.h"

#include "fix_creep_history.h"

#include "creep_lammps.h"

#include <vector>

namespace LAMMPS_NS {

class PairGranularCreep : public Pair, public CreepHistoryOwner {
 public:
  PairGranularCreep(class LAMMPS *);
  ~PairGranularCreep() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;
  void sync_history_rows() override;
  void save_before_exchange() override;

 private:
  void allocate();

  int maxpartners;                      // history slots per atom
  uint32_t tier;                        // CREEP_LAMMPS_TIER_*
  int creep;                            // Kuhn's creep on/off
  uint32_t rolling;                     // CREEP_LAMMPS_ROLLING_*
  double rolling_friction, rolling_damping;
  CreepLammpsModel ***models;           // per type pair (owned by [i][j], i <= j)
  double maxrad;                        // largest radius of any atom [m]
  class FixCreepHistory *fix_history;   // per-atom history storage

  void rebuild_slots(bool refs);
  void write_rows();
  void write_refs();
  // Each contact of the list built last whose history is live, in list order:
  // visit(i, j, tag_j, s), atoms i and j, j's tag at the build, s its slot in the store.
  template <class Visit> void each_live_contact(Visit &&visit) const;

  // Contact histories, each stored once, in place between neighbour-list builds (as LAMMPS'
  // fix neigh/history does): neighbour entry e (entry jj of list atom ii is
  // slot_first[ii] + jj) has its history in slot slot[e] of `store` (-1: none), creep-law's own
  // structs kept by the Rust side; the law walks the list and steps them there
  // (creep_lammps_compute_list). The
  // per-atom rows of fix creep/history are written from them only when atoms may move between
  // ranks or a restart is written (sync_history_rows), and read back after each neighbour-list
  // build (rebuild_slots); `stage` carries their flat form across the C ABI then.
  std::vector<int> slot_first, slot;
  std::vector<tagint> partner_tag;    // per neighbour entry: the partner's tag at the build
  int built_nlocal;                   // owned atoms at the build
  CreepLammpsStore *store;
  std::vector<double> stage;
  int nslots;
  bool rows_stale;            // the store holds newer histories than the rows
  // One rank: before an exchange each live history's slot in the store is noted under the
  // tags of its owned atoms (no atom leaves the process, so the histories stay in the store;
  // write_refs), and the rebuild that follows reorders the store by them
  // (creep_lammps_store_remap). Tag t's references (partner tag, slot) are
  // ref_tag/ref_slot[ref_first[t] .. ref_first[t + 1]), t in 1 .. ref_maxtag; `from`: the old
  // slot of each new one.
  bool rows_hold_refs;
  std::vector<int> from;
  std::vector<int> ref_first, ref_next, ref_slot;
  std::vector<tagint> ref_tag;
  tagint ref_maxtag;
  bigint rebuilt_at;          // timestep of the last rebuild_slots() outside set-up
  double maxrad_user;         // pair_style ... maxradius R [m] (0: none)
  std::vector<const CreepLammpsModel *> model_table;    // [ti * (ntypes + 1) + tj]

  // Dropped-history accounting (pvector, `compute pair granular/creep`): each contact is
  // counted once, on the rank that owns its lower-tag atom.
  double saved_contacts;       // histories written to the rows at the last sync
  double restored_contacts;    // histories found again at the rebuild that followed it
  bool counting;               // a sync happened since the last rebuild
  double dropped_total;        // sum of (saved - restored) over this run's rebuilds

  // Per neighbour entry: 1 where the neighbour is body p (the lower tag), set at the build.
  std::vector<uint8_t> swap;
  // The contacts' forces for the virial (kept between steps: no allocation in the steady state).
  std::vector<CreepLammpsPairForce> virial;
};

}    // namespace LAMMPS_NS

#endif
