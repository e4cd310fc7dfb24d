//! triangle.

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Triangle {
    pub p: [DVec3; 3],
}
