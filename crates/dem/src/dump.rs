//! Snapshots for visualisers: LAMMPS-style text dumps (OVITO, ParaView) and VTK XML PolyData
//! (`.vtp`, ParaView), of the particles and of the particle-particle contacts (force chains).
//!
//! # Particle dump (`dump custom` of LAMMPS)
//! ```text
//! ITEM: TIMESTEP
//! 1200
//! ITEM: NUMBER OF ATOMS
//! 343
//! ITEM: BOX BOUNDS ss ss ss
//! xlo xhi
//! ylo yhi
//! zlo zhi
//! ITEM: ATOMS id type radius x y z vx vy vz omegax omegay omegaz fx fy fz contacts sticking creeping sliding
//! 1 1 1.2e-3 ...
//! ```
//! One line per particle, by id. LAMMPS numbers atoms and types from 1: `id` is creep-dem's
//! particle id + 1, `type` its material id + 1. `contacts` counts the particle's touching
//! contacts (particles and walls), of which `sticking`, `creeping` (a creep displacement in
//! the step, not sliding) and `sliding` (at the Coulomb limit). Box bounds: the periodic box
//! on periodic axes (`pp`), else the particles' extent (`ss`, LAMMPS' shrink-wrapped).
//! SI units: m, m/s, rad/s, N.
//!
//! # Contact dump (`dump local` of LAMMPS)
//! ```text
//! ITEM: TIMESTEP
//! 1200
//! ITEM: NUMBER OF ENTRIES
//! 612
//! ITEM: BOX BOUNDS ss ss ss
//! ...
//! ITEM: ENTRIES id1 id2 cx cy cz nx ny nz fn ftx fty ftz state
//! ```
//! One line per touching particle-particle contact: the two particle ids (LAMMPS' numbering,
//! `id1 < id2`), the contact point, the unit normal from `id1` to `id2`, the normal force on
//! `id2` (>= 0, damping included) and the tangential force on `id1` \[N\], and the state (`0`
//! sticking, `1` creeping, `2` sliding). Contacts with walls are not in it (their forces are
//! the walls' reactions).
//!
//! # The state of a contact
//! Forces are those the contacts carry now (creep-dem's `for_each_contact_force` with
//! `dt = 0`); the state is that of one more step at the current velocities on a copy of the
//! history (`dt` the engine's step), as the engine's [`DemCounts`](crate::DemCounts) count
//! them.

use std::collections::HashMap;
use std::fmt::Write as _;
use std::io::Write;
use std::path::{Path, PathBuf};

use creep_law::Vec3;
use creep_law::pair::TangentialLaw;

use crate::{ContactForce, Dem};

/// Contact state of the dumps: at neither limit.
pub const STICKING: u8 = 0;
/// Contact state of the dumps: a creep displacement in the step, not at the Coulomb limit.
pub const CREEPING: u8 = 1;
/// Contact state of the dumps: at the Coulomb limit.
pub const SLIDING: u8 = 2;

/// The columns of the particle dump, in order.
pub const PARTICLE_COLUMNS: &str = "id type radius x y z vx vy vz omegax omegay omegaz fx fy fz contacts sticking creeping sliding";
/// The columns of the contact dump, in order.
pub const CONTACT_COLUMNS: &str = "id1 id2 cx cy cz nx ny nz fn ftx fty ftz state";

/// Errors of the snapshot writer and reader.
#[derive(Debug, thiserror::Error)]
pub enum DumpError {
    /// Writing or reading a file failed.
    #[error("{path}: {source}")]
    Io {
        /// The file.
        path: PathBuf,
        /// What went wrong.
        source: std::io::Error,
    },
    /// A dump's text is not of the form written here.
    #[error("dump line {line}: {why}")]
    Format {
        /// 1-based line number.
        line: usize,
        /// What was expected.
        why: String,
    },
    /// An invalid setting.
    #[error("{0}")]
    Setting(&'static str),
}

/// One touching particle-particle contact of a snapshot.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DumpContact {
    /// Particle ids (creep-dem's, from 0), `p < q`.
    pub p: usize,
    /// See `p`.
    pub q: usize,
    /// Contact point \[m\].
    pub point: Vec3,
    /// Unit normal from p to q [-].
    pub normal: Vec3,
    /// Normal force on q \[N\] (>= 0).
    pub normal_force: f64,
    /// Tangential force on p \[N\].
    pub tangential_force: Vec3,
    /// [`STICKING`], [`CREEPING`] or [`SLIDING`].
    pub state: u8,
}

/// A contact's key in [`Dem::for_each_contact_force`]'s reports: `(p, wall, q)`.
type Key = (Option<usize>, Option<usize>, usize);

fn state_of(c: &ContactForce) -> u8 {
    if c.forces.sliding {
        SLIDING
    } else if c.forces.creep_displacement != creep_law::Vec2::ZERO {
        CREEPING
    } else {
        STICKING
    }
}

impl<T: TangentialLaw> Dem<T> {
    /// The touching particle-particle contacts as the dumps write them, and per particle id
    /// the counts `[sticking, creeping, sliding]` of all its touching contacts (walls too).
    pub fn snapshot_contacts(&self) -> (Vec<DumpContact>, Vec<[u32; 3]>) {
        let mut states: HashMap<Key, u8> = HashMap::new();
        self.for_each_contact_force(self.config().dt, |c| {
            states.insert((c.p, c.wall, c.q), state_of(&c));
        });
        let mut counts = vec![[0u32; 3]; self.len()];
        let mut out = Vec::new();
        self.for_each_contact_force(0.0, |c| {
            let state = states.get(&(c.p, c.wall, c.q)).copied().unwrap_or(STICKING);
            counts[c.q][state as usize] += 1;
            if let Some(p) = c.p {
                counts[p][state as usize] += 1;
                let normal = (c.x_q - c.x_p).try_normalize().unwrap_or(Vec3::ZERO);
                out.push(DumpContact {
                    p,
                    q: c.q,
                    point: c.forces.point,
                    normal,
                    normal_force: c.forces.normal_force,
                    tangential_force: c.forces.tangential_force,
                    state,
                });
            }
        });
        (out, counts)
    }

    /// The box of the dumps: `(bounds, flags)` per axis.
    fn dump_box(&self) -> ([(f64, f64); 3], [&'static str; 3]) {
        let mut b = [(f64::INFINITY, f64::NEG_INFINITY); 3];
        for (x, r) in self.positions().iter().zip(self.radii()) {
            for (a, v) in [x.x, x.y, x.z].into_iter().enumerate() {
                b[a].0 = b[a].0.min(v - r);
                b[a].1 = b[a].1.max(v + r);
            }
        }
        let mut flags = ["ss"; 3];
        for a in 0..3 {
            if let Some(p) = self.config().periodic[a] {
                b[a] = p;
                flags[a] = "pp";
            } else if !(b[a].0 <= b[a].1) {
                b[a] = (0.0, 0.0);
            }
        }
        (b, flags)
    }

    /// Writes the particle dump of the module docs, with `timestep` the step number.
    pub fn write_particle_dump(&self, timestep: u64, w: &mut dyn Write) -> std::io::Result<()> {
        let (_, counts) = self.snapshot_contacts();
        self.write_particle_dump_with(timestep, &counts, w)
    }

    fn write_particle_dump_with(
        &self,
        timestep: u64,
        counts: &[[u32; 3]],
        w: &mut dyn Write,
    ) -> std::io::Result<()> {
        let mut s = String::with_capacity(200 * self.len() + 300);
        header(
            &mut s,
            timestep,
            self.time(),
            "NUMBER OF ATOMS",
            self.len(),
            self.dump_box(),
        );
        let _ = writeln!(s, "ITEM: ATOMS {PARTICLE_COLUMNS}");
        for id in 0..self.len() {
            let p = self.particle(id);
            let i = self.index_of(id);
            let f = self.particle_forces()[i];
            let c = counts[id];
            let _ = write!(s, "{} {} {:e}", id + 1, p.material + 1, p.radius);
            for v in [p.position, p.velocity, p.angular_velocity, f] {
                let _ = write!(s, " {:e} {:e} {:e}", v.x, v.y, v.z);
            }
            let _ = writeln!(s, " {} {} {} {}", c[0] + c[1] + c[2], c[0], c[1], c[2]);
        }
        w.write_all(s.as_bytes())
    }

    /// Writes the contact dump of the module docs, with `timestep` the step number.
    pub fn write_contact_dump(&self, timestep: u64, w: &mut dyn Write) -> std::io::Result<()> {
        let (contacts, _) = self.snapshot_contacts();
        self.write_contact_dump_with(timestep, &contacts, w)
    }

    fn write_contact_dump_with(
        &self,
        timestep: u64,
        contacts: &[DumpContact],
        w: &mut dyn Write,
    ) -> std::io::Result<()> {
        let mut s = String::with_capacity(200 * contacts.len() + 300);
        header(
            &mut s,
            timestep,
            self.time(),
            "NUMBER OF ENTRIES",
            contacts.len(),
            self.dump_box(),
        );
        let _ = writeln!(s, "ITEM: ENTRIES {CONTACT_COLUMNS}");
        for c in contacts {
            let _ = write!(s, "{} {}", c.p + 1, c.q + 1);
            for v in [c.point, c.normal] {
                let _ = write!(s, " {:e} {:e} {:e}", v.x, v.y, v.z);
            }
            let t = c.tangential_force;
            let _ = writeln!(
                s,
                " {:e} {:e} {:e} {:e} {}",
                c.normal_force, t.x, t.y, t.z, c.state
            );
        }
        w.write_all(s.as_bytes())
    }

    /// Writes the particles as VTK XML PolyData (ASCII `.vtp`, ParaView): one vertex per
    /// particle (by id) with the point data of the particle dump's columns.
    fn write_particle_vtp(&self, counts: &[[u32; 3]], w: &mut dyn Write) -> std::io::Result<()> {
        let n = self.len();
        let parts: Vec<_> = (0..n).map(|id| self.particle(id)).collect();
        let forces: Vec<Vec3> = (0..n)
            .map(|id| self.particle_forces()[self.index_of(id)])
            .collect();
        let mut s = String::with_capacity(250 * n + 2000);
        vtp_open(&mut s, n, n, 0);
        s.push_str("<Points>\n");
        vec_array(&mut s, "Points", parts.iter().map(|p| p.position));
        s.push_str("</Points>\n<PointData Scalars=\"radius\" Vectors=\"velocity\">\n");
        int_array(&mut s, "id", (0..n).map(|i| i as i64 + 1));
        int_array(&mut s, "type", parts.iter().map(|p| p.material as i64 + 1));
        f_array(&mut s, "radius", parts.iter().map(|p| p.radius));
        vec_array(&mut s, "velocity", parts.iter().map(|p| p.velocity));
        vec_array(
            &mut s,
            "angular_velocity",
            parts.iter().map(|p| p.angular_velocity),
        );
        vec_array(&mut s, "force", forces.iter().copied());
        int_array(
            &mut s,
            "contacts",
            counts.iter().map(|c| i64::from(c[0] + c[1] + c[2])),
        );
        for (k, name) in ["sticking", "creeping", "sliding"].into_iter().enumerate() {
            int_array(&mut s, name, counts.iter().map(|c| i64::from(c[k])));
        }
        s.push_str("</PointData>\n<Verts>\n");
        int_array(&mut s, "connectivity", 0..n as i64);
        int_array(&mut s, "offsets", 1..=n as i64);
        s.push_str("</Verts>\n");
        vtp_close(&mut s);
        w.write_all(s.as_bytes())
    }

    /// Writes the contacts as VTK XML PolyData (ParaView): one line per contact between the
    /// two centres, with the contact dump's columns as cell data (force chains: colour the
    /// lines by `fn`).
    fn write_contact_vtp(
        &self,
        contacts: &[DumpContact],
        w: &mut dyn Write,
    ) -> std::io::Result<()> {
        let n = self.len();
        let m = contacts.len();
        let mut s = String::with_capacity(300 * m + 60 * n + 2000);
        vtp_open(&mut s, n, 0, m);
        s.push_str("<Points>\n");
        vec_array(
            &mut s,
            "Points",
            (0..n).map(|id| self.particle(id).position),
        );
        s.push_str("</Points>\n<CellData Scalars=\"fn\">\n");
        int_array(&mut s, "id1", contacts.iter().map(|c| c.p as i64 + 1));
        int_array(&mut s, "id2", contacts.iter().map(|c| c.q as i64 + 1));
        vec_array(&mut s, "point", contacts.iter().map(|c| c.point));
        vec_array(&mut s, "normal", contacts.iter().map(|c| c.normal));
        f_array(&mut s, "fn", contacts.iter().map(|c| c.normal_force));
        vec_array(&mut s, "ft", contacts.iter().map(|c| c.tangential_force));
        int_array(&mut s, "state", contacts.iter().map(|c| i64::from(c.state)));
        s.push_str("</CellData>\n<Lines>\n");
        int_array(
            &mut s,
            "connectivity",
            contacts.iter().flat_map(|c| [c.p as i64, c.q as i64]),
        );
        int_array(&mut s, "offsets", (1..=m as i64).map(|i| 2 * i));
        s.push_str("</Lines>\n");
        vtp_close(&mut s);
        w.write_all(s.as_bytes())
    }
}

fn header(
    s: &mut String,
    timestep: u64,
    time: f64,
    what: &str,
    n: usize,
    (b, flags): ([(f64, f64); 3], [&str; 3]),
) {
    let _ = writeln!(s, "ITEM: TIMESTEP\n{timestep}\nITEM: TIME\n{time:e}");
    let _ = writeln!(s, "ITEM: {what}\n{n}");
    let _ = writeln!(s, "ITEM: BOX BOUNDS {} {} {}", flags[0], flags[1], flags[2]);
    for (lo, hi) in b {
        let _ = writeln!(s, "{lo:e} {hi:e}");
    }
}

fn vtp_open(s: &mut String, points: usize, verts: usize, lines: usize) {
    let _ = writeln!(
        s,
        "<?xml version=\"1.0\"?>\n<VTKFile type=\"PolyData\" version=\"0.1\" byte_order=\"LittleEndian\">\n<PolyData>\n<Piece NumberOfPoints=\"{points}\" NumberOfVerts=\"{verts}\" NumberOfLines=\"{lines}\" NumberOfStrips=\"0\" NumberOfPolys=\"0\">"
    );
}

fn vtp_close(s: &mut String) {
    s.push_str("</Piece>\n</PolyData>\n</VTKFile>\n");
}

fn f_array(s: &mut String, name: &str, v: impl Iterator<Item = f64>) {
    let _ = write!(
        s,
        "<DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">"
    );
    for x in v {
        let _ = write!(s, " {x:e}");
    }
    s.push_str("</DataArray>\n");
}

fn vec_array(s: &mut String, name: &str, v: impl Iterator<Item = Vec3>) {
    let _ = write!(
        s,
        "<DataArray type=\"Float64\" Name=\"{name}\" NumberOfComponents=\"3\" format=\"ascii\">"
    );
    for x in v {
        let _ = write!(s, " {:e} {:e} {:e}", x.x, x.y, x.z);
    }
    s.push_str("</DataArray>\n");
}

fn int_array(s: &mut String, name: &str, v: impl Iterator<Item = i64>) {
    let _ = write!(
        s,
        "<DataArray type=\"Int64\" Name=\"{name}\" format=\"ascii\">"
    );
    for x in v {
        let _ = write!(s, " {x}");
    }
    s.push_str("</DataArray>\n");
}

/// Writes snapshots of an engine into a directory every `every` steps: per snapshot
/// `particles.<step>.dump` and `contacts.<step>.dump` (the LAMMPS-style dumps of the module
/// docs; OVITO opens the series as `particles.*.dump`) and, with [`Snapshots::with_vtk`],
/// `particles.<step>.vtp` and `contacts.<step>.vtp` with the collections `particles.pvd` and
/// `contacts.pvd` (ParaView opens the `.pvd` as a time series). `<step>` is the engine's step
/// count, zero-padded to 9 digits.
#[derive(Debug, Clone)]
pub struct Snapshots {
    dir: PathBuf,
    every: u64,
    vtk: bool,
    written: Vec<(u64, f64)>,
    prefix: String,
}

impl Snapshots {
    /// Snapshots into `dir` (created if missing) every `every >= 1` steps.
    pub fn new(dir: impl Into<PathBuf>, every: u64) -> Result<Self, DumpError> {
        if every == 0 {
            return Err(DumpError::Setting(
                "the dump interval must be at least one step",
            ));
        }
        let dir = dir.into();
        std::fs::create_dir_all(&dir).map_err(|source| DumpError::Io {
            path: dir.clone(),
            source,
        })?;
        Ok(Self {
            dir,
            every,
            vtk: true,
            written: Vec::new(),
            prefix: String::new(),
        })
    }

    /// Whether to write the `.vtp` files and `.pvd` collections too (default: yes).
    pub fn with_vtk(mut self, vtk: bool) -> Self {
        self.vtk = vtk;
        self
    }

    /// A prefix of every file name (e.g. `"shear_creep."`; default none).
    pub fn with_prefix(mut self, prefix: impl Into<String>) -> Self {
        self.prefix = prefix.into();
        self
    }

    /// Takes the snapshots already in the directory (this prefix's `particles.<step>.dump`,
    /// with their `ITEM: TIME`) into the series, so that the `.pvd` collections list them too
    /// and an interval that has one is not written again: for a run resumed from a checkpoint
    /// (its frames are the same bits as the stopped run's).
    pub fn adopt_existing(mut self) -> Result<Self, DumpError> {
        let io = |source| DumpError::Io {
            path: self.dir.clone(),
            source,
        };
        let head = format!("{}particles.", self.prefix);
        for entry in std::fs::read_dir(&self.dir).map_err(io)? {
            let name = entry.map_err(io)?.file_name();
            let name = name.to_string_lossy();
            let Some(step) = name
                .strip_prefix(&head)
                .and_then(|r| r.strip_suffix(".dump"))
                .and_then(|r| r.parse::<u64>().ok())
            else {
                continue;
            };
            let path = self.dir.join(name.as_ref());
            let text = std::fs::read_to_string(&path).map_err(|source| DumpError::Io {
                path: path.clone(),
                source,
            })?;
            // The header only: up to the count.
            let cut = text.find("ITEM: NUMBER OF").unwrap_or(text.len());
            let time = text[..cut]
                .split_once("ITEM: TIME\n")
                .and_then(|(_, t)| t.lines().next()?.trim().parse::<f64>().ok())
                .unwrap_or(f64::NAN);
            if !self.written.iter().any(|w| w.0 == step) {
                self.written.push((step, time));
            }
        }
        self.written.sort_by_key(|w| w.0);
        Ok(self)
    }

    /// The directory.
    pub fn dir(&self) -> &Path {
        &self.dir
    }

    /// The steps of the series so far, ascending.
    pub fn written(&self) -> impl Iterator<Item = u64> + '_ {
        self.written.iter().map(|w| w.0)
    }

    /// Writes a snapshot unless one was written in the same interval of steps (`steps /
    /// every`), so that callers that step by more than one step at a time still write one per
    /// interval; the first call always writes. Returns whether it wrote one.
    pub fn maybe_write<T: TangentialLaw>(&mut self, dem: &Dem<T>) -> Result<bool, DumpError> {
        let block = dem.steps() / self.every;
        if self.written.iter().any(|w| w.0 / self.every == block) {
            return Ok(false);
        }
        self.write(dem)?;
        Ok(true)
    }

    /// Writes a snapshot of the engine now (named by its step count).
    pub fn write<T: TangentialLaw>(&mut self, dem: &Dem<T>) -> Result<(), DumpError> {
        let step = dem.steps();
        let (contacts, counts) = dem.snapshot_contacts();
        let name = |kind: &str, ext: &str| format!("{}{kind}.{step:09}.{ext}", self.prefix);
        self.file(&name("particles", "dump"), |w| {
            dem.write_particle_dump_with(step, &counts, w)
        })?;
        self.file(&name("contacts", "dump"), |w| {
            dem.write_contact_dump_with(step, &contacts, w)
        })?;
        self.written.retain(|w| w.0 != step);
        self.written.push((step, dem.time()));
        self.written.sort_by_key(|w| w.0);
        if self.vtk {
            self.file(&name("particles", "vtp"), |w| {
                dem.write_particle_vtp(&counts, w)
            })?;
            self.file(&name("contacts", "vtp"), |w| {
                dem.write_contact_vtp(&contacts, w)
            })?;
            for kind in ["particles", "contacts"] {
                let mut s = String::from(
                    "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\">\n<Collection>\n",
                );
                for &(k, t) in &self.written {
                    let _ = writeln!(
                        s,
                        "<DataSet timestep=\"{t:e}\" part=\"0\" file=\"{}{kind}.{k:09}.vtp\"/>",
                        self.prefix
                    );
                }
                s.push_str("</Collection>\n</VTKFile>\n");
                let pvd = format!("{}{kind}.pvd", self.prefix);
                self.file(&pvd, |w| w.write_all(s.as_bytes()))?;
            }
        }
        Ok(())
    }

    fn file(
        &self,
        name: &str,
        f: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<(), DumpError> {
        let path = self.dir.join(name);
        let io = |source| DumpError::Io {
            path: path.clone(),
            source,
        };
        let file = std::fs::File::create(&path).map_err(io)?;
        let mut w = std::io::BufWriter::new(file);
        f(&mut w).map_err(io)?;
        w.flush().map_err(io)
    }
}

/// One frame of a LAMMPS-style text dump, as [`read_dump`] parses it.
#[derive(Debug, Clone, PartialEq)]
pub struct DumpFrame {
    /// `ITEM: TIMESTEP`.
    pub timestep: u64,
    /// `ITEM: TIME`, if present \[s\].
    pub time: Option<f64>,
    /// `ITEM: BOX BOUNDS`: `(lo, hi)` per axis \[m\].
    pub bounds: [(f64, f64); 3],
    /// The column names of `ITEM: ATOMS` or `ITEM: ENTRIES`.
    pub columns: Vec<String>,
    /// One row per atom or entry, as numbers.
    pub rows: Vec<Vec<f64>>,
}

impl DumpFrame {
    /// The values of column `name`, if the frame has it.
    pub fn column(&self, name: &str) -> Option<Vec<f64>> {
        let k = self.columns.iter().position(|c| c == name)?;
        Some(self.rows.iter().map(|r| r[k]).collect())
    }
}

/// Parses every frame of a LAMMPS text dump (`dump custom` or `dump local`, orthogonal box;
/// the form written here, and LAMMPS' own).
pub fn read_dump(text: &str) -> Result<Vec<DumpFrame>, DumpError> {
    let mut lines = text.lines().enumerate().peekable();
    let mut frames = Vec::new();
    let bad = |line: usize, why: &str| DumpError::Format {
        line: line + 1,
        why: why.to_string(),
    };
    let mut next = |why: &str| -> Result<(usize, &str), DumpError> {
        lines.next().ok_or_else(|| DumpError::Format {
            line: 0,
            why: format!("the text ends where {why} was expected"),
        })
    };
    fn num<X: std::str::FromStr>(l: usize, s: &str) -> Result<X, DumpError> {
        s.trim().parse().map_err(|_| DumpError::Format {
            line: l + 1,
            why: format!("{s:?} is not a number"),
        })
    }
    loop {
        let (l, item) = match next("ITEM: TIMESTEP") {
            Ok(x) => x,
            Err(_) if !frames.is_empty() => break,
            Err(e) => return Err(e),
        };
        if item.trim().is_empty() {
            continue;
        }
        if item.trim() != "ITEM: TIMESTEP" {
            return Err(bad(l, "expected ITEM: TIMESTEP"));
        }
        let (l, v) = next("the timestep")?;
        let timestep: u64 = num(l, v)?;
        let (mut l, mut item) = next("an ITEM")?;
        let mut time = None;
        if item.trim() == "ITEM: TIME" {
            let (lt, v) = next("the time")?;
            time = Some(num(lt, v)?);
            (l, item) = next("ITEM: NUMBER OF ...")?;
        }
        if !item.starts_with("ITEM: NUMBER OF") {
            return Err(bad(l, "expected ITEM: NUMBER OF ATOMS or ENTRIES"));
        }
        let (l, v) = next("the count")?;
        let n: usize = num(l, v)?;
        let (l, item) = next("ITEM: BOX BOUNDS")?;
        if !item.starts_with("ITEM: BOX BOUNDS") {
            return Err(bad(l, "expected ITEM: BOX BOUNDS"));
        }
        let mut bounds = [(0.0, 0.0); 3];
        for b in &mut bounds {
            let (l, v) = next("box bounds")?;
            let mut it = v.split_whitespace();
            let lo = num(l, it.next().unwrap_or(""))?;
            let hi = num(l, it.next().unwrap_or(""))?;
            *b = (lo, hi);
        }
        let (l, item) = next("ITEM: ATOMS or ENTRIES")?;
        let cols = item
            .strip_prefix("ITEM: ATOMS")
            .or_else(|| item.strip_prefix("ITEM: ENTRIES"))
            .ok_or_else(|| bad(l, "expected ITEM: ATOMS or ITEM: ENTRIES"))?;
        let columns: Vec<String> = cols.split_whitespace().map(String::from).collect();
        let mut rows = Vec::with_capacity(n);
        for _ in 0..n {
            let (l, v) = next("a row")?;
            let row: Vec<f64> = v
                .split_whitespace()
                .map(|s| num(l, s))
                .collect::<Result<_, _>>()?;
            if row.len() != columns.len() {
                return Err(bad(l, "a row has not as many values as there are columns"));
            }
            rows.push(row);
        }
        frames.push(DumpFrame {
            timestep,
            time,
            bounds,
            columns,
            rows,
        });
    }
    Ok(frames)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{DemConfig, MaterialTable, Particle, Wall};
    use creep_law::{CreepModel, Material};

    /// A small heap of spheres on a floor, settled for a while, with friction and creep.
    fn heap() -> Dem<crate::Cheap> {
        let glass = Material::new(29e6, 0.2, 0.5, 2500.0).unwrap();
        let table = MaterialTable::new(&[glass], 0.1, Some(CreepModel::Kuhn), None).unwrap();
        let r = 1e-3;
        let mut ps = Vec::new();
        for i in 0..5 {
            for j in 0..5 {
                for k in 0..4 {
                    let jitter = 1e-5 * ((i * 7 + j * 3 + k * 5) % 11) as f64;
                    ps.push(Particle {
                        position: Vec3::new(
                            2.05 * r * i as f64 + jitter,
                            2.05 * r * j as f64,
                            r + 2.05 * r * k as f64,
                        ),
                        velocity: Vec3::new(0.0, 0.0, -0.3),
                        angular_velocity: Vec3::ZERO,
                        radius: r * (1.0 - 0.1 * ((i + j + k) % 3) as f64),
                        material: 0,
                    });
                }
            }
        }
        let floor = Wall {
            point: Vec3::ZERO,
            normal: Vec3::Z,
            velocity: Vec3::ZERO,
            material: 0,
        };
        let cfg = DemConfig {
            dt: 2e-6,
            skin: 1e-4,
            gravity: Vec3::new(0.0, 0.0, -9.81),
            ..DemConfig::default()
        };
        let mut dem = Dem::new(cfg, table, &ps, &[floor]).unwrap();
        for _ in 0..8000 {
            dem.step().unwrap();
        }
        dem
    }

    /// The particle dump reads back with every particle once, at its position and radius (to
    /// the bit: the numbers are written in Rust's shortest round-trip form); the contact dump
    /// has every touching pair with its counts matching the per-particle columns.
    #[test]
    fn a_dump_reads_back_with_every_particle() {
        let dem = heap();
        let mut buf = Vec::new();
        dem.write_particle_dump(dem.steps(), &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let frames = read_dump(&text).unwrap();
        assert_eq!(frames.len(), 1);
        let f = &frames[0];
        assert_eq!(f.timestep, 8000);
        assert_eq!(f.time, Some(dem.time()));
        assert_eq!(f.columns.join(" "), PARTICLE_COLUMNS);
        assert_eq!(f.rows.len(), dem.len());
        let ids = f.column("id").unwrap();
        let mut seen = vec![false; dem.len()];
        for (row, &id) in f.rows.iter().zip(&ids) {
            let id = id as usize - 1;
            assert!(!seen[id], "particle {id} twice");
            seen[id] = true;
            let p = dem.particle(id);
            assert_eq!(row[2], p.radius);
            assert_eq!(
                Vec3::new(row[3], row[4], row[5]),
                p.position,
                "particle {id}"
            );
            for a in 0..3 {
                let x = [p.position.x, p.position.y, p.position.z][a];
                assert!(x - p.radius >= f.bounds[a].0 && x + p.radius <= f.bounds[a].1);
            }
        }
        assert!(seen.iter().all(|&s| s), "every particle is in the dump");

        let mut buf = Vec::new();
        dem.write_contact_dump(dem.steps(), &mut buf).unwrap();
        let frames = read_dump(std::str::from_utf8(&buf).unwrap()).unwrap();
        let c = &frames[0];
        assert_eq!(c.columns.join(" "), CONTACT_COLUMNS);
        let mut pairs = 0;
        dem.for_each_contact(|v| pairs += usize::from(v.p.is_some()));
        assert!(pairs > 20, "a settled heap has contacts ({pairs})");
        assert_eq!(c.rows.len(), pairs);
        // Each contact appears in both particles' counts; the wall contacts in one.
        let total: f64 = f.column("contacts").unwrap().iter().sum();
        let mut walls = 0;
        dem.for_each_contact(|v| walls += usize::from(v.wall.is_some()));
        assert_eq!(total as usize, 2 * pairs + walls);
        for row in &c.rows {
            assert!(row[0] < row[1]);
            let n = Vec3::new(row[5], row[6], row[7]);
            assert!((n.length() - 1.0).abs() < 1e-12);
            assert!(row[8] >= 0.0);
            assert!([0.0, 1.0, 2.0].contains(&row[12]));
        }
        // Weight carried: the normal forces are not all zero.
        assert!(c.column("fn").unwrap().iter().any(|&x| x > 0.0));
    }

    /// The snapshot writer writes the dumps, the .vtp files and the .pvd collections, once per
    /// interval of `every` steps (the first call always), also when stepped several steps at
    /// a time; a zero interval is refused.
    #[test]
    fn snapshots_write_the_series() {
        let mut dem = heap();
        let dir = std::env::temp_dir().join(format!("creep-dem-dump-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        assert!(matches!(
            Snapshots::new(&dir, 0),
            Err(DumpError::Setting(_))
        ));
        let mut snaps = Snapshots::new(&dir, 10).unwrap();
        for _ in 0..25 {
            snaps.maybe_write(&dem).unwrap();
            dem.step().unwrap();
        }
        let steps: Vec<u64> = snaps.written().collect();
        assert_eq!(steps, vec![8000, 8010, 8020]);
        for s in &steps {
            for f in ["particles", "contacts"] {
                for ext in ["dump", "vtp"] {
                    assert!(dir.join(format!("{f}.{s:09}.{ext}")).is_file(), "{f} {ext}");
                }
            }
        }
        let pvd = std::fs::read_to_string(dir.join("particles.pvd")).unwrap();
        assert_eq!(pvd.matches("<DataSet").count(), 3);
        let vtp = std::fs::read_to_string(dir.join("particles.000008020.vtp")).unwrap();
        assert!(vtp.contains(&format!("NumberOfPoints=\"{}\"", dem.len())));
        // Three steps at a time: the first step of each interval of 10 reached.
        let mut coarse = Snapshots::new(dir.join("coarse"), 10).unwrap();
        for _ in 0..8 {
            coarse.maybe_write(&dem).unwrap();
            for _ in 0..3 {
                dem.step().unwrap();
            }
        }
        let coarse_steps: Vec<u64> = coarse.written().collect();
        assert_eq!(coarse_steps, vec![8025, 8031, 8040]);
        // A resumed writer takes the series over, times and all.
        let adopted = Snapshots::new(&dir, 10).unwrap().adopt_existing().unwrap();
        assert_eq!(adopted.written, snaps.written);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    /// A damaged dump is a typed error naming the line.
    #[test]
    fn a_damaged_dump_is_an_error() {
        let dem = heap();
        let mut buf = Vec::new();
        dem.write_particle_dump(1, &mut buf).unwrap();
        let text = String::from_utf8(buf).unwrap();
        let cut = &text[..text.len() / 2];
        assert!(matches!(read_dump(cut), Err(DumpError::Format { .. })));
        let garbled = text.replacen("ITEM: BOX BOUNDS", "ITEM: BOX", 1);
        assert!(matches!(
            read_dump(&garbled),
            Err(DumpError::Format { line: 7, .. })
        ));
    }
}
