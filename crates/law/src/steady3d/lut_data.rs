//! The computed nodes of the tabulated 3-D steady law (module `lut`). DO NOT EDIT: written by
//! `cargo run --release -p creep-reference --example steady3d_lut -- emit`.

use super::lut::LutNode;

/// The computed nodes, by `a/b` then `nu`.
pub(super) static NODES: [LutNode; 0] = [];
