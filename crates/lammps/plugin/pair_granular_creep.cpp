// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// pair_style granular/creep [tier exact|spring] [creep yes|no] [maxpartners N]
//                           [rolling none | rolling constant MU_R | rolling epsd MU_R ETA]
//                           [maxradius R]   (m: the cut-off is 2 x the largest of R, the atoms'
//                                            radii at init and fix pour/deposit's radii)
// pair_coeff I J E e nu mu          (Young's modulus (Pa), restitution, Poisson ratio, friction)
//
// Requirements (checked in init_style): atom_style sphere, comm_modify vel yes, newton off
// (for pairs: each rank then computes every owned-ghost pair itself and keeps its history
// under its owned atom, so no history has to be sent back to the ghost's owner).
//
// Contact orientation: body p is the atom with the lower tag, so the two ranks that compute an
// owned-ghost pair (newton off) evaluate it identically and keep the same history.
//
// History storage: each contact's history once, in a pool with one slot per neighbour entry,
// stepped in place by creep_lammps_compute_list (one call per step that walks the neighbour
// list itself); fix creep/history's per-atom rows are written
// from the pool only before exchange / at run end / for restarts (sync_history_rows) and read
// back after each neighbour-list build (rebuild_slots), as LAMMPS' fix neigh/history does.
// On one rank no atom leaves the process: before an exchange during a run only each
// history's slot in the pool is noted, by the tags of its atoms (save_before_exchange; the
// rows are not written), and the rebuild reorders the pool by them.
#include "pair_granular_creep.h"

#include "atom.h"
#include "comm.h"
#include "error.h"
#include "fix_creep_history.h"
#include "force.h"
#include "memory.h"
#include "modify.h"
#include "neigh_list.h"
#include "neighbor.h"
#include "update.h"
#include "utils.h"

#include <cmath>
#include <cstring>
#include <algorithm>
#include <string>

using namespace LAMMPS_NS;

static const char HISTORY_FIX_ID[] = "CREEP_HISTORY";

PairGranularCreep::PairGranularCreep(LAMMPS *lmp) :
    Pair(lmp), maxpartners(24), tier(CREEP_LAMMPS_TIER_EXACT), creep(1), rolling(CREEP_LAMMPS_ROLLING_NONE),
    rolling_friction(0.0), rolling_damping(0.0),
    models(nullptr), maxrad(0.0), fix_history(nullptr), built_nlocal(0), store(nullptr), nslots(0), rows_stale(false),
    rows_hold_refs(false), ref_maxtag(0),
    rebuilt_at(-1), maxrad_user(0.0), saved_contacts(0.0), restored_contacts(0.0), counting(false),
    dropped_total(0.0)
{
  single_enable = 0;
  restartinfo = 0;    // re-issue pair_style and pair_coeff after read_restart
  no_virial_fdotr_compute = 1;
  finitecutflag = 1;
  centroidstressflag = CENTROID_SAME;
  // compute pair granular/creep: [1] touching contacts this step, [2] histories dropped at
  // neighbour-list rebuilds during the current run (saved before and not found again after;
  // each contact counted once, on the rank that owns its lower-tag atom; summed over ranks).
  nextra = 2;
  pvector = new double[nextra];
  for (int k = 0; k < nextra; k++) pvector[k] = 0.0;
}

PairGranularCreep::~PairGranularCreep()
{
  delete[] pvector;
  creep_lammps_store_free(store);
  if (allocated) {
    const int n = atom->ntypes;
    for (int i = 1; i <= n; i++)
      for (int j = i; j <= n; j++) creep_lammps_model_free(models[i][j]);
    memory->destroy(setflag);
    memory->destroy(cutsq);
    for (int i = 0; i <= n; i++) delete[] models[i];
    delete[] models;
  }
}

void PairGranularCreep::allocate()
{
  allocated = 1;
  const int n = atom->ntypes;
  memory->create(setflag, n + 1, n + 1, "pair:setflag");
  memory->create(cutsq, n + 1, n + 1, "pair:cutsq");
  models = new CreepLammpsModel **[n + 1];
  for (int i = 0; i <= n; i++) {
    models[i] = new CreepLammpsModel *[n + 1];
    for (int j = 0; j <= n; j++) {
      models[i][j] = nullptr;
      setflag[i][j] = 0;
    }
  }
}

void PairGranularCreep::settings(int narg, char **arg)
{
  int iarg = 0;
  while (iarg < narg) {
    const std::string key = arg[iarg];
    if (key == "rolling") {
      if (iarg + 1 >= narg) error->all(FLERR, "pair_style granular/creep: rolling needs a model");
      const std::string model = arg[iarg + 1];
      if (model == "none") {
        rolling = CREEP_LAMMPS_ROLLING_NONE;
        iarg += 2;
      } else if (model == "constant" && iarg + 2 < narg) {
        rolling = CREEP_LAMMPS_ROLLING_CONSTANT;
        rolling_friction = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        iarg += 3;
      } else if (model == "epsd" && iarg + 3 < narg) {
        rolling = CREEP_LAMMPS_ROLLING_EPSD;
        rolling_friction = utils::numeric(FLERR, arg[iarg + 2], false, lmp);
        rolling_damping = utils::numeric(FLERR, arg[iarg + 3], false, lmp);
        iarg += 4;
      } else {
        error->all(FLERR, "pair_style granular/creep: rolling none | constant MU_R | epsd MU_R ETA");
      }
      continue;
    }
    if (iarg + 1 >= narg) error->all(FLERR, "pair_style granular/creep: keyword {} needs a value", key);
    const std::string val = arg[iarg + 1];
    if (key == "tier") {
      if (val == "exact") tier = CREEP_LAMMPS_TIER_EXACT;
      else if (val == "spring") tier = CREEP_LAMMPS_TIER_SPRING;
      else error->all(FLERR, "pair_style granular/creep: tier must be exact or spring, not {}", val);
    } else if (key == "creep") {
      creep = utils::logical(FLERR, val, false, lmp);
    } else if (key == "maxradius") {
      maxrad_user = utils::numeric(FLERR, val, false, lmp);
      if (!(maxrad_user > 0.0)) error->all(FLERR, "pair_style granular/creep: maxradius must be > 0 (m)");
    } else if (key == "maxpartners") {
      maxpartners = utils::inumeric(FLERR, val, false, lmp);
      if (maxpartners < 1) error->all(FLERR, "pair_style granular/creep: maxpartners must be >= 1");
    } else {
      error->all(FLERR, "pair_style granular/creep: unknown keyword {}", key);
    }
    iarg += 2;
  }
}

void PairGranularCreep::coeff(int narg, char **arg)
{
  if (narg != 6) error->all(FLERR, "pair_coeff I J E e nu mu: expected 6 arguments for granular/creep");
  if (!allocated) allocate();
  int ilo, ihi, jlo, jhi;
  utils::bounds(FLERR, arg[0], 1, atom->ntypes, ilo, ihi, error);
  utils::bounds(FLERR, arg[1], 1, atom->ntypes, jlo, jhi, error);
  CreepLammpsSettings s;
  s.young_modulus = utils::numeric(FLERR, arg[2], false, lmp);
  s.restitution = utils::numeric(FLERR, arg[3], false, lmp);
  s.poisson_ratio = utils::numeric(FLERR, arg[4], false, lmp);
  s.friction = utils::numeric(FLERR, arg[5], false, lmp);
  s.rolling = rolling;
  s.rolling_friction = rolling_friction;
  s.rolling_damping = rolling_damping;
  s.tier = tier;
  s.creep = creep ? 1 : 0;
  int count = 0;
  for (int i = ilo; i <= ihi; i++) {
    for (int j = std::max(jlo, i); j <= jhi; j++) {
      char msg[512] = {0};
      CreepLammpsModel *m = creep_lammps_model_new(&s, msg, sizeof(msg));
      if (!m) error->all(FLERR, "pair_coeff granular/creep: {}", msg);
      creep_lammps_model_free(models[i][j]);
      models[i][j] = m;
      setflag[i][j] = 1;
      count++;
    }
  }
  if (count == 0) error->all(FLERR, "Incorrect args for pair coefficients");
}

void PairGranularCreep::init_style()
{
  if (!atom->radius_flag || !atom->rmass_flag || !atom->omega_flag || !atom->torque_flag)
    error->all(FLERR, "pair granular/creep requires atom_style sphere (radius, rmass, omega, torque)");
  if (comm->ghost_velocity == 0) error->all(FLERR, "pair granular/creep requires comm_modify vel yes");
  if (force->newton_pair) error->all(FLERR, "pair granular/creep requires newton off (for pairs)");

  // Inside pair_style hybrid: one instance only (its contact histories live in the one per-atom
  // fix CREEP_HISTORY, which finds the pair by its style name).
  if (force->pair_match("granular/creep", 1) != this)
    error->all(FLERR, "pair granular/creep: pair_style hybrid may hold granular/creep once only (its contact "
                      "histories are kept in one per-atom store); give all its type pairs to that one instance");

  neighbor->add_request(this, NeighConst::REQ_SIZE);

  const int hlen = static_cast<int>(creep_lammps_history_len(tier));
  if (rows_stale)    // post_run / write_restart save them; a new init must not lose them
    error->all(FLERR, "pair granular/creep: contact histories not saved before a new init");
  creep_lammps_store_free(store);    // the rows hold every history now (post_run synced them)
  store = creep_lammps_store_new(tier);
  if (!store) error->all(FLERR, "pair granular/creep: could not create the history store");
  nslots = 0;
  slot.clear();
  slot_first.clear();
  dropped_total = 0.0;

  // The model of each pair of types, symmetric, for the law's lookup (null: no pair_coeff,
  // e.g. pairs that pair_style hybrid gives to another style).
  const int nt = atom->ntypes;
  model_table.assign(static_cast<size_t>(nt + 1) * (nt + 1), nullptr);
  for (int i = 1; i <= nt; i++)
    for (int j = 1; j <= nt; j++) model_table[i * (nt + 1) + j] = i <= j ? models[i][j] : models[j][i];
  fix_history = dynamic_cast<FixCreepHistory *>(modify->get_fix_by_id(HISTORY_FIX_ID));
  if (!fix_history) {
    fix_history = dynamic_cast<FixCreepHistory *>(modify->add_fix(
        fmt::format("{} all creep/history {} {}", HISTORY_FIX_ID, maxpartners, hlen)));
    if (!fix_history) error->all(FLERR, "pair granular/creep: could not create fix creep/history");
  }
  if (fix_history->hlen != hlen || fix_history->maxpartners != maxpartners)
    error->all(FLERR, "pair granular/creep: fix {} has maxpartners {} hlen {}, need {} {}", HISTORY_FIX_ID,
               fix_history->maxpartners, fix_history->hlen, maxpartners, hlen);

  // The cut-off (2 maxrad): the largest radius of the atoms now, of what fix pour / deposit
  // will insert (their extract("radius")), and of pair_style ... maxradius R. Recomputed at
  // every run's init; an atom larger than that appearing during a run is an error (compute).
  double mine = maxrad_user;
  for (int i = 0; i < atom->nlocal; i++) mine = std::max(mine, atom->radius[i]);
  for (const char *style : {"^pour", "^deposit"})
    for (auto *ifix : modify->get_fix_by_style(style))
      for (int t = 1; t <= atom->ntypes; t++) {
        int itype = t;    // in: the type; the fix answers with its largest radius for it
        if (auto *r = static_cast<double *>(ifix->extract("radius", itype))) mine = std::max(mine, *r);
      }
  MPI_Allreduce(&mine, &maxrad, 1, MPI_DOUBLE, MPI_MAX, world);
  if (!(maxrad > 0.0))
    error->all(FLERR, "pair granular/creep: no atoms and no pair_style ... maxradius R to size the cut-off");

}

double PairGranularCreep::init_one(int i, int j)
{
  if (setflag[i][j] == 0) {
    if (setflag[j][i] == 0 && !(i > j && setflag[j][i]))
      error->all(FLERR, "pair granular/creep: pair_coeff {} {} not set", i, j);
  }
  // Cut-off: the largest contact distance (sizes set the real one per pair).
  return 2.0 * maxrad;
}

// Reads the per-atom rows into one slot per neighbour entry that has a history, in the
// neighbour list's order (so the store is also compacted: contacts that opened since the last
// build are gone), and hands them to the law's store in one call. Runs after each
// neighbour-list build, when the rows are current.
void PairGranularCreep::rebuild_slots(bool refs)
{
  const int hlen = fix_history->hlen;
  double **rows = fix_history->rows;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  slot_first.resize(inum + 1);
  int total = 0;
  for (int ii = 0; ii < inum; ii++) {
    slot_first[ii] = total;
    total += numneigh[ilist[ii]];
  }
  slot_first[inum] = total;
  slot.assign(total, -1);
  swap.resize(total);
  partner_tag.resize(total);
  built_nlocal = nlocal;
  nslots = 0;
  stage.clear();
  from.clear();
  double restored = 0.0;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const tagint tj = tag[jlist[jj] & NEIGHMASK];
      partner_tag[slot_first[ii] + jj] = tj;
      swap[slot_first[ii] + jj] = tag[i] > tj ? 1 : 0;    // body p is the lower tag
    }
    if (refs) {    // atom i's references: ref_tag/ref_slot[ref_first[tag] .. ref_first[tag + 1])
      const tagint ti = tag[i];
      if (ti < 1 || ti > ref_maxtag) continue;
      const int r0 = ref_first[ti], r1 = ref_first[ti + 1];
      for (int jj = 0; jj < numneigh[i]; jj++) {
        const int j = jlist[jj] & NEIGHMASK;
        const tagint partner = tag[j];
        for (int r = r0; r < r1; r++)
          if (ref_tag[r] == partner) {
            from.push_back(ref_slot[r]);
            slot[slot_first[ii] + jj] = nslots++;
            if ((tag[i] < tag[j] ? i : j) < nlocal) restored += 1.0;
            break;
          }
      }
      continue;
    }
    double *rowi = rows[i];
    const int ni = static_cast<int>(rowi[0]);
    if (ni == 0) continue;
    const double *tagsi = FixCreepHistory::tag_of(rowi, 0);
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int j = jlist[jj] & NEIGHMASK;
      const double partner = static_cast<double>(tag[j]);
      for (int e = 0; e < ni; e++)
        if (tagsi[e] == partner) {
          const double *h = fix_history->hist_of(rowi, e);
          stage.insert(stage.end(), h, h + hlen);
          slot[slot_first[ii] + jj] = nslots++;
          if ((tag[i] < tag[j] ? i : j) < nlocal) restored += 1.0;
          break;
        }
    }
  }
  char msg[512] = {0};
  if (refs) {
    if (creep_lammps_store_remap(store, static_cast<size_t>(nslots), from.data(), msg, sizeof(msg)) != 0)
      error->one(FLERR, "pair granular/creep: reordering the contact histories: {}", msg);
  } else if (creep_lammps_store_load(store, static_cast<size_t>(nslots), stage.data(), static_cast<size_t>(hlen), msg,
                                     sizeof(msg)) != 0) {
    error->one(FLERR, "pair granular/creep: reading the contact histories back: {}", msg);
  }
  if (counting) dropped_total += saved_contacts - restored;
  counting = false;
}

// Writes every live contact's history into the rows of its owned atoms (both, for a pair of
// owned atoms, so that either may migrate), keyed by the partner's tag. Only when the store is
// newer than the rows. The owned atoms must still be those the slots were built for (true
// before exchange, at the end of a run, when a restart is written); ghosts need not be: a fix
// that inserts atoms in pre_exchange before this one (fix deposit, fix pour) writes the new
// atom over the first ghost, so the partners' tags and the owned count are those recorded at
// the neighbour-list build, not the arrays' current ones.
void PairGranularCreep::sync_history_rows()
{
  if (!rows_stale || !fix_history || !list || !store) return;
  // Between a one-rank exchange and the rebuild that follows it the list no longer matches
  // the atoms; nothing asks for the rows then.
  if (rows_hold_refs)
    error->one(FLERR, "pair granular/creep: contact histories requested between an exchange and the rebuild");
  write_rows();
}

// Before an exchange during a run: on one rank each history's slot in the store, by the
// tags of its atoms (write_refs; the histories stay in the store and rebuild_slots(true)
// reorders it), otherwise the histories into the rows.
void PairGranularCreep::save_before_exchange()
{
  if (!rows_stale || !fix_history || !list || !store) return;
  if (comm->nprocs == 1 && !update->setupflag) {
    write_refs();
    rows_hold_refs = true;    // rows_stale stays: the rows are not written
  } else {
    sync_history_rows();
  }
}

// The neighbour list's live contacts (the header's declaration says what visit gets).
template <class Visit> void PairGranularCreep::each_live_contact(Visit &&visit) const
{
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;
  for (int ii = 0; ii < inum; ii++) {
    const int i = ilist[ii];
    const int *jlist = firstneigh[i];
    for (int jj = 0; jj < numneigh[i]; jj++) {
      const int e = slot_first[ii] + jj;
      const int s = slot[e];
      if (s < 0) continue;
      visit(i, jlist[jj] & NEIGHMASK, partner_tag[e], s);
    }
  }
}

// One rank, before an exchange: every live contact's slot under the tag of each of its atoms
// owned at the build, with the partner's tag, in the order write_rows would put them into
// the rows (so that rebuild_slots finds the same first match); bucketed by tag (a counting
// sort over ref_first, tags 1 .. ref_maxtag) instead of the per-atom rows, which are
// scattered over memory and which LAMMPS would then carry through the exchange and sort.
void PairGranularCreep::write_refs()
{
  const tagint *tag = atom->tag;
  const int nlocal = built_nlocal;
  tagint maxtag = 0;
  for (int ii = 0; ii < list->inum; ii++) maxtag = std::max(maxtag, tag[list->ilist[ii]]);
  for (const tagint t : partner_tag) maxtag = std::max(maxtag, t);
  ref_maxtag = maxtag;
  ref_first.assign(static_cast<size_t>(maxtag) + 2, 0);
  // Each stored reference (tag_a, tag_b, slot s), as write_rows stores histories: under each
  // owned atom of the contact, atom i's first.
  auto each = [&](auto &&visit) {
    each_live_contact([&](int i, int j, tagint tag_j, int s) {
      if (i < nlocal) visit(tag[i], tag_j, s);
      if (j < nlocal) visit(tag_j, tag[i], s);
    });
  };
  double saved = 0.0;
  each_live_contact([&](int i, int j, tagint tag_j, int) {
    if ((tag[i] < tag_j ? i : j) < nlocal) saved += 1.0;
  });
  each([&](tagint tag_a, tagint, int) {
    if (++ref_first[tag_a + 1] > maxpartners)
      error->one(FLERR, "pair granular/creep: atom {} has more than {} contacts (pair_style maxpartners N)",
                 tag_a, maxpartners);
  });
  for (size_t t = 1; t < ref_first.size(); t++) ref_first[t] += ref_first[t - 1];
  ref_tag.resize(ref_first.back());
  ref_slot.resize(ref_first.back());
  ref_next.assign(ref_first.begin(), ref_first.end() - 1);
  each([&](tagint tag_a, tagint tag_b, int s) {
    const int r = ref_next[tag_a]++;
    ref_tag[r] = tag_b;
    ref_slot[r] = s;
  });
  saved_contacts = saved;
  counting = true;
}

// The rows from the store: each live contact's history under both owned atoms, keyed by the
// partner's tag.
void PairGranularCreep::write_rows()
{
  const int hlen = fix_history->hlen;
  double **rows = fix_history->rows;
  const tagint *tag = atom->tag;
  const int nlocal = built_nlocal;
  stage.resize(static_cast<size_t>(nslots) * hlen);
  char msg[512] = {0};
  if (creep_lammps_store_save(store, stage.data(), stage.size(), static_cast<size_t>(hlen), msg, sizeof(msg)) != 0)
    error->one(FLERR, "pair granular/creep: saving the contact histories: {}", msg);
  double saved = 0.0;
  for (int i = 0; i < atom->nlocal; i++) rows[i][0] = 0.0;
  each_live_contact([&](int i, int j, tagint tag_j, int s) {
    const double *h = &stage[static_cast<size_t>(s) * hlen];
    if ((tag[i] < tag_j ? i : j) < nlocal) saved += 1.0;
    for (int side = 0; side < 2; side++) {
      const int a = side == 0 ? i : j;
      const tagint tag_a = side == 0 ? tag[i] : tag_j, tag_b = side == 0 ? tag_j : tag[i];
      if (a >= nlocal) continue;
      double *row = rows[a];
      const int cnt = static_cast<int>(row[0]);
      if (cnt >= maxpartners)
        error->one(FLERR, "pair granular/creep: atom {} has more than {} contacts (pair_style maxpartners N)",
                   tag_a, maxpartners);
      *FixCreepHistory::tag_of(row, cnt) = static_cast<double>(tag_b);
      std::memcpy(fix_history->hist_of(row, cnt), h, sizeof(double) * hlen);
      row[0] = cnt + 1;
    }
  });
  saved_contacts = saved;
  counting = true;
  rows_stale = false;
}

void PairGranularCreep::compute(int eflag, int vflag)
{
  ev_init(eflag, vflag);

  double **x = atom->x, **v = atom->v, **f = atom->f;
  double **omega = atom->omega, **torque = atom->torque;
  const double *radius = atom->radius, *rmass = atom->rmass;
  const int *type = atom->type;
  const tagint *tag = atom->tag;
  const int nlocal = atom->nlocal;
  // Set-up forces (start of a run) see no displacement: dt = 0, as creep-dem's initial forces.
  // Their history update only sets the contact's basis and radius (an identity for a contact
  // that was stepped before), so `run N; run M` and a restart continue alike.
  const double dt = update->setupflag ? 0.0 : update->dt;
  const int inum = list->inum;
  const int *ilist = list->ilist, *numneigh = list->numneigh;
  int **firstneigh = list->firstneigh;

  // 0. After a neighbour-list build: the histories from the rows into the slots. (Set-up
  // always rebuilds, harmless when the list did not change: the rows were synced at the end
  // of the previous run.)
  if (neighbor->ago == 0 && (update->setupflag || update->ntimestep != rebuilt_at)) {
    const bool refs = rows_hold_refs && !update->setupflag;
    if (rows_stale && !refs)
      error->one(FLERR, "pair granular/creep: neighbour lists were rebuilt without the contact histories "
                        "being saved first (a rebuild outside the pre-exchange path?)");
    rebuild_slots(refs);
    rows_hold_refs = false;
    if (!update->setupflag) rebuilt_at = update->ntimestep;
  }
  // A sphere larger than the cut-off was made for (created or grown during the run by a fix
  // other than pour/deposit) would miss contacts: stop instead. One compare per owned atom.
  for (int i = 0; i < nlocal; i++)
    if (radius[i] > maxrad)
      error->one(FLERR, "pair granular/creep: atom {} has radius {} m, larger than the {} m the neighbour "
                 "cut-off was set up for (pair_style granular/creep maxradius R)", tag[i], radius[i], maxrad);

  // 1. One call into the law over the whole neighbour list: it finds the touching pairs (body
  // p the lower tag, per swap[]), keeps each history where it is (slot[]: a new contact gets a
  // new, virgin slot, a pair found apart -1, its slot reclaimed at the next build), steps them
  // in place in its store and adds the forces and torques of the owned atoms.
  const int nall = nlocal + atom->nghost;
  CreepLammpsAtoms at;
  at.nlocal = static_cast<size_t>(nlocal);
  at.nall = static_cast<size_t>(nall);
  at.x = nall ? x[0] : nullptr;
  at.v = nall ? v[0] : nullptr;
  at.omega = nall ? omega[0] : nullptr;
  at.radius = radius;
  at.rmass = rmass;
  at.type_ = type;
  at.f = nlocal ? f[0] : nullptr;
  at.torque = nlocal ? torque[0] : nullptr;
  CreepLammpsList nl;
  nl.inum = static_cast<size_t>(inum);
  nl.ilist = ilist;
  nl.numneigh = numneigh;
  nl.firstneigh = firstneigh;
  nl.maxatom = static_cast<size_t>(list->maxatom);
  nl.neighmask = NEIGHMASK;
  nl.nentries = slot.size();
  nl.slot = slot.data();
  nl.swap = swap.data();
  // The contacts' forces only on the steps that tally the virial (sized once per build).
  if (evflag && virial.size() < slot.size()) virial.resize(slot.size());
  CreepLammpsCounts counts;
  char msg[512] = {0};
  const int rc = creep_lammps_compute_list(model_table.data(), static_cast<size_t>(atom->ntypes), store, &at, &nl,
                                           dt, evflag ? virial.data() : nullptr, &counts, msg, sizeof(msg));
  if (rc != 0) error->one(FLERR, "pair granular/creep: {}", msg);
  nslots = static_cast<int>(counts.nslots);
  rows_stale = true;

  // 2. The virial (on the steps that ask for it; symmetric in p and q).
  if (evflag)
    for (size_t k = 0; k < counts.contacts; k++) {
      const CreepLammpsPairForce &c = virial[k];
      const int p = c.p, q = c.q;
      ev_tally_xyz(p, q, nlocal, 0, 0.0, 0.0, c.force_p[0], c.force_p[1], c.force_p[2], x[p][0] - x[q][0],
                   x[p][1] - x[q][1], x[p][2] - x[q][2]);
    }
  const double touching_here = static_cast<double>(counts.owned_contacts);
  pvector[0] = touching_here;
  pvector[1] = dropped_total;
}
