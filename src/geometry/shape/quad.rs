//! quad.

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Quad {
    pub origin: DVec3,
    pub u: DVec3,
    pub v: DVec3,
}
