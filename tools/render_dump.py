#!/usr/bin/env python3
"""Render one frame of creep-dem's snapshots to PNG with OVITO (PyPI's `ovito` module).

    pip install ovito
    creep triaxial --quick --dump snaps
    python3 tools/render_dump.py snaps/shear_creep --out triaxial_frame.png

Reads the particle dump series `DIR/particles.*.dump` (LAMMPS `dump custom` text, written by
creep-dem's `dump` module) and, unless `--no-contacts`, the contact dump of the same step
`DIR/contacts.<step>.dump` (LAMMPS `dump local`) as bonds between the two particles: the force
chains, coloured and sized by the normal force `fn`. Particles are coloured by their count of
sliding contacts (or `--color PROPERTY`, any column of the particle dump). Renders with OVITO's
software renderer (Tachyon: no display or GPU needed). Not part of CI.
"""
import argparse
import glob
import os
import sys

import numpy as np

from ovito.io import import_file
from ovito.modifiers import (ColorCodingModifier, LoadTrajectoryModifier,
                             SliceModifier)
from ovito.vis import TachyonRenderer, Viewport

# The contact dump's columns (id1 id2 cx cy cz nx ny nz fn ftx fty ftz state) as bond
# properties: the two ids make the bond, the rest are scalar bond properties of the same names.
CONTACT_COLUMNS = ["Particle Identifiers.1", "Particle Identifiers.2",
                   "cx", "cy", "cz", "nx", "ny", "nz", "fn", "ftx", "fty", "ftz", "state"]


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("dir", help="a directory of particles.*.dump (and contacts.*.dump)")
    ap.add_argument("--out", default="frame.png", help="PNG to write")
    ap.add_argument("--frame", type=int, default=-1,
                    help="frame index in the series (default: the last)")
    ap.add_argument("--color", default="sliding", help="particle property to colour by")
    ap.add_argument("--no-contacts", action="store_true", help="particles only")
    ap.add_argument("--chains", action="store_true",
                    help="draw the particles at a quarter of their radius, to see the force chains")
    ap.add_argument("--slice", action="store_true",
                    help="cut the packing in half (x normal) to show the interior")
    ap.add_argument("--size", default="1000x800", help="image size WxH")
    a = ap.parse_args()

    files = sorted(glob.glob(os.path.join(a.dir, "particles.*.dump")))
    if not files:
        sys.exit(f"no particles.*.dump in {a.dir}")
    pipeline = import_file(os.path.join(a.dir, "particles.*.dump"))
    n = pipeline.source.num_frames
    frame = a.frame % n
    step = os.path.basename(files[frame]).split(".")[1]
    contacts = os.path.join(a.dir, f"contacts.{step}.dump")
    if not a.no_contacts and os.path.exists(contacts):
        bonds = LoadTrajectoryModifier()
        bonds.source.load(contacts, columns=CONTACT_COLUMNS)
        pipeline.modifiers.append(bonds)
        pipeline.modifiers.append(ColorCodingModifier(
            operate_on="bonds", property="fn", gradient=ColorCodingModifier.Hot()))

        def force_chain_widths(frame, data):
            """Bond width in proportion to the normal force (0.05 to 0.65 mean radius)."""
            if data.particles.bonds is None or data.particles.bonds.count == 0:
                return
            fn = np.asarray(data.particles.bonds["fn"])
            r = float(np.mean(np.asarray(data.particles["Radius"])))
            width = r * (0.05 + 0.6 * fn / max(float(fn.max()), 1e-300))
            data.particles_.bonds_.create_property("Width", data=width)

        pipeline.modifiers.append(force_chain_widths)
    if a.slice:
        pipeline.modifiers.append(SliceModifier(normal=(1, 0, 0), distance=0.0,
                                                slab_width=0.0, only_selected=False))
    pipeline.modifiers.append(ColorCodingModifier(
        property=a.color, gradient=ColorCodingModifier.Viridis()))
    if a.chains:
        def shrink(frame, data):
            """Particles at a quarter of their radius (drawing only)."""
            data.particles_["Radius_"][:] *= 0.25

        pipeline.modifiers.append(shrink)
    data = pipeline.compute(frame)
    print(f"{files[frame]}: {data.particles.count} particles"
          + (f", {data.particles.bonds.count} contacts" if data.particles.bonds else ""))
    pipeline.add_to_scene()
    vp = Viewport(type=Viewport.Type.Perspective, camera_dir=(-1.0, 0.6, -0.5),
                  camera_up=(0, 1, 0))
    vp.zoom_all()
    w, h = (int(x) for x in a.size.split("x"))
    vp.render_image(filename=a.out, size=(w, h), frame=frame,
                    renderer=TachyonRenderer(), background=(1, 1, 1))
    print(f"wrote {a.out}")


if __name__ == "__main__":
    main()
