// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// fix ID group wall/creep E e nu mu [tier exact|spring] [creep yes|no] [velocity VX VY VZ]
//     {xplane|yplane|zplane} LO|NULL HI|NULL ...
// E Young's modulus (Pa), e restitution, nu Poisson ratio, mu friction of the sphere-wall pair
// (the wall of the same elastic material). The wall is body p of each contact. With
// `velocity VX VY VZ` (m/s) all walls of the fix move rigidly: a wall given at position LO is at
// LO + V_axis dt (step - step0) at a step (step0: the step the fix was defined at, kept in
// restart files; constant dt), and the law sees the full wall velocity (a tangential
// component shears without moving the plane), as creep-dem's moving plane walls (point +=
// velocity dt per step). compute_vector: the total force on each wall given (3 numbers per
// wall, in the order given, lower before upper), summed over ranks.
#include "fix_wall_creep.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <string>

using namespace LAMMPS_NS;
using namespace FixConst;

namespace {
// Keyword arguments common to the static helpers below (before the base class exists).
struct Parsed {
  int nwalls = 0;
  uint32_t tier = CREEP_LAMMPS_TIER_EXACT;
};

Parsed parse(int narg, char **arg)
{
  Parsed p;
  for (int i = 7; i < narg; i++) {
    const std::string a = arg[i];
    if (a == "tier" && i + 1 < narg) {
      p.tier = std::string(arg[i + 1]) == "spring" ? CREEP_LAMMPS_TIER_SPRING : CREEP_LAMMPS_TIER_EXACT;
      i++;
    } else if ((a == "xplane" || a == "yplane" || a == "zplane") && i + 2 < narg) {
      p.nwalls += (std::string(arg[i + 1]) != "NULL") + (std::string(arg[i + 2]) != "NULL");
      i += 2;
    }
  }
  return p;
}
}    // namespace

FixWallCreep::FixWallCreep(LAMMPS *lmp, int narg, char **arg) :
    FixCreepHistory(lmp, narg, arg, parse(narg, arg).nwalls, static_cast<int>(creep_lammps_history_len(parse(narg, arg).tier))),
    velocity{0.0, 0.0, 0.0}, time_origin(update->ntimestep), model(nullptr), force_flag(0)
{
  if (narg < 10) error->all(FLERR, "fix wall/creep: E e nu mu [tier exact|spring] [creep yes|no] xplane|yplane|zplane LO HI ...");
  CreepLammpsSettings s;
  s.young_modulus = utils::numeric(FLERR, arg[3], false, lmp);
  s.restitution = utils::numeric(FLERR, arg[4], false, lmp);
  s.poisson_ratio = utils::numeric(FLERR, arg[5], false, lmp);
  s.friction = utils::numeric(FLERR, arg[6], false, lmp);
  s.tier = CREEP_LAMMPS_TIER_EXACT;
  s.creep = 1;
  s.rolling = CREEP_LAMMPS_ROLLING_NONE;
  s.rolling_friction = 0.0;
  s.rolling_damping = 0.0;
  for (int i = 7; i < narg; i++) {
    const std::string a = arg[i];
    if (a == "tier" && i + 1 < narg) {
      const std::string v = arg[++i];
      if (v == "exact") s.tier = CREEP_LAMMPS_TIER_EXACT;
      else if (v == "spring") s.tier = CREEP_LAMMPS_TIER_SPRING;
      else error->all(FLERR, "fix wall/creep: tier must be exact or spring, not {}", v);
    } else if (a == "velocity" && i + 3 < narg) {
      for (int d = 0; d < 3; d++) velocity[d] = utils::numeric(FLERR, arg[i + 1 + d], false, lmp);
      i += 3;
    } else if (a == "creep" && i + 1 < narg) {
      s.creep = utils::logical(FLERR, arg[++i], false, lmp) ? 1 : 0;
    } else if ((a == "xplane" || a == "yplane" || a == "zplane") && i + 2 < narg) {
      const int axis = a[0] - 'x';
      for (int k = 0; k < 2; k++) {
        const std::string v = arg[i + 1 + k];
        if (v == "NULL") continue;
        planes.push_back({axis, k == 0 ? 1.0 : -1.0, utils::numeric(FLERR, v, false, lmp)});
      }
      i += 2;
    } else {
      error->all(FLERR, "fix wall/creep: unknown or incomplete keyword {}", a);
    }
  }
  if (planes.empty()) error->all(FLERR, "fix wall/creep: no wall given");
  for (double vd : velocity)
    if (!std::isfinite(vd)) error->all(FLERR, "fix wall/creep: velocity must be finite (m/s)");
  if (velocity[0] != 0.0 || velocity[1] != 0.0 || velocity[2] != 0.0) {
    time_depend = 1;       // positions follow the step count
    restart_global = 1;    // keep time_origin across restarts
  }
  char msg[512] = {0};
  model = creep_lammps_model_new(&s, msg, sizeof(msg));
  if (!model) error->all(FLERR, "fix wall/creep: {}", msg);
  vector_flag = 1;
  size_vector = 3 * static_cast<int>(planes.size());
  global_freq = 1;
  extvector = 1;
  wall_force.assign(size_vector, 0.0);
  wall_force_all.assign(size_vector, 0.0);
}

FixWallCreep::~FixWallCreep()
{
  creep_lammps_model_free(model);
}

int FixWallCreep::setmask()
{
  return POST_FORCE;
}

void FixWallCreep::init()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "fix wall/creep requires atom_style sphere");
}

void FixWallCreep::setup(int vflag)
{
  post_force(vflag);
}

void FixWallCreep::post_force(int /*vflag*/)
{
  double **x = atom->x, **v = atom->v, **f = atom->f;
  double **omega = atom->omega, **torque = atom->torque;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *mask = atom->mask;
  const int nlocal = atom->nlocal;
  const double dt = update->setupflag ? 0.0 : update->dt;    // as the pair style
  // Moving walls: displacement since the step they were defined at (constant time step).
  const double elapsed = update->dt * static_cast<double>(update->ntimestep - time_origin);

  batch.clear();
  batch_i.clear();
  batch_w.clear();
  batch_model.clear();
  batch_hist.clear();
  for (int i = 0; i < nlocal; i++) {
    if (!(mask[i] & groupbit)) continue;
    double *row = rows[i];
    const int ni = static_cast<int>(row[0]);
    for (int w = 0; w < static_cast<int>(planes.size()); w++) {
      const Plane &pl = planes[w];
      const double wall_at = pl.at + velocity[pl.axis] * elapsed;
      const double dist = pl.side * (x[i][pl.axis] - wall_at);
      if (dist >= radius[i]) continue;
      CreepLammpsWallContact c;
      for (int d = 0; d < 3; d++) {
        c.point[d] = 0.0;
        c.normal[d] = 0.0;
        c.wall_velocity[d] = velocity[d];
        c.sphere.x[d] = x[i][d];
        c.sphere.v[d] = v[i][d];
        c.sphere.omega[d] = omega[i][d];
      }
      c.point[pl.axis] = wall_at;
      c.normal[pl.axis] = pl.side;
      c.sphere.radius = radius[i];
      c.sphere.mass = rmass[i];
      batch.push_back(c);
      batch_i.push_back(i);
      batch_w.push_back(w);
      batch_model.push_back(model);
      const size_t at = batch_hist.size();
      batch_hist.resize(at + hlen);
      int found = -1;
      for (int e = 0; e < ni; e++)
        if (*tag_of(row, e) == static_cast<double>(w + 1)) {
          found = e;
          break;
        }
      if (found >= 0) std::memcpy(&batch_hist[at], hist_of(row, found), sizeof(double) * hlen);
      else std::memset(&batch_hist[at], 0, sizeof(double) * hlen);
    }
  }
  const size_t n = batch.size();
  batch_out.resize(n);
  if (n > 0) {
    char msg[512] = {0};
    const int rc = creep_lammps_compute_walls(batch_model.data(), dt, n, batch.data(), batch_hist.data(),
                                              static_cast<size_t>(hlen), batch_out.data(), msg, sizeof(msg));
    if (rc != 0) error->one(FLERR, "fix wall/creep: {}", msg);
  }
  for (auto &wf : wall_force) wf = 0.0;
  force_flag = 0;
  for (int i = 0; i < nlocal; i++) spare[i][0] = 0.0;
  for (size_t k = 0; k < n; k++) {
    const int i = batch_i[k], w = batch_w[k];
    const CreepLammpsOutput &o = batch_out[k];
    for (int d = 0; d < 3; d++) {
      f[i][d] -= o.force_p[d];
      torque[i][d] += o.torque_q[d];
      wall_force[3 * w + d] += o.force_p[d];
    }
    if (!o.touching) continue;
    double *row = spare[i];
    const int cnt = static_cast<int>(row[0]);
    *tag_of(row, cnt) = static_cast<double>(w + 1);
    std::memcpy(hist_of(row, cnt), &batch_hist[k * hlen], sizeof(double) * hlen);
    row[0] = cnt + 1;
  }
  swap_rows();
}

double FixWallCreep::compute_vector(int n)
{
  if (force_flag == 0) {
    MPI_Allreduce(wall_force.data(), wall_force_all.data(), size_vector, MPI_DOUBLE, MPI_SUM, world);
    force_flag = 1;
  }
  return wall_force_all[n];
}

// Global restart state (moving walls only): the step the walls were at their given positions.
void FixWallCreep::write_restart(FILE *fp)
{
  if (comm->me == 0) {
    double list[2] = {1.0, static_cast<double>(time_origin)};
    int size = sizeof(list);
    fwrite(&size, sizeof(int), 1, fp);
    fwrite(list, sizeof(double), 2, fp);
  }
}

void FixWallCreep::restart(char *buf)
{
  const auto *list = reinterpret_cast<const double *>(buf);
  if (static_cast<int>(list[0]) != 1) error->all(FLERR, "fix wall/creep: restart data from another version");
  time_origin = static_cast<bigint>(list[1]);
}
