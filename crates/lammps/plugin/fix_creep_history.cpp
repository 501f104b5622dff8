// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
#include "fix_creep_history.h"

#include "atom.h"
#include "error.h"
#include "force.h"
#include "pair.h"
#include "memory.h"
#include "utils.h"

#include <cstring>

using namespace LAMMPS_NS;
using namespace FixConst;

// fix ID group creep/history maxpartners hlen
FixCreepHistory::FixCreepHistory(LAMMPS *lmp, int narg, char **arg) :
    Fix(lmp, narg, arg), pair_store(true), maxpartners(0), hlen(0), rowlen(0), rows(nullptr), spare(nullptr)
{
  if (narg != 5) error->all(FLERR, "Illegal fix creep/history command: expected maxpartners hlen");
  maxpartners = utils::inumeric(FLERR, arg[3], false, lmp);
  hlen = utils::inumeric(FLERR, arg[4], false, lmp);
  if (maxpartners < 1 || hlen < 1) error->all(FLERR, "fix creep/history: maxpartners and hlen must be >= 1");
  init_storage();
}

FixCreepHistory::FixCreepHistory(LAMMPS *lmp, int narg, char **arg, int maxp, int hl) :
    Fix(lmp, narg, arg), pair_store(false), maxpartners(maxp), hlen(hl), rowlen(0), rows(nullptr), spare(nullptr)
{
  if (maxpartners < 1 || hlen < 1) error->all(FLERR, "fix {}: no walls or no history", style);
  init_storage();
}

void FixCreepHistory::init_storage()
{
  rowlen = 1 + maxpartners * (1 + hlen);
  restart_peratom = 1;
  create_attribute = 1;
  maxexchange = rowlen;

  grow_arrays(atom->nmax);
  atom->add_callback(Atom::GROW);
  atom->add_callback(Atom::RESTART);
  for (int i = 0; i < atom->nlocal; i++) rows[i][0] = 0.0;
}

FixCreepHistory::~FixCreepHistory()
{
  atom->delete_callback(id, Atom::GROW);
  atom->delete_callback(id, Atom::RESTART);
  memory->destroy(rows);
  memory->destroy(spare);
}

int FixCreepHistory::setmask()
{
  return PRE_EXCHANGE | MIN_PRE_EXCHANGE;
}

void FixCreepHistory::sync_from_pair()
{
  if (!pair_store) return;
  // The pair style itself, or its instance inside pair_style hybrid (one at most: init_style).
  if (auto *owner = dynamic_cast<CreepHistoryOwner *>(force->pair_match("granular/creep", 1)))
    owner->sync_history_rows();
}

// Atoms are about to migrate (and be sorted): the rows must hold the current histories.
void FixCreepHistory::setup_pre_exchange()
{
  sync_from_pair();
}

void FixCreepHistory::save_from_pair_before_exchange()
{
  if (!pair_store) return;
  if (auto *owner = dynamic_cast<CreepHistoryOwner *>(force->pair_match("granular/creep", 1)))
    owner->save_before_exchange();
}

void FixCreepHistory::pre_exchange()
{
  save_from_pair_before_exchange();
}

void FixCreepHistory::min_pre_exchange()
{
  sync_from_pair();
}

// Between runs atoms may be deleted, created or written to a restart: rows current.
void FixCreepHistory::post_run()
{
  sync_from_pair();
}

void FixCreepHistory::grow_arrays(int nmax)
{
  memory->grow(rows, nmax, rowlen, "creep/history:rows");
  // The second buffer only for fix wall/creep (it rewrites its rows every step); the pair
  // style's rows are rewritten in place (sync_history_rows).
  if (!pair_store) memory->grow(spare, nmax, rowlen, "creep/history:spare");
}

void FixCreepHistory::copy_arrays(int i, int j, int /*delflag*/)
{
  std::memcpy(rows[j], rows[i], sizeof(double) * used(i));
}

void FixCreepHistory::set_arrays(int i)
{
  rows[i][0] = 0.0;
}

int FixCreepHistory::pack_exchange(int i, double *buf)
{
  const int n = used(i);
  std::memcpy(buf, rows[i], sizeof(double) * n);
  return n;
}

int FixCreepHistory::unpack_exchange(int nlocal, double *buf)
{
  const int count = static_cast<int>(buf[0]);
  if (count < 0 || count > maxpartners) error->one(FLERR, "fix creep/history: corrupt exchange buffer");
  const int n = used_for(count);
  std::memcpy(rows[nlocal], buf, sizeof(double) * n);
  return n;
}

// Restart: [n + 1, row...], LAMMPS' convention that the first value counts the values.
int FixCreepHistory::pack_restart(int i, double *buf)
{
  sync_from_pair();    // a restart written during a run (restart N file): once, then current
  const int n = used(i);
  buf[0] = n + 1;
  std::memcpy(buf + 1, rows[i], sizeof(double) * n);
  return n + 1;
}

void FixCreepHistory::unpack_restart(int nlocal, int nth)
{
  double **extra = atom->extra;
  int m = 0;
  for (int k = 0; k < nth; k++) m += static_cast<int>(extra[nlocal][m]);
  const int n = static_cast<int>(extra[nlocal][m]) - 1;
  const int count = static_cast<int>(extra[nlocal][m + 1]);
  if (count < 0 || count > maxpartners || n != used_for(count))
    error->one(FLERR, "fix creep/history: restart row does not match maxpartners/hlen of this build");
  std::memcpy(rows[nlocal], &extra[nlocal][m + 1], sizeof(double) * n);
}

int FixCreepHistory::size_restart(int i)
{
  sync_from_pair();
  return used(i) + 1;
}

int FixCreepHistory::maxsize_restart()
{
  return rowlen + 1;
}

double FixCreepHistory::memory_usage()
{
  return (pair_store ? 1.0 : 2.0) * static_cast<double>(atom->nmax) * rowlen * sizeof(double);
}
