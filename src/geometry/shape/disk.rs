//! disk.

use glam::DVec3;

#[derive(Clone, Debug, PartialEq)]
pub struct Disk {
    pub center: DVec3,
    pub normal: DVec3,
    pub radius: f64,
}
