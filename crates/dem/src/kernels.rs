//! The instruction set of the force loops, chosen at run time.
//!
//! The contact loops (the pair entries of the serial step, and each block of entries of the
//! parallel step) are compiled three times: once for the target's baseline (x86-64: SSE2, two
//! `f64` per vector instruction) and, on x86-64, once inside a function compiled with AVX2 and
//! FMA enabled, into which the kernels inline (creep-law's [`pair_force`], down to the exact
//! tier's Cattaneo-Mindlin memory update, and the cheap tier's block of four contacts): four
//! `f64` per instruction, three-operand forms; and once more with AVX-512 (F and VL) enabled
//! too: the same four-lane vectors, but 32 vector registers instead of 16 (the cheap tier's
//! block of four contacts holds more values than 16 registers, and spills the rest to the
//! stack) and mask registers for its lane tests. The engine takes the widest copy the CPU
//! runs ([`Kernels::detected`], checked once per process), so a default `cargo build
//! --release` runs at the speed of a `-C target-cpu` build on such CPUs and still runs
//! everywhere.
//!
//! All copies give the same bits: Rust never contracts `a * b + c` into a fused
//! multiply-add (FMA is only enabled, not used, by the compiler's own choice), and every
//! other operation is IEEE 754's, correctly rounded lane by lane whatever the vector width
//! (test `kernels_give_the_same_bits`).
//!
//! `CREEP_DEM_KERNELS=portable` (or `avx2`) in the environment makes [`Kernels::detected`]
//! (and so every engine) take the baseline (or the AVX2) copy; [`Dem::set_kernels`](crate::Dem::set_kernels)
//! chooses per engine.
//!
//! [`pair_force`]: creep_law::pair::pair_force

use std::sync::OnceLock;

use crate::DemError;

/// Which compiled copy of the force loops an engine runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Kernels {
    /// The target's baseline instruction set (every CPU of the target).
    Portable,
    /// x86-64 with AVX2 and FMA (the CPU must have both: [`Kernels::available`]).
    Avx2,
    /// x86-64 with AVX2, FMA, AVX-512F and AVX-512VL (the CPU must have all four:
    /// [`Kernels::available`]).
    Avx512,
}

/// The environment variable that forces the portable kernels (`portable`), the AVX2 ones
/// (`avx2`, where the CPU has them), or (`auto` or unset) the detected ones.
pub const KERNELS_ENV: &str = "CREEP_DEM_KERNELS";

impl Kernels {
    /// Whether this CPU runs the kernels (checked at run time; cached by the standard library).
    pub fn available(self) -> bool {
        match self {
            Kernels::Portable => true,
            #[cfg(target_arch = "x86_64")]
            Kernels::Avx2 => {
                std::arch::is_x86_feature_detected!("avx2")
                    && std::arch::is_x86_feature_detected!("fma")
            }
            #[cfg(target_arch = "x86_64")]
            Kernels::Avx512 => {
                Kernels::Avx2.available()
                    && std::arch::is_x86_feature_detected!("avx512f")
                    && std::arch::is_x86_feature_detected!("avx512vl")
            }
            #[cfg(not(target_arch = "x86_64"))]
            Kernels::Avx2 | Kernels::Avx512 => false,
        }
    }

    /// The kernels new engines take: [`Kernels::Avx512`] where available, else
    /// [`Kernels::Avx2`] where available, unless the environment variable [`KERNELS_ENV`] says
    /// `portable` (or `avx2`: the AVX2 copy where available); read once per process. Another
    /// value of the variable is an error.
    pub fn detected() -> Result<Kernels, DemError> {
        static CHOICE: OnceLock<Result<Kernels, DemError>> = OnceLock::new();
        CHOICE
            .get_or_init(|| {
                let avx2 = if Kernels::Avx2.available() {
                    Kernels::Avx2
                } else {
                    Kernels::Portable
                };
                let fastest = if Kernels::Avx512.available() {
                    Kernels::Avx512
                } else {
                    avx2
                };
                match std::env::var(KERNELS_ENV) {
                    Err(std::env::VarError::NotPresent) => Ok(fastest),
                    Ok(v) if v == "auto" || v.is_empty() => Ok(fastest),
                    Ok(v) if v == "portable" => Ok(Kernels::Portable),
                    Ok(v) if v == "avx2" => Ok(avx2),
                    _ => Err(DemError::Parameter {
                        name: "CREEP_DEM_KERNELS",
                        value: f64::NAN,
                        why: "the environment variable must be `portable`, `avx2`, `auto` or unset",
                    }),
                }
            })
            .clone()
    }

    /// The kernels' name: `portable`, `avx2` or `avx512`.
    pub fn name(self) -> &'static str {
        match self {
            Kernels::Portable => "portable",
            Kernels::Avx2 => "avx2",
            Kernels::Avx512 => "avx512",
        }
    }

    /// Whether the copy has four-lane vector registers (AVX2 or wider).
    pub fn wide(self) -> bool {
        self != Kernels::Portable
    }
}

/// Calls `$body` (an expression) through a function compiled with AVX2 and FMA enabled when
/// `$kernels` is [`Kernels::Avx2`], with AVX-512F and AVX-512VL too when it is
/// [`Kernels::Avx512`], else as it is. `$body`'s callees must be `#[inline(always)]` (down to
/// the kernels) for them to be compiled with the features: a function that is not inlined is
/// compiled once, for the baseline. Each use makes its own copies: `$name` names the AVX2
/// function (the AVX-512 one is `$name` in a module `avx512`), `($($arg: $ty),*)` their
/// arguments (generic over `$T: TangentialLaw`), `-> $ret` their result. `$body` sees the
/// constant `WIDE`: `true` in the AVX2 and AVX-512 copies (four-lane vector registers),
/// `false` in the portable one.
macro_rules! dispatch {
    ($kernels:expr, $name:ident<$T:ident>($($arg:ident: $ty:ty = $val:expr),* $(,)?) -> $ret:ty $body:block) => {{
        #[cfg(target_arch = "x86_64")]
        #[target_feature(enable = "avx2,fma")]
        fn $name<$T: creep_law::pair::TangentialLaw>($($arg: $ty),*) -> $ret {
            #[allow(dead_code)]
            const WIDE: bool = true;
            $body
        }
        #[cfg(target_arch = "x86_64")]
        mod avx512 {
            #[allow(unused_imports)]
            use super::*;
            #[target_feature(enable = "avx2,fma,avx512f,avx512vl")]
            pub(super) fn $name<$T: creep_law::pair::TangentialLaw>($($arg: $ty),*) -> $ret {
                #[allow(dead_code)]
                const WIDE: bool = true;
                $body
            }
        }
        match $kernels {
            // SAFETY: an engine holds `Kernels::Avx2` only where `Kernels::available` found
            // AVX2 and FMA on this CPU (`Dem::new`, `Dem::set_kernels`).
            #[cfg(target_arch = "x86_64")]
            #[allow(unsafe_code)]
            $crate::kernels::Kernels::Avx2 => unsafe { $name::<$T>($($val),*) },
            // SAFETY: an engine holds `Kernels::Avx512` only where `Kernels::available` found
            // AVX2, FMA, AVX-512F and AVX-512VL on this CPU (`Dem::new`, `Dem::set_kernels`).
            #[cfg(target_arch = "x86_64")]
            #[allow(unsafe_code)]
            $crate::kernels::Kernels::Avx512 => unsafe { avx512::$name::<$T>($($val),*) },
            _ => {
                #[allow(dead_code)]
                const WIDE: bool = false;
                $(let $arg: $ty = $val;)*
                $body
            }
        }
    }};
}
pub(crate) use dispatch;

/// Entries ahead of the one in hand whose contact history the one-contact loops prefetch
/// ([`prefetch`]).
pub(crate) const PREFETCH_AHEAD: usize = 4;

/// Asks the CPU to bring the cache lines of `v` into the level-1 cache ahead of their use
/// (x86-64's `prefetcht0`, one per 64-byte line; nothing on other targets). A hint: no value
/// changes. The force loops prefetch the contact history a few list entries ahead, since an
/// exact-tier history (hundreds of bytes) is read and written once per step and the histories
/// of a packing of thousands of particles exceed the level-2 cache.
#[inline(always)]
pub(crate) fn prefetch<V>(v: &V) {
    #[cfg(target_arch = "x86_64")]
    {
        use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
        let p = (v as *const V).cast::<i8>();
        let mut off = 0;
        while off < size_of::<V>() {
            // SAFETY: SSE is part of x86-64's baseline instruction set, so the instruction
            // exists on every CPU of the target; a prefetch reads and writes nothing
            // architecturally (it cannot fault), and `p + off` stays within `v`.
            #[allow(unsafe_code)]
            unsafe {
                _mm_prefetch::<_MM_HINT_T0>(p.add(off))
            };
            off += 64;
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = v;
}
