//! A base field plus local perturbations: n = n_base + Σᵢ δnᵢ·wᵢ(x) (see [`Bump`]).

use super::IndexField;
use crate::field::Bump;
use glam::DVec3;

/// A base field plus local bumps: n = n_base + Σᵢ δnᵢ wᵢ(x).
#[derive(Clone, Debug)]
pub struct Sum {
    /// The field the bumps are added to.
    pub base: Box<IndexField>,
    /// Local perturbations δnᵢ wᵢ(x).
    pub bumps: Vec<Bump>,
}

impl Sum {
    /// n and ∇n at `p` (m): the base field's plus every bump's.
    pub fn n_grad(&self, wavelength_nm: f64, p: DVec3) -> (f64, DVec3) {
        let (mut n, mut g) = self.base.n_grad(wavelength_nm, p);
        for b in &self.bumps {
            let (dn, dg) = b.value_grad(p);
            n += dn;
            g += dg;
        }
        (n, g)
    }

    /// The base's bound lowered by every negative bump.
    pub fn min_n_added(&self) -> f64 {
        self.bumps.iter().map(|b| b.delta_n.min(0.0)).sum()
    }
}
