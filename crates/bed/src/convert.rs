//! Conversions between Rapier's vectors (glam: f32 `Vec3`/`Quat`, f64 `DVec3`/`DQuat`) and
//! creep-law's f64 `Vec3`.

use creep_law::Vec3;
use rapier3d::glamx::{DQuat, DVec3, Quat, Vec3 as FVec3};

#[inline]
pub(crate) fn dv(v: FVec3) -> DVec3 {
    DVec3::new(f64::from(v.x), f64::from(v.y), f64::from(v.z))
}
#[inline]
pub(crate) fn dq(q: Quat) -> DQuat {
    DQuat::from_xyzw(
        f64::from(q.x),
        f64::from(q.y),
        f64::from(q.z),
        f64::from(q.w),
    )
    .normalize()
}
#[inline]
pub(crate) fn lv(v: DVec3) -> Vec3 {
    Vec3::new(v.x, v.y, v.z)
}
#[inline]
pub(crate) fn gv(v: Vec3) -> DVec3 {
    DVec3::new(v.x, v.y, v.z)
}
#[inline]
pub(crate) fn fv(v: DVec3) -> FVec3 {
    FVec3::new(v.x as f32, v.y as f32, v.z as f32)
}
