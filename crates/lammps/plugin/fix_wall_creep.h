// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// fix wall/creep: flat walls (planes normal to x, y or z) with Kuhn's creep-friction contact law
// (the same kernel as pair_style granular/creep, the wall as a half-space of the given
// material). Per-atom wall-contact histories keyed by wall index, migrating and restarting like
// fix creep/history's.
#ifndef CREEP_FIX_WALL_CREEP_H
#define CREEP_FIX_WALL_CREEP_H

#include "fix_creep_history.h"

#include "creep_lammps.h"

#include <vector>

namespace LAMMPS_NS {

class FixWallCreep : public FixCreepHistory {
 public:
  FixWallCreep(class LAMMPS *, int, char **);
  ~FixWallCreep() override;
  int setmask() override;
  void init() override;
  void setup(int) override;
  void post_force(int) override;
  double compute_vector(int) override;
  void write_restart(FILE *) override;
  void restart(char *) override;

 private:
  struct Plane {
    int axis;        // 0, 1, 2
    double side;     // +1: lower wall (normal +axis), -1: upper wall (normal -axis)
    double at;       // position [m]
  };
  std::vector<Plane> planes;
  double velocity[3];     // of all walls of this fix [m/s] (velocity VX VY VZ; default 0)
  bigint time_origin;     // step at which the walls were at their given positions
  CreepLammpsModel *model;
  std::vector<CreepLammpsWallContact> batch;
  std::vector<double> batch_hist;
  std::vector<CreepLammpsOutput> batch_out;
  std::vector<int> batch_i, batch_w;
  std::vector<const CreepLammpsModel *> batch_model;
  std::vector<double> wall_force, wall_force_all;    // 3 per plane
  int force_flag;
};

}    // namespace LAMMPS_NS

#endif
