// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// Plugin entry point: registers pair_style granular/creep, fix creep/history and fix wall/creep.
#include "lammpsplugin_decl.h"

#include "fix_creep_history.h"
#include "lammps.h"
#include "fix_wall_creep.h"
#include "pair_granular_creep.h"

using namespace LAMMPS_NS;

static void *pair_creator(void *lmp)
{
  return new PairGranularCreep(static_cast<LAMMPS *>(lmp));
}

static void *fix_creator(void *lmp, int narg, char **arg)
{
  return new FixCreepHistory(static_cast<LAMMPS *>(lmp), narg, arg);
}

static void *wall_creator(void *lmp, int narg, char **arg)
{
  return new FixWallCreep(static_cast<LAMMPS *>(lmp), narg, arg);
}

extern "C" void lammpsplugin_init(void *lmp, void *handle, void *regfunc)
{
  auto reg = reinterpret_cast<creep_lammpsplugin_regfunc>(regfunc);
  // The version of the running LAMMPS: the plugin must be built against the same version's
  // headers (the loader compares this string with its own).
  const char *version = static_cast<LAMMPS *>(lmp)->version;

  creep_lammpsplugin_t plugin;
  plugin.version = version;
  plugin.style = "pair";
  plugin.name = "granular/creep";
  plugin.info = "Kuhn's creep-friction (Hertz, Tsuji damping, Cattaneo-Mindlin + creep) via creep-lammps";
  plugin.author = "creep-friction contributors";
  plugin.creator.v1 = &pair_creator;
  plugin.handle = handle;
  reg(&plugin, lmp);

  plugin.style = "fix";
  plugin.name = "creep/history";
  plugin.info = "per-atom contact history of pair_style granular/creep, keyed by partner tag";
  plugin.creator.v2 = &fix_creator;
  reg(&plugin, lmp);

  plugin.name = "wall/creep";
  plugin.info = "flat walls (x/y/z planes) with Kuhn's creep-friction law via creep-lammps";
  plugin.creator.v2 = &wall_creator;
  reg(&plugin, lmp);
}
