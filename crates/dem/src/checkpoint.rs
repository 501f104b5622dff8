//! Checkpoints: the engine's whole state in a small versioned binary file, from which a run
//! continues to the same results, bit for bit, as if it had not stopped.
//!
//! # File format (version 1)
//! All integers and floats little-endian; `f64` as their IEEE-754 bits.
//! ```text
//! magic    8 bytes  "CREEPCKP"
//! version  u32      1
//! kind     u32 length + UTF-8 (what the payload is: "creep-dem engine", or a host's kind)
//! length   u64      payload bytes
//! payload  length bytes
//! crc      u32      CRC-32 (IEEE 802.3) of every byte before it
//! ```
//! A file that does not start with the magic is [`CheckpointError::Foreign`]; another version,
//! [`CheckpointError::Version`]; a short file or a wrong CRC, [`CheckpointError::Damaged`]; a
//! payload of another kind, [`CheckpointError::Kind`]. Nothing is ever silently started afresh.
//!
//! # The engine's payload
//! The tier's name and its history length ([`ContactHistory::LEN`]); the settings (step, skin,
//! periodic box, gravity); a fingerprint of the material table (CRC-32 of its `Debug` text:
//! the caller gives the table back, and a different one is [`CheckpointError::Mismatch`]);
//! time, steps, counters and energies; per particle in the engine's order its id, material,
//! radius, mass, inverse mass and inertia, position, velocity, angular velocity, force,
//! torque and position at the last list rebuild; the walls and their positions at the last
//! rebuild and forces; then every contact history that is not virgin, keyed by the two
//! particle ids (or wall and particle), in creep-law's flat form
//! ([`ContactHistory::write`]).
//!
//! On restore the neighbour and wall lists are rebuilt from the positions of the last rebuild
//! (the order of the particles is already the cell order of that rebuild, which the stable
//! cell sort keeps), so they are the lists the engine had, entry for entry, and the histories
//! are put back by key: the next steps add the same forces in the same order.
//!
//! [`CheckpointWriter`] and [`CheckpointReader`] are the primitive encoders; a host (e.g. a
//! test protocol with servo state) writes its own payload with them, the engine's inside it
//! ([`Dem::write_checkpoint`], [`Dem::read_checkpoint`]), and seals it with [`seal`].

use std::path::Path;

use creep_law::Vec3;
use creep_law::pair::{ContactHistory, TangentialLaw};

use crate::{Dem, DemConfig, DemCounts, DemEnergy, DemError, MaterialTable, Wall};

/// The first eight bytes of every checkpoint.
pub const MAGIC: &[u8; 8] = b"CREEPCKP";
/// The format version written.
pub const VERSION: u32 = 1;
/// The kind of a payload holding only an engine ([`Dem::save_checkpoint`]).
pub const ENGINE_KIND: &str = "creep-dem engine";

/// Why a checkpoint could not be read.
#[derive(Debug, thiserror::Error)]
pub enum CheckpointError {
    /// Reading or writing the file failed.
    #[error("checkpoint {path}: {source}")]
    Io {
        /// The file.
        path: String,
        /// What went wrong.
        source: std::io::Error,
    },
    /// Not a checkpoint (no magic).
    #[error("not a creep checkpoint (the file does not start with {MAGIC:?})")]
    Foreign,
    /// A checkpoint of another format version.
    #[error("checkpoint format version {found}, this build reads version {VERSION}")]
    Version {
        /// The file's version.
        found: u32,
    },
    /// Truncated, or the checksum does not match.
    #[error("damaged checkpoint: {0}")]
    Damaged(String),
    /// A checkpoint of something else.
    #[error("the checkpoint holds a {found:?}, expected a {expected:?}")]
    Kind {
        /// What it holds.
        found: String,
        /// What was asked for.
        expected: String,
    },
    /// The checkpoint does not fit what it is restored into (another tier, table, ...).
    #[error("checkpoint mismatch: {0}")]
    Mismatch(String),
    /// The engine refused the restored state.
    #[error(transparent)]
    Engine(#[from] DemError),
}

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320) of `bytes`.
pub fn crc32(bytes: &[u8]) -> u32 {
    const TABLE: [u32; 256] = {
        let mut t = [0u32; 256];
        let mut i = 0;
        while i < 256 {
            let mut c = i as u32;
            let mut k = 0;
            while k < 8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
                k += 1;
            }
            t[i] = c;
            i += 1;
        }
        t
    };
    let mut c = !0u32;
    for &b in bytes {
        c = TABLE[((c ^ u32::from(b)) & 0xff) as usize] ^ (c >> 8);
    }
    !c
}

/// The framed file of the module docs around `payload`.
pub fn seal(kind: &str, payload: &[u8]) -> Vec<u8> {
    let mut w = CheckpointWriter::default();
    w.buf.extend_from_slice(MAGIC);
    w.u32(VERSION);
    w.str(kind);
    w.u64(payload.len() as u64);
    w.buf.extend_from_slice(payload);
    let crc = crc32(&w.buf);
    w.u32(crc);
    w.buf
}

/// The payload of a framed file of kind `kind`, checked (magic, version, length, CRC, kind).
pub fn unseal<'a>(kind: &str, file: &'a [u8]) -> Result<&'a [u8], CheckpointError> {
    if file.len() < MAGIC.len() || &file[..MAGIC.len()] != MAGIC {
        return Err(CheckpointError::Foreign);
    }
    let mut r = CheckpointReader::new(&file[MAGIC.len()..]);
    let version = r.u32()?;
    if version != VERSION {
        return Err(CheckpointError::Version { found: version });
    }
    let found = r.str()?;
    let len = r.u64()?;
    let start = file.len() - r.remaining();
    let end = start
        .checked_add(len as usize)
        .filter(|&e| e.checked_add(4) == Some(file.len()))
        .ok_or_else(|| {
            CheckpointError::Damaged(format!(
                "{} bytes, the header announces a payload of {len} bytes",
                file.len()
            ))
        })?;
    let stored = u32::from_le_bytes([file[end], file[end + 1], file[end + 2], file[end + 3]]);
    let crc = crc32(&file[..end]);
    if crc != stored {
        return Err(CheckpointError::Damaged(format!(
            "checksum {crc:08x}, the file says {stored:08x}"
        )));
    }
    if found != kind {
        return Err(CheckpointError::Kind {
            found,
            expected: kind.to_string(),
        });
    }
    Ok(&file[start..end])
}

/// Writes `bytes` to `path` atomically: into `path` + `.tmp`, synced, then renamed over
/// `path` (a run killed while writing leaves the previous checkpoint intact).
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<(), CheckpointError> {
    use std::io::Write;
    let io = |source| CheckpointError::Io {
        path: path.display().to_string(),
        source,
    };
    let mut tmp = path.as_os_str().to_owned();
    tmp.push(".tmp");
    let tmp = std::path::PathBuf::from(tmp);
    let mut f = std::fs::File::create(&tmp).map_err(io)?;
    f.write_all(bytes).map_err(io)?;
    f.sync_all().map_err(io)?;
    drop(f);
    std::fs::rename(&tmp, path).map_err(io)
}

/// Reads a whole file (an [`CheckpointError::Io`] naming it on failure).
pub fn read_file(path: &Path) -> Result<Vec<u8>, CheckpointError> {
    std::fs::read(path).map_err(|source| CheckpointError::Io {
        path: path.display().to_string(),
        source,
    })
}

/// Little-endian encoder of a payload.
#[derive(Debug, Default, Clone)]
pub struct CheckpointWriter {
    buf: Vec<u8>,
}

impl CheckpointWriter {
    /// The bytes so far.
    pub fn into_bytes(self) -> Vec<u8> {
        self.buf
    }
    /// A byte.
    pub fn u8(&mut self, v: u8) {
        self.buf.push(v);
    }
    /// A `u32`.
    pub fn u32(&mut self, v: u32) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    /// A `u64`.
    pub fn u64(&mut self, v: u64) {
        self.buf.extend_from_slice(&v.to_le_bytes());
    }
    /// A `usize`, as `u64`.
    pub fn usize(&mut self, v: usize) {
        self.u64(v as u64);
    }
    /// An `f64` (its bits).
    pub fn f64(&mut self, v: f64) {
        self.buf.extend_from_slice(&v.to_bits().to_le_bytes());
    }
    /// A bool, as a byte.
    pub fn bool(&mut self, v: bool) {
        self.u8(u8::from(v));
    }
    /// A vector.
    pub fn vec3(&mut self, v: Vec3) {
        self.f64(v.x);
        self.f64(v.y);
        self.f64(v.z);
    }
    /// A string (`u32` length, UTF-8).
    pub fn str(&mut self, s: &str) {
        self.u32(s.len() as u32);
        self.buf.extend_from_slice(s.as_bytes());
    }
    /// Raw bytes (`u64` length, then the bytes).
    pub fn bytes(&mut self, b: &[u8]) {
        self.u64(b.len() as u64);
        self.buf.extend_from_slice(b);
    }
}

/// Little-endian decoder of a payload: reading past its end is [`CheckpointError::Damaged`].
#[derive(Debug, Clone)]
pub struct CheckpointReader<'a> {
    buf: &'a [u8],
    pos: usize,
}

impl<'a> CheckpointReader<'a> {
    /// A reader of `buf`.
    pub fn new(buf: &'a [u8]) -> Self {
        Self { buf, pos: 0 }
    }
    /// Bytes left.
    pub fn remaining(&self) -> usize {
        self.buf.len() - self.pos
    }
    /// Errors unless every byte was read.
    pub fn finish(&self) -> Result<(), CheckpointError> {
        if self.remaining() == 0 {
            Ok(())
        } else {
            Err(CheckpointError::Damaged(format!(
                "{} bytes left over after the payload",
                self.remaining()
            )))
        }
    }
    fn take(&mut self, n: usize) -> Result<&'a [u8], CheckpointError> {
        if self.remaining() < n {
            return Err(CheckpointError::Damaged(format!(
                "the payload ends at byte {} of {}, {n} more were expected",
                self.pos,
                self.buf.len()
            )));
        }
        let s = &self.buf[self.pos..self.pos + n];
        self.pos += n;
        Ok(s)
    }
    /// A byte.
    pub fn u8(&mut self) -> Result<u8, CheckpointError> {
        Ok(self.take(1)?[0])
    }
    /// A `u32`.
    pub fn u32(&mut self) -> Result<u32, CheckpointError> {
        let b = self.take(4)?;
        Ok(u32::from_le_bytes([b[0], b[1], b[2], b[3]]))
    }
    /// A `u64`.
    pub fn u64(&mut self) -> Result<u64, CheckpointError> {
        let mut a = [0u8; 8];
        a.copy_from_slice(self.take(8)?);
        Ok(u64::from_le_bytes(a))
    }
    /// A `usize` written as `u64`.
    pub fn usize(&mut self) -> Result<usize, CheckpointError> {
        let v = self.u64()?;
        usize::try_from(v)
            .map_err(|_| CheckpointError::Damaged(format!("count {v} does not fit this machine")))
    }
    /// A count of items of at least `item_bytes` bytes each, checked against the bytes left
    /// (so that a damaged count cannot ask for a huge allocation).
    pub fn count(&mut self, item_bytes: usize) -> Result<usize, CheckpointError> {
        let n = self.usize()?;
        if n.saturating_mul(item_bytes.max(1)) > self.remaining() {
            return Err(CheckpointError::Damaged(format!(
                "a count of {n} items does not fit in the {} bytes left",
                self.remaining()
            )));
        }
        Ok(n)
    }
    /// An `f64`.
    pub fn f64(&mut self) -> Result<f64, CheckpointError> {
        Ok(f64::from_bits(self.u64()?))
    }
    /// A bool.
    pub fn bool(&mut self) -> Result<bool, CheckpointError> {
        match self.u8()? {
            0 => Ok(false),
            1 => Ok(true),
            b => Err(CheckpointError::Damaged(format!("{b} is not a bool"))),
        }
    }
    /// A vector.
    pub fn vec3(&mut self) -> Result<Vec3, CheckpointError> {
        Ok(Vec3::new(self.f64()?, self.f64()?, self.f64()?))
    }
    /// A string.
    pub fn str(&mut self) -> Result<String, CheckpointError> {
        let n = self.u32()? as usize;
        let b = self.take(n)?;
        String::from_utf8(b.to_vec())
            .map_err(|_| CheckpointError::Damaged("a string is not UTF-8".into()))
    }
    /// Raw bytes written by [`CheckpointWriter::bytes`].
    pub fn bytes(&mut self) -> Result<&'a [u8], CheckpointError> {
        let n = self.count(1)?;
        self.take(n)
    }
}

/// The fingerprint of a material table stored in a checkpoint (CRC-32 of its `Debug` text,
/// which prints every constant to the bit).
fn table_fingerprint(table: &MaterialTable) -> u32 {
    crc32(format!("{table:?}").as_bytes())
}

/// The engine's state in engine order, as [`Dem::raw_state`] hands it out and
/// [`Dem::from_raw_state`] takes it back.
#[derive(Debug, Clone, Default)]
pub(crate) struct RawState<T: TangentialLaw> {
    pub(crate) id: Vec<u32>,
    pub(crate) mat: Vec<u32>,
    pub(crate) r: Vec<f64>,
    pub(crate) mass: Vec<f64>,
    pub(crate) inv_m: Vec<f64>,
    pub(crate) inv_i: Vec<f64>,
    pub(crate) x: Vec<Vec3>,
    pub(crate) v: Vec<Vec3>,
    pub(crate) w: Vec<Vec3>,
    pub(crate) f: Vec<Vec3>,
    pub(crate) t: Vec<Vec3>,
    pub(crate) x_build: Vec<Vec3>,
    pub(crate) walls: Vec<Wall>,
    pub(crate) wall_build: Vec<Vec3>,
    pub(crate) wall_force: Vec<Vec3>,
    /// `(smaller id, larger id, history)` of every non-virgin pair contact.
    pub(crate) pairs: Vec<(u32, u32, ContactHistory<T>)>,
    /// `(wall, particle id, history)` of every non-virgin wall contact.
    pub(crate) wall_pairs: Vec<(u32, u32, ContactHistory<T>)>,
    pub(crate) energy: DemEnergy,
    pub(crate) counts: DemCounts,
    pub(crate) time: f64,
    pub(crate) steps: u64,
}

impl<T: TangentialLaw> Dem<T> {
    /// Writes the engine's payload (module docs) into `w`.
    pub fn write_checkpoint(&self, w: &mut CheckpointWriter) {
        let s = self.raw_state();
        let cfg = self.config();
        w.str(T::NAME);
        w.u32(ContactHistory::<T>::LEN as u32);
        w.f64(cfg.dt);
        w.f64(cfg.skin);
        for p in cfg.periodic {
            w.bool(p.is_some());
            let (lo, hi) = p.unwrap_or((0.0, 0.0));
            w.f64(lo);
            w.f64(hi);
        }
        w.vec3(cfg.gravity);
        w.u32(table_fingerprint(self.table()));
        w.f64(s.time);
        w.u64(s.steps);
        let c = s.counts;
        for v in [
            c.contacts,
            c.wall_contacts,
            c.sliding,
            c.creeping,
            c.neighbours,
            c.rebuilds,
        ] {
            w.usize(v);
        }
        let e = s.energy;
        for v in [
            e.normal_elastic,
            e.tangential_elastic,
            e.damping,
            e.slip,
            e.creep,
            e.rolling,
            e.truncation,
        ] {
            w.f64(v);
        }
        w.usize(s.id.len());
        for i in 0..s.id.len() {
            w.u32(s.id[i]);
            w.u32(s.mat[i]);
            for v in [s.r[i], s.mass[i], s.inv_m[i], s.inv_i[i]] {
                w.f64(v);
            }
            for v in [s.x[i], s.v[i], s.w[i], s.f[i], s.t[i], s.x_build[i]] {
                w.vec3(v);
            }
        }
        w.usize(s.walls.len());
        for (k, wall) in s.walls.iter().enumerate() {
            w.vec3(wall.point);
            w.vec3(wall.normal);
            w.vec3(wall.velocity);
            w.u32(wall.material as u32);
            w.vec3(s.wall_build[k]);
            w.vec3(s.wall_force[k]);
        }
        let mut flat = vec![0.0; ContactHistory::<T>::LEN];
        for list in [&s.pairs, &s.wall_pairs] {
            w.usize(list.len());
            for (a, b, h) in list {
                w.u32(*a);
                w.u32(*b);
                // `write` only fails on a buffer of the wrong length.
                let _ = h.write(&mut flat);
                for &x in &flat {
                    w.f64(x);
                }
            }
        }
    }

    /// Reads an engine's payload written by [`Dem::write_checkpoint`], with the material
    /// table it ran with (checked against the stored fingerprint) and whether to step on
    /// rayon's threads ([`DemConfig::parallel`]; the results are the same bits either way).
    pub fn read_checkpoint(
        r: &mut CheckpointReader<'_>,
        table: MaterialTable,
        parallel: bool,
    ) -> Result<Self, CheckpointError> {
        let tier = r.str()?;
        let len = r.u32()? as usize;
        if tier != T::NAME || len != ContactHistory::<T>::LEN {
            return Err(CheckpointError::Mismatch(format!(
                "written by the {tier} tier ({len} numbers per contact history), read as the {} tier ({})",
                T::NAME,
                ContactHistory::<T>::LEN
            )));
        }
        let dt = r.f64()?;
        let skin = r.f64()?;
        let mut periodic = [None; 3];
        for p in &mut periodic {
            let on = r.bool()?;
            let (lo, hi) = (r.f64()?, r.f64()?);
            *p = on.then_some((lo, hi));
        }
        let gravity = r.vec3()?;
        let cfg = DemConfig {
            dt,
            skin,
            periodic,
            gravity,
            parallel,
        };
        let fp = r.u32()?;
        if fp != table_fingerprint(&table) {
            return Err(CheckpointError::Mismatch(
                "the material table differs from the one the checkpoint was written with".into(),
            ));
        }
        let mut s = RawState::<T> {
            time: r.f64()?,
            steps: r.u64()?,
            ..RawState::default()
        };
        let mut c = [0usize; 6];
        for v in &mut c {
            *v = r.usize()?;
        }
        s.counts = DemCounts {
            contacts: c[0],
            wall_contacts: c[1],
            sliding: c[2],
            creeping: c[3],
            neighbours: c[4],
            rebuilds: c[5],
        };
        let mut e = [0.0; 7];
        for v in &mut e {
            *v = r.f64()?;
        }
        s.energy = DemEnergy {
            normal_elastic: e[0],
            tangential_elastic: e[1],
            damping: e[2],
            slip: e[3],
            creep: e[4],
            rolling: e[5],
            truncation: e[6],
        };
        let n = r.count(8 + 4 * 8 + 6 * 24)?;
        for _ in 0..n {
            s.id.push(r.u32()?);
            s.mat.push(r.u32()?);
            s.r.push(r.f64()?);
            s.mass.push(r.f64()?);
            s.inv_m.push(r.f64()?);
            s.inv_i.push(r.f64()?);
            s.x.push(r.vec3()?);
            s.v.push(r.vec3()?);
            s.w.push(r.vec3()?);
            s.f.push(r.vec3()?);
            s.t.push(r.vec3()?);
            s.x_build.push(r.vec3()?);
        }
        let nw = r.count(5 * 24 + 4)?;
        for _ in 0..nw {
            let point = r.vec3()?;
            let normal = r.vec3()?;
            let velocity = r.vec3()?;
            let material = r.u32()? as usize;
            s.walls.push(Wall {
                point,
                normal,
                velocity,
                material,
            });
            s.wall_build.push(r.vec3()?);
            s.wall_force.push(r.vec3()?);
        }
        let mut flat = vec![0.0; ContactHistory::<T>::LEN];
        for list in [&mut s.pairs, &mut s.wall_pairs] {
            let m = r.count(8 + 8 * flat.len())?;
            for _ in 0..m {
                let (a, b) = (r.u32()?, r.u32()?);
                for x in &mut flat {
                    *x = r.f64()?;
                }
                let h = ContactHistory::<T>::read(&flat)
                    .map_err(|e| CheckpointError::Damaged(format!("contact history: {e}")))?;
                list.push((a, b, h));
            }
        }
        Ok(Self::from_raw_state(cfg, table, s)?)
    }

    /// Writes a checkpoint of the engine alone to `path` (atomically: [`write_atomic`]).
    pub fn save_checkpoint(&self, path: &Path) -> Result<(), CheckpointError> {
        let mut w = CheckpointWriter::default();
        self.write_checkpoint(&mut w);
        write_atomic(path, &seal(ENGINE_KIND, &w.into_bytes()))
    }

    /// Restores an engine saved by [`Dem::save_checkpoint`] (see [`Dem::read_checkpoint`]).
    pub fn load_checkpoint(
        path: &Path,
        table: MaterialTable,
        parallel: bool,
    ) -> Result<Self, CheckpointError> {
        let file = read_file(path)?;
        let payload = unseal(ENGINE_KIND, &file)?;
        let mut r = CheckpointReader::new(payload);
        let dem = Self::read_checkpoint(&mut r, table, parallel)?;
        r.finish()?;
        Ok(dem)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::{Cheap, Exact, Particle};
    use creep_law::{CreepModel, Material};

    /// A box of spheres falling onto a floor between two side walls, with friction and
    /// creep, shaken sideways (a moving wall), to have contacts stick, creep and slide.
    fn engine<T: TangentialLaw>(parallel: bool) -> Dem<T> {
        let glass = Material::new(29e6, 0.2, 0.5, 2500.0).unwrap();
        let table = MaterialTable::new(&[glass], 0.1, Some(CreepModel::Kuhn), None).unwrap();
        let r = 1e-3;
        let mut ps = Vec::new();
        for i in 0..6 {
            for j in 0..4 {
                for k in 0..5 {
                    let jit = 1e-5 * ((i * 7 + j * 3 + k * 5) % 11) as f64;
                    ps.push(Particle {
                        position: Vec3::new(
                            2.1 * r * i as f64 + jit,
                            2.1 * r * j as f64,
                            r + 2.1 * r * k as f64,
                        ),
                        velocity: Vec3::new(0.01 * jit / 1e-5, 0.0, -0.3),
                        angular_velocity: Vec3::ZERO,
                        radius: r * (1.0 - 0.1 * ((i + j + k) % 3) as f64),
                        material: 0,
                    });
                }
            }
        }
        let walls = [
            Wall {
                point: Vec3::ZERO,
                normal: Vec3::Z,
                velocity: Vec3::ZERO,
                material: 0,
            },
            Wall {
                point: Vec3::new(-1.2 * r, 0.0, 0.0),
                normal: Vec3::X,
                velocity: Vec3::new(0.02, 0.0, 0.0),
                material: 0,
            },
        ];
        let cfg = DemConfig {
            dt: 2e-6,
            skin: 5e-5,
            gravity: Vec3::new(0.0, 0.0, -9.81),
            periodic: [None, Some((-r, 8.4 * r - r)), None],
            parallel,
        };
        Dem::new(cfg, table, &ps, &walls).unwrap()
    }

    fn same<T: TangentialLaw>(a: &Dem<T>, b: &Dem<T>) {
        assert_eq!(a.steps(), b.steps());
        assert_eq!(a.time().to_bits(), b.time().to_bits());
        assert_eq!(a.ids(), b.ids());
        assert_eq!(a.positions(), b.positions());
        assert_eq!(a.velocities(), b.velocities());
        assert_eq!(a.angular_velocities(), b.angular_velocities());
        assert_eq!(a.particle_forces(), b.particle_forces());
        assert_eq!(a.walls(), b.walls());
        assert_eq!(a.counts(), b.counts());
        assert_eq!(a.energy(), b.energy());
        let (sa, sb) = (a.raw_state(), b.raw_state());
        assert_eq!(sa.pairs, sb.pairs);
        assert_eq!(sa.wall_pairs, sb.wall_pairs);
    }

    /// Stepping, saving, restoring and stepping on gives the same bits as stepping straight
    /// through, for both tiers, serial and parallel, with list rebuilds before and after the
    /// checkpoint.
    fn resume_is_bit_for_bit<T: TangentialLaw>(parallel: bool) {
        let mut straight = engine::<T>(parallel);
        for _ in 0..1500 {
            straight.step().unwrap();
        }
        let mut w = CheckpointWriter::default();
        straight.write_checkpoint(&mut w);
        let file = seal("test", &w.into_bytes());
        let table = straight.table().clone();
        let mut r = CheckpointReader::new(unseal("test", &file).unwrap());
        let mut resumed = Dem::<T>::read_checkpoint(&mut r, table, parallel).unwrap();
        r.finish().unwrap();
        same(&straight, &resumed);
        let rebuilds = straight.counts().rebuilds;
        for _ in 0..1500 {
            straight.step().unwrap();
            resumed.step().unwrap();
        }
        assert!(
            straight.counts().rebuilds > rebuilds + 2,
            "the list was rebuilt after the checkpoint"
        );
        let mut touching = 0;
        straight.for_each_contact(|_| touching += 1);
        assert!(touching > 30, "{touching} contacts");
        same(&straight, &resumed);
    }

    #[test]
    fn resume_is_bit_for_bit_exact_tier() {
        resume_is_bit_for_bit::<Exact>(false);
    }

    #[test]
    fn resume_is_bit_for_bit_cheap_tier() {
        resume_is_bit_for_bit::<Cheap>(false);
    }

    #[cfg(feature = "parallel")]
    #[test]
    fn resume_is_bit_for_bit_parallel() {
        crate::with_threads(2, || resume_is_bit_for_bit::<Cheap>(true)).unwrap();
    }

    /// Every contact history survives its flat form unchanged (the checkpoint's premise).
    #[test]
    fn histories_round_trip_through_the_flat_form() {
        let mut dem = engine::<Exact>(false);
        for _ in 0..1500 {
            dem.step().unwrap();
        }
        let s = dem.raw_state();
        assert!(!s.pairs.is_empty() && !s.wall_pairs.is_empty());
        let mut flat = vec![0.0; ContactHistory::<Exact>::LEN];
        for (_, _, h) in s.pairs.iter().chain(&s.wall_pairs) {
            h.write(&mut flat).unwrap();
            assert_eq!(&ContactHistory::<Exact>::read(&flat).unwrap(), h);
        }
    }

    /// A file that is not a checkpoint, one of another version, a truncated one, one with a
    /// flipped bit, one of another kind, another tier or another table: each its typed error.
    #[test]
    fn damaged_or_foreign_checkpoints_are_typed_errors() {
        let mut dem = engine::<Cheap>(false);
        for _ in 0..200 {
            dem.step().unwrap();
        }
        let dir = std::env::temp_dir().join(format!("creep-dem-ckpt-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("engine.ckpt");
        dem.save_checkpoint(&path).unwrap();
        let table = dem.table().clone();
        let good = std::fs::read(&path).unwrap();
        let load = |bytes: &[u8]| {
            std::fs::write(&path, bytes).unwrap();
            Dem::<Cheap>::load_checkpoint(&path, table.clone(), false)
        };
        let back = load(&good).unwrap();
        same(&dem, &back);

        assert!(matches!(
            load(b"ITEM: TIMESTEP\n0\n"),
            Err(CheckpointError::Foreign)
        ));
        assert!(matches!(load(b""), Err(CheckpointError::Foreign)));
        let mut v2 = good.clone();
        v2[8] = 2;
        assert!(matches!(
            load(&v2),
            Err(CheckpointError::Version { found: 2 })
        ));
        assert!(matches!(
            load(&good[..good.len() - 100]),
            Err(CheckpointError::Damaged(_))
        ));
        for at in [40, good.len() / 2, good.len() - 5] {
            let mut flipped = good.clone();
            flipped[at] ^= 0x10;
            assert!(
                matches!(load(&flipped), Err(CheckpointError::Damaged(_))),
                "bit flip at {at}"
            );
        }
        let other_kind = seal("a triaxial test", unseal(ENGINE_KIND, &good).unwrap());
        assert!(matches!(
            load(&other_kind),
            Err(CheckpointError::Kind { .. })
        ));
        std::fs::write(&path, &good).unwrap();
        let exact = Dem::<Exact>::load_checkpoint(&path, table.clone(), false);
        assert!(matches!(exact, Err(CheckpointError::Mismatch(_))));
        let glass = Material::new(29e6, 0.2, 0.4, 2500.0).unwrap();
        let other = MaterialTable::new(&[glass], 0.5, Some(CreepModel::Kuhn), None).unwrap();
        assert!(matches!(
            Dem::<Cheap>::load_checkpoint(&path, other, false),
            Err(CheckpointError::Mismatch(_))
        ));
        let missing = Dem::<Cheap>::load_checkpoint(&dir.join("nothing"), table, false);
        assert!(matches!(missing, Err(CheckpointError::Io { .. })));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn crc32_of_the_check_string() {
        // The standard check value of CRC-32/ISO-HDLC.
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
    }
}
