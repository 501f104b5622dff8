// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// pair_style granular/creep: Kuhn's creep-friction contact law (Hertz + damping from the
// restitution + Cattaneo-Mindlin with Kuhn's creep) evaluated by the Rust crate creep-lammps
// through its C ABI (creep_lammps.h), many contacts per call.
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

  void rebuild_slots();

  // Contact histories, each stored once, in place between neighbour-list builds (as LAMMPS'
  // fix neigh/history does): neighbour entry e (entry jj of list atom ii is
  // slot_first[ii] + jj) has its history in pool[slot[e] * hlen ..] (slot -1: none). The law
  // steps them there (creep_lammps_compute_at); the per-atom rows of fix creep/history are
  // written from them only when atoms may move between ranks or a restart is written
  // (sync_history_rows), and read back after each neighbour-list build (rebuild_slots).
  std::vector<int> slot_first, slot;
  std::vector<double> pool;
  int nslots;
  bool rows_stale;            // the pool holds newer histories than the rows
  bigint rebuilt_at;          // timestep of the last rebuild_slots() outside set-up
  double maxrad_user;         // pair_style ... maxradius R [m] (0: none)

  // Batch buffers (kept between steps: no allocation in the steady state).
  std::vector<CreepLammpsContact> batch;
  std::vector<size_t> batch_off;
  std::vector<CreepLammpsOutput> batch_out;
  std::vector<int> batch_i, batch_j, batch_e;
  std::vector<char> batch_swap;
  std::vector<const CreepLammpsModel *> batch_model;
};

}    // namespace LAMMPS_NS

#endif
