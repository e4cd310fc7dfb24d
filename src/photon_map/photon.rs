//! What a photon map stores.

use glam::DVec3;

/// A photon as the tracer produces it (full precision).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PhotonRecord {
    pub position: DVec3,
    /// Unit direction of travel when the photon arrived.
    pub dir: DVec3,
    /// Unit surface normal at a surface photon; zero for a photon stored in a medium.
    pub normal: DVec3,
    pub wavelength_nm: f64,
    pub power_w: f64,
}

/// A stored photon, at most 32 bytes.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Photon {}

impl super::KdPoint for Photon {
    fn position(&self) -> [f32; 3] {
        todo!()
    }
}
