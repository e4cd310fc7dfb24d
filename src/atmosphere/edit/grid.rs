//! A 3-D temperature perturbation from a lattice file (quantity `delta_temperature_k`, see
//! [`crate::field::grid_file`]): T += ΔT(x), interpolated trilinearly or by Catmull–Rom,
//! and zero outside the lattice. The file's face values must be zero, so the edit fades out where
//! the lattice ends and n stays continuous there.

use crate::field::{Beyond, Interpolation, Lattice};
use glam::DVec3;

/// Largest |ΔT| accepted on a face, K.
pub const FACE_TOLERANCE_K: f64 = 1e-6;

/// A temperature perturbation ΔT(x) on a lattice (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct GridEdit {
    lattice: Lattice,
    /// How ΔT is interpolated between lattice points.
    pub interpolation: Interpolation,
    range: (f64, f64),
}

impl GridEdit {
    /// Checks that ΔT is zero on the lattice faces (within `FACE_TOLERANCE_K`, 10⁻⁶ K).
    pub fn new(lattice: Lattice, interpolation: Interpolation) -> Result<GridEdit, String> {
        let (lo, hi) = lattice.face_range();
        let worst = lo.abs().max(hi.abs());
        if worst > FACE_TOLERANCE_K {
            return Err(format!(
                "temperature perturbation grid: ΔT on the lattice faces reaches {worst} K; it must be 0 \
                 (within {FACE_TOLERANCE_K} K) so the perturbation fades out where the lattice ends"
            ));
        }
        let (vlo, vhi) = lattice.value_range();
        let o = crate::field::catmull_rom_overshoot(&lattice, interpolation);
        Ok(GridEdit { lattice, interpolation, range: (vlo.min(0.0) - o, vhi.max(0.0) + o) })
    }

    /// The ΔT lattice, K.
    pub fn lattice(&self) -> &Lattice {
        &self.lattice
    }

    /// ΔT (K) and ∇ΔT (K m⁻¹) at `p`; zero outside the lattice.
    pub fn delta(&self, p: DVec3) -> (f64, DVec3) {
        self.lattice.value_grad(p, self.interpolation, Beyond::Zero)
    }

    /// The smallest and largest ΔT the interpolant can give (Catmull–Rom overshoot included), K.
    pub fn range_k(&self) -> (f64, f64) {
        self.range
    }
}
