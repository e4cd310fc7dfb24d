//! Exponential height profile d(x) = exp(−(h(x) − h₀)/H), h(x) = x·up: a barometric atmosphere
//! or a layer of ground fog.
//!
//! Along a ray o + s·ω with height rate μ = ω·up, ∫₀ᵗ d ds = d(o)·H/μ·(1 − e^{−μt/H}) (μ ≠ 0), and
//! d(o)·t when μ = 0 — the closed form the tracking tests compare against.

use glam::DVec3;

/// d(x) = exp(−(x·up − reference_m)/H): exponential in height along a fixed direction.
#[derive(Clone, Debug, PartialEq)]
pub struct ExponentialHeight {
    /// Unit "up" direction.
    pub up: DVec3,
    /// Height (along `up`, from the origin) where d = 1, m.
    pub reference_m: f64,
    /// Scale height H, m.
    pub scale_height_m: f64,
}

/// Intervals are cut so that the height changes by at most this many scale heights on each,
/// which keeps the majorant within a factor e^{0.5} of the density.
const MAX_SCALE_HEIGHTS_PER_INTERVAL: f64 = 0.5;

impl ExponentialHeight {
    /// d at `p`.
    pub fn at(&self, p: DVec3) -> f64 {
        (-(p.dot(self.up) - self.reference_m) / self.scale_height_m).exp()
    }

    /// ∫₀ᵗ d(o + s·dir) ds in closed form (a series where μ t/H is tiny); `dir` a unit vector.
    pub fn integral(&self, o: DVec3, dir: DVec3, t: f64) -> f64 {
        let mu = dir.dot(self.up);
        let d0 = self.at(o);
        let x = mu * t / self.scale_height_m;
        if x.abs() < 1e-8 {
            // Series of (1 − e^{−x})/x for small x.
            return d0 * t * (1.0 - 0.5 * x + x * x / 6.0);
        }
        d0 * t * (-(-x).exp_m1()) / x
    }

    /// Intervals of at most H/2 in height, each bounded by d at its lower end; see
    /// [`super::Density::majorant_intervals`].
    pub fn majorant_intervals(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        let mu = dir.dot(self.up);
        let step = if mu.abs() > 0.0 {
            MAX_SCALE_HEIGHTS_PER_INTERVAL * self.scale_height_m / mu.abs()
        } else {
            f64::INFINITY
        };
        let mut t0 = 0.0;
        while t0 < t_max {
            let t1 = (t0 + step).min(t_max);
            // The density is largest at the lower end of the interval.
            let lower = if mu > 0.0 { t0 } else { t1 };
            let bound = if mu == 0.0 {
                self.at(o)
            } else if lower.is_finite() {
                self.at(o + lower * dir)
            } else {
                f64::INFINITY
            };
            if !bound.is_finite() || !visit(t0, t1, bound) {
                return;
            }
            t0 = t1;
        }
    }
}
