//! Choosing the light that emits a photon, in proportion to its power.

use crate::light::Light;
use crate::sampling::Discrete1D;

/// Chooses light i with probability Φ_i / ΣΦ.
pub struct LightChooser {
    dist: Discrete1D,
}

impl LightChooser {
    /// `None` if no light has positive power.
    pub fn new(lights: &[Light]) -> Option<LightChooser> {
        let powers: Vec<f64> = lights.iter().map(Light::power_w).collect();
        Discrete1D::new(&powers).map(|dist| LightChooser { dist })
    }

    /// Index of the chosen light and its probability.
    pub fn choose(&self, u: f64) -> (usize, f64) {
        let (i, p, _) = self.dist.sample(u);
        (i, p)
    }

    /// Total power of all lights, W.
    pub fn total_power_w(&self) -> f64 {
        self.dist.total()
    }
}
