// creep-lammps plugin shim - GPL-2.0-only (see LICENSE-NOTE.md in this directory).
//
// The LAMMPS plugin interface, declared from its documentation (LAMMPS manual, "Writing
// plugins", Developer_plugins): LAMMPS dlopen()s the plugin and calls its C function
// `lammpsplugin_init(lmp, handle, regfunc)`, which hands one descriptor per style to `regfunc`.
// The PyPI wheel ships no lammpsplugin.h, so this is our own declaration of that documented
// struct (no LAMMPS source copied).
#ifndef CREEP_LAMMPSPLUGIN_DECL_H
#define CREEP_LAMMPSPLUGIN_DECL_H

extern "C" {
// Factory of a pair style (and other one-argument styles): `new Style(lmp)`.
typedef void *(creep_lammpsplugin_factory1)(void *lmp);
// Factory of a fix or compute: `new Style(lmp, narg, arg)`.
typedef void *(creep_lammpsplugin_factory2)(void *lmp, int narg, char **arg);

typedef struct {
  const char *version;    // LAMMPS version the plugin was built for
  const char *style;      // "pair", "fix", ...
  const char *name;       // style name in input scripts
  const char *info;       // one line shown by `plugin list`
  const char *author;
  union {
    creep_lammpsplugin_factory1 *v1;
    creep_lammpsplugin_factory2 *v2;
  } creator;
  void *handle;    // dlopen() handle, passed through
} creep_lammpsplugin_t;

typedef void (*creep_lammpsplugin_regfunc)(creep_lammpsplugin_t *, void *lmp);
}

#endif
