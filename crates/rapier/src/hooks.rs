//! Paths kept for the compliant regime (`crate::hooks::{FastMap, body_motion, v3, vf}`): the
//! rigid regime lives in `rigid`, the conversions in `convert`, the contact store in `store`.

pub(crate) use crate::convert::{body_motion, v3, vf};
pub(crate) use crate::store::FastMap;
