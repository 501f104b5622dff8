// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// pair_style granular/creep: Kuhn's creep-friction contact law (Hertz + damping from the
// restitution + Cattaneo-Mindlin with Kuhn's creep) evaluated by the Rust crate creep-lammps
// through its C ABI (creep_lammps.h), many contacts per call.
#ifndef CREEP_PAIR_GRANULAR_CREEP_H
#define CREEP_PAIR_GRANULAR_CREEP_H

#include "pair.h"

#include "creep_lammps.h"

#include <vector>

namespace LAMMPS_NS {

class PairGranularCreep : public Pair {
 public:
  PairGranularCreep(class LAMMPS *);
  ~PairGranularCreep() override;

  void compute(int, int) override;
  void settings(int, char **) override;
  void coeff(int, char **) override;
  void init_style() override;
  double init_one(int, int) override;

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

  // Batch buffers (kept between steps: no allocation in the steady state).
  std::vector<CreepLammpsContact> batch;
  std::vector<double> batch_hist;
  std::vector<CreepLammpsOutput> batch_out;
  std::vector<int> batch_i, batch_j, batch_swap;
  std::vector<const CreepLammpsModel *> batch_model;
};

}    // namespace LAMMPS_NS

#endif
