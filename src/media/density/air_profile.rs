//! The molecular number density of an atmosphere, relative to a reference density:
//! d(x) = N(h(x))/N_ref with N = P N_A/(R* T) from the atmosphere's profile (USA76 or a table,
//! with its height-only edits) and h the height above the atmosphere's Earth (flat or spherical).
//! The density of the air that scatters by Rayleigh scattering ([`crate::media::rayleigh_air`]).
//!
//! # The table
//! N(h)/N_ref is tabulated at heights h_i = i Δh from the ground to the atmosphere's top
//! (Δh ≤ 5 m) and interpolated linearly in h; d = 0 at and above the top, and d = d(0) below the
//! ground (which a scene closes with a surface). For a profile whose density scale height
//! H = −N/(dN/dh) is at least 5.8 km (USA76 below 86 km: 5.9 km at its coldest), linear
//! interpolation changes N by at most Δh² |N''|/8 ≈ Δh²/(8H²) N < 10⁻⁷ N.
//!
//! # Optical depth and majorants
//! Along a straight chord the integral ∫ d ds is computed by 16-point Gauss–Legendre quadrature
//! on pieces of at most 1 km of the part of the chord below the top. Each piece is bounded by the
//! largest tabulated value at or above its lowest height (a running maximum from the top down),
//! which bounds the interpolant anywhere on the piece whether or not N decreases with height (it
//! may not, under a strong inversion).

use crate::atmosphere::{Atmosphere, Earth, gas};
use crate::quadrature::gauss_legendre;
use glam::DVec3;
use std::sync::Arc;

/// Longest height step of the table, m.
const MAX_STEP_M: f64 = 5.0;
/// Longest piece of a chord for quadrature and majorants, m.
const PIECE_M: f64 = 1_000.0;

/// d(x) = N(h)/N_ref tabulated in height (see the module docs).
#[derive(Clone, Debug)]
pub struct AirProfile {
    earth: Earth,
    top_m: f64,
    step_m: f64,
    values: Arc<[f64]>,
    max_above: Arc<[f64]>,
}

impl AirProfile {
    /// The Earth whose heights the profile follows.
    pub fn earth(&self) -> &Earth {
        &self.earth
    }

    /// The number density of `atmosphere` over `earth`, relative to `reference_per_m3`. Fails when
    /// an edit of the atmosphere depends on more than height (a bubble, a grid): then N is not a
    /// function of height.
    pub fn new(atmosphere: &Atmosphere, earth: Earth, reference_per_m3: f64) -> Result<AirProfile, String> {
        if let Some(e) = atmosphere.edits.iter().find(|e| !e.is_height_only()) {
            return Err(format!(
                "atmosphere \"{}\": its edit {e:?} varies along the ground; scattering air needs air that depends on height alone",
                atmosphere.name
            ));
        }
        let at_height = |h: f64| {
            let air = atmosphere.air(point_at_height(&earth, h));
            gas::number_density_per_m3(air.pressure_pa, air.temperature_k) / reference_per_m3
        };
        Ok(AirProfile::from_heights(earth, atmosphere.top_m(), at_height))
    }

    /// Any function `d(h)` ≥ 0 of the height above `earth`, tabulated from the ground to `top_m`
    /// on the same nodes as an atmosphere's air of that top (so tables of one atmosphere's
    /// constituents share their heights, pieces and majorant intervals).
    pub fn from_heights(earth: Earth, top_m: f64, d: impl Fn(f64) -> f64) -> AirProfile {
        let cells = (top_m / MAX_STEP_M).ceil() as usize;
        let step_m = top_m / cells as f64;
        let values: Vec<f64> = (0..=cells).map(|i| d(i as f64 * step_m)).collect();
        let mut max_above = values.clone();
        for i in (0..cells).rev() {
            max_above[i] = max_above[i].max(max_above[i + 1]);
        }
        AirProfile { earth, top_m, step_m, values: values.into(), max_above: max_above.into() }
    }

    /// The atmosphere's top, m: d = 0 at and above it.
    pub fn top_m(&self) -> f64 {
        self.top_m
    }

    /// d at height `h` (m).
    pub fn at_height(&self, h: f64) -> f64 {
        if h >= self.top_m {
            return 0.0;
        }
        if h <= 0.0 {
            return self.values[0];
        }
        let x = h / self.step_m;
        let i = (x as usize).min(self.values.len() - 2);
        let f = x - i as f64;
        self.values[i] + f * (self.values[i + 1] - self.values[i])
    }

    /// d at `p`.
    pub fn at(&self, p: DVec3) -> f64 {
        self.at_height(self.earth.height(p))
    }

    /// The height of `p` above the table's Earth, m.
    pub fn height(&self, p: DVec3) -> f64 {
        self.earth.height(p)
    }

    /// ∫₀ᵗ d(o + s·dir) ds by piecewise Gauss–Legendre quadrature below the top.
    pub fn integral(&self, o: DVec3, dir: DVec3, t: f64) -> f64 {
        let Some((a, b)) = self.below_top(o, dir, t) else { return 0.0 };
        if b.is_infinite() {
            // Down or level for ever under a flat Earth's top (never, in a scene with ground).
            return if self.values[0] > 0.0 { f64::INFINITY } else { 0.0 };
        }
        let n = pieces(b - a);
        gauss_legendre(&|s: f64| self.at(o + s * dir), a, b, n)
    }

    /// ∫₀ᵗ dₖ(o + s·dir) ds of several tables of one atmosphere (same Earth and top) into
    /// `out[k]`: the heights are found once per node, and each integral equals
    /// [`AirProfile::integral`] of that table to the bit.
    pub fn integrals(tables: &[&AirProfile], o: DVec3, dir: DVec3, t: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        let Some(first) = tables.first() else { return };
        let Some((a, b)) = first.below_top(o, dir, t) else { return };
        if b.is_infinite() {
            for (v, table) in out.iter_mut().zip(tables) {
                *v = if table.values[0] > 0.0 { f64::INFINITY } else { 0.0 };
            }
            return;
        }
        let n = pieces(b - a);
        let mut f = |s: f64, values: &mut [f64]| {
            let h = first.earth.height(o + s * dir);
            for (v, table) in values.iter_mut().zip(tables) {
                *v = table.at_height(h);
            }
        };
        crate::quadrature::gauss_legendre_many(&mut f, a, b, n, &mut out[..tables.len()]);
    }

    /// Pieces of at most 1 km below the top, each bounded by the running maximum at its lowest
    /// height, and bound 0 elsewhere; see [`super::Density::majorant_intervals`].
    pub fn majorant_intervals(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        self.pieces(o, dir, t_max, &mut |t0, t1, h| visit(t0, t1, self.bound_from(h)))
    }

    /// Calls `visit(t0, t1, h)` for consecutive intervals covering [0, t_max]: pieces of at most
    /// 1 km below the top with h the least height on each (−∞ for a ray down or level for ever
    /// under a flat Earth's top), and the parts above the top with h = +∞. `visit` returns false
    /// to stop. The pieces depend only on the Earth and the top, so tables of one atmosphere
    /// share them.
    pub fn pieces(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        let Some((a, b)) = self.below_top(o, dir, t_max) else {
            visit(0.0, t_max, f64::INFINITY);
            return;
        };
        if a > 0.0 && !visit(0.0, a, f64::INFINITY) {
            return;
        }
        if b.is_infinite() {
            // Down or level for ever under a flat Earth's top: one interval, bounded by the
            // largest value of the table.
            visit(a, b, f64::NEG_INFINITY);
            return;
        }
        let n = pieces(b - a);
        let dt = (b - a) / n as f64;
        for i in 0..n {
            let (t0, t1) = (a + i as f64 * dt, if i + 1 == n { b } else { a + (i + 1) as f64 * dt });
            if !visit(t0, t1, self.lowest_height(o, dir, t0, t1)) {
                return;
            }
        }
        if b < t_max {
            visit(b, t_max, f64::INFINITY);
        }
    }

    /// The largest tabulated value at or above height `h` (0 at and above the top; the largest
    /// of the table for h ≤ 0).
    pub fn bound_from(&self, h: f64) -> f64 {
        if h >= self.top_m {
            return 0.0;
        }
        let i = ((h.max(0.0) / self.step_m) as usize).min(self.values.len() - 1);
        self.max_above[i]
    }

    /// The least height on the segment o + t·dir, t ∈ [t0, t1].
    fn lowest_height(&self, o: DVec3, dir: DVec3, t0: f64, t1: f64) -> f64 {
        match &self.earth {
            Earth::Flat { up } => (o + t0 * dir).dot(*up).min((o + t1 * dir).dot(*up)),
            Earth::Spherical(s) => {
                let t = (-(o - s.centre).dot(dir)).clamp(t0, t1);
                self.earth.height(o + t * dir)
            }
        }
    }

    /// The part [a, b] of [0, t_max] where the ray o + t·dir is below the top, if any.
    fn below_top(&self, o: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, f64)> {
        let (a, b) = match &self.earth {
            Earth::Flat { up } => {
                let (h0, rate) = (o.dot(*up), dir.dot(*up));
                if rate == 0.0 {
                    if h0 < self.top_m { (0.0, t_max) } else { return None }
                } else {
                    let t_top = (self.top_m - h0) / rate;
                    if rate > 0.0 { (0.0, t_top) } else { (t_top, f64::INFINITY) }
                }
            }
            Earth::Spherical(s) => {
                let r = s.radius_m + self.top_m;
                let q = o - s.centre;
                let (half_b, c) = (q.dot(dir), q.length_squared() - r * r);
                let disc = half_b * half_b - c;
                if disc <= 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                (-half_b - root, -half_b + root)
            }
        };
        let (a, b) = (a.max(0.0), b.min(t_max));
        (a < b).then_some((a, b))
    }
}

/// Pieces of at most `PIECE_M` covering a length.
fn pieces(length: f64) -> usize {
    ((length / PIECE_M).ceil() as usize).max(1)
}

/// A point at height `h` above the ground point under the scene origin.
fn point_at_height(earth: &Earth, h: f64) -> DVec3 {
    match earth {
        Earth::Flat { up } => h * *up,
        Earth::Spherical(s) => {
            let up = (-s.centre).try_normalize().unwrap_or(DVec3::Y);
            s.centre + (s.radius_m + h) * up
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::usa76;

    fn usa76_profile() -> AirProfile {
        AirProfile::new(&Atmosphere::usa76(), Earth::standard(), 2.5e25).unwrap()
    }

    /// N(h)/N_ref straight from the standard's P and T (the molecular-scale temperature gives
    /// the exact density, see `usa76`).
    fn exact(h: f64) -> f64 {
        let s = usa76::at_geometric(h);
        s.pressure_pa * gas::AVOGADRO_PER_MOL / (gas::R_STAR * s.temperature_k) / 2.5e25
    }

    #[test]
    fn the_table_interpolates_the_standard_to_1e_7() {
        let p = usa76_profile();
        // Sea level: N = 2.547 × 10²⁵ m⁻³ (USA76 Table I: number density 2.5470E+25 at 0 m).
        assert!((p.at_height(0.0) * 2.5e25 / 2.5470e25 - 1.0).abs() < 1e-4);
        for k in 0..2000 {
            let h = 3.0 + k as f64 * 42.9; // between nodes, up to 85.8 km
            let (got, want) = (p.at_height(h), exact(h));
            assert!((got / want - 1.0).abs() < 1e-7, "h = {h}: {got} vs {want}");
        }
        assert_eq!(p.at_height(86_000.0), 0.0);
        assert_eq!(p.at_height(-10.0), p.at_height(0.0));
    }

    #[test]
    fn the_majorant_bounds_the_density_on_every_piece() {
        let p = usa76_profile();
        for (o, d) in [
            (DVec3::new(0.0, 3000.0, 0.0), DVec3::new(1.0, -0.05, 0.2).normalize()),
            (DVec3::new(0.0, 10.0, 0.0), DVec3::Y),
            (DVec3::new(-2e6, 2e5, 0.0), DVec3::new(1.0, -0.1, 0.0).normalize()),
        ] {
            let mut covered = 0.0;
            p.majorant_intervals(o, d, 3e6, &mut |t0, t1, bound| {
                assert_eq!(t0, covered, "intervals are consecutive");
                covered = t1;
                for k in 0..=40 {
                    let t = t0 + (t1 - t0) * k as f64 / 40.0;
                    assert!(p.at(o + t * d) <= bound, "t = {t}");
                }
                true
            });
            assert_eq!(covered, 3e6);
        }
    }

    #[test]
    fn a_vertical_column_integrates_the_standard() {
        // ∫₀^86 km N dh by Simpson's rule on the exact standard (1 m steps) against the table's
        // Gauss–Legendre integral up a vertical chord.
        let p = usa76_profile();
        let got = p.integral(DVec3::ZERO, DVec3::Y, 1e6);
        let n = 86_000;
        let simpson: f64 = (0..n / 2)
            .map(|i| {
                let h = 2.0 * i as f64;
                (exact(h) + 4.0 * exact(h + 1.0) + exact(h + 2.0)) / 3.0
            })
            .sum();
        assert!((got / simpson - 1.0).abs() < 1e-7, "{got} vs {simpson}");
    }
}
