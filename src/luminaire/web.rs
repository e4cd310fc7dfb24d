//! The photometric web: luminous intensity I(C, γ) in candela on a full grid of angles, the one
//! model every reader produces.
//!
//! # Angles and axes
//! A web is a grid over two angles about a polar axis: the plane angle C (degrees, about the
//! pole) and the polar angle γ (degrees from the pole, 0–180). [`WebAxes`] maps them to a unit
//! direction in the luminaire's own frame (x = C0 = length axis, y = C90, z = up):
//!
//! d(C, γ) = cos γ · pole + sin γ · (cos C · zero + sin C · quarter)
//!
//! - Type C (LM-63 type C, EULUMDAT, CIE 121 C-γ): pole = nadir (−z), zero = +x, quarter = +y,
//!   so C is counterclockwise seen from above and γ = 0 points straight down.
//! - Type A (LM-63): vertical angles V are elevations (γ = V + 90°) and horizontal angles H turn
//!   clockwise seen from above (quarter = −y), LM-63-2002 §3.
//! - Type B (LM-63; CIE 121 B-β): the pole is the luminaire's horizontal transverse axis (+y),
//!   H turns about it from nadir (zero = −z, quarter = +x) and V is the latitude from the
//!   equator, so γ = 90° − V.
//!
//! # Interpolation
//! I is interpolated bilinearly in (C, cos γ) between grid nodes. In C the grid is periodic when
//! it covers the full circle (C and C + 360° are the same plane; a single plane is rotationally
//! symmetric); a web that covers only part of the circle (type A/B, −90° ≤ H ≤ 90°) emits nothing
//! outside it. Outside [γ_first, γ_last] I = 0 (a file with γ = 0–90° emits only downward). At a
//! pole (γ = 0° or 180° on a periodic grid) every plane meets in one direction, so the node values
//! there are replaced by their mean over the planes (weighted by the C-interval each plane
//! stands for); files normally agree there, and [`PhotometricWeb::pole_note`] says when not.
//!
//! # Flux
//! Since dω = dC d(cos γ), the interpolant integrates exactly cell by cell:
//!
//! Φ = ∫ I dω = Σ_cells ΔC · Δ(cos γ) · (I₀₀ + I₁₀ + I₀₁ + I₁₁)/4     (ΔC in radians),
//!
//! the trapezoidal rule in (C, cos γ) — the zonal-lumen summation of IES LM-63/CIE 121 with
//! zones bounded at the grid angles. The same cell integrals drive photon emission
//! ([`super::WebSampler`]), so emitted photons carry exactly this flux.
//!
//! # References
//! - ANSI/IES LM-63-2002 (R2008) and LM-63-2019, *Standard File Format for the Electronic
//!   Transfer of Photometric Data*, §3 (definitions of types A, B, C and their angles).
//! - CIE 121-1996, *The Photometry and Goniophotometry of Luminaires*, §2 (C-γ and B-β systems,
//!   luminous flux from intensity by zonal summation).

use glam::DVec3;

/// Maps a web's (C, γ) to directions in the luminaire frame (see the module docs).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct WebAxes {
    /// Unit polar axis (γ = 0).
    pub pole: DVec3,
    /// Unit direction of the plane C = 0 (at γ = 90°).
    pub zero: DVec3,
    /// Unit direction of the plane C = 90° (at γ = 90°).
    pub quarter: DVec3,
}

impl WebAxes {
    /// Type C: pole at the nadir, C0 along +x, C counterclockwise seen from above.
    pub const TYPE_C: WebAxes = WebAxes { pole: DVec3::NEG_Z, zero: DVec3::X, quarter: DVec3::Y };
    /// Type A: pole at the nadir, H clockwise seen from above.
    pub const TYPE_A: WebAxes = WebAxes { pole: DVec3::NEG_Z, zero: DVec3::X, quarter: DVec3::NEG_Y };
    /// Type B: pole along the transverse axis +y, H from the nadir.
    pub const TYPE_B: WebAxes = WebAxes { pole: DVec3::Y, zero: DVec3::NEG_Z, quarter: DVec3::X };

    /// The unit direction at plane angle `c_deg` and polar cosine `cos_gamma`.
    pub fn direction_cos(&self, c_deg: f64, cos_gamma: f64) -> DVec3 {
        let z = cos_gamma.clamp(-1.0, 1.0);
        let s = (1.0 - z * z).max(0.0).sqrt();
        let (sc, cc) = c_deg.to_radians().sin_cos();
        z * self.pole + s * (cc * self.zero + sc * self.quarter)
    }

    /// The unit direction at (C, γ) in degrees.
    pub fn direction(&self, c_deg: f64, gamma_deg: f64) -> DVec3 {
        self.direction_cos(c_deg, gamma_deg.to_radians().cos())
    }

    /// (C in [0°, 360°), cos γ) of a unit direction.
    pub fn angles_cos(&self, d: DVec3) -> (f64, f64) {
        let c = d.dot(self.quarter).atan2(d.dot(self.zero)).to_degrees().rem_euclid(360.0);
        (c, d.dot(self.pole).clamp(-1.0, 1.0))
    }
}

/// One cell of the grid: C from `c0` to `c1` (degrees), cos γ from `z0` down to `z1`, and the
/// intensities at its corners [(c0, z0), (c1, z0), (c0, z1), (c1, z1)].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Cell {
    /// First plane angle C, degrees.
    pub c0: f64,
    /// Last plane angle C, degrees.
    pub c1: f64,
    /// cos γ at the cell's first polar angle (the larger cosine).
    pub z0: f64,
    /// cos γ at the cell's last polar angle (z1 ≤ z0).
    pub z1: f64,
    /// Intensities at the corners (c0, z0), (c1, z0), (c0, z1), (c1, z1), cd.
    pub cd: [f64; 4],
}

impl Cell {
    /// ∫ I dω over the cell (lm): ΔC Δz times the mean of the corners.
    pub fn flux(&self) -> f64 {
        (self.c1 - self.c0).to_radians() * (self.z0 - self.z1) * 0.25 * self.cd.iter().sum::<f64>()
    }
}

/// Intensity in candela on a grid of angles; see the module docs.
#[derive(Clone, Debug, PartialEq)]
pub struct PhotometricWeb {
    axes: WebAxes,
    c_deg: Vec<f64>,
    periodic: bool,
    gamma_deg: Vec<f64>,
    cos_gamma: Vec<f64>,
    /// `cd[i * ng + j]`: plane i, polar angle j.
    cd: Vec<f64>,
    pole_note: Option<String>,
}

impl PhotometricWeb {
    /// A web from planes `c_deg` (strictly ascending; spanning less than 360° when `periodic`),
    /// polar angles `gamma_deg` (strictly ascending within 0–180°, at least two) and intensities
    /// `cd[i * ng + j]` (finite, ≥ 0). The error says which of these is violated.
    pub fn new(
        axes: WebAxes,
        c_deg: Vec<f64>,
        periodic: bool,
        gamma_deg: Vec<f64>,
        cd: Vec<f64>,
    ) -> Result<PhotometricWeb, String> {
        let (nc, ng) = (c_deg.len(), gamma_deg.len());
        if nc == 0 || (!periodic && nc < 2) {
            return Err(format!("a web needs at least {} plane(s), found {nc}", if periodic { 1 } else { 2 }));
        }
        if ng < 2 {
            return Err(format!("a web needs at least two polar angles, found {ng}"));
        }
        if !strictly_ascending(&c_deg) || c_deg.iter().any(|c| !c.is_finite()) {
            return Err("plane angles must be finite and strictly ascending".into());
        }
        if periodic && c_deg[nc - 1] - c_deg[0] >= 360.0 {
            return Err("a periodic web's planes must span less than 360°".into());
        }
        if !strictly_ascending(&gamma_deg) || gamma_deg[0] < 0.0 || gamma_deg[ng - 1] > 180.0 {
            return Err("polar angles must be strictly ascending within 0–180°".into());
        }
        if cd.len() != nc * ng {
            return Err(format!("{nc} planes × {ng} angles need {} intensities, found {}", nc * ng, cd.len()));
        }
        if let Some(x) = cd.iter().find(|x| !(x.is_finite() && **x >= 0.0)) {
            return Err(format!("intensities must be finite and ≥ 0, found {x}"));
        }
        let cos_gamma = gamma_deg.iter().map(|g| g.to_radians().cos()).collect();
        let mut web = PhotometricWeb { axes, c_deg, periodic, gamma_deg, cos_gamma, cd, pole_note: None };
        web.unify_poles();
        if !web.flux_lm().is_finite() {
            return Err("the intensities are too large: their flux overflows".into());
        }
        Ok(web)
    }

    fn unify_poles(&mut self) {
        let ng = self.gamma_deg.len();
        let nc = self.c_deg.len();
        if !self.periodic || nc < 2 {
            return;
        }
        let weights: Vec<f64> = (0..nc).map(|i| self.c_cell_width(i) + self.c_cell_width((i + nc - 1) % nc)).collect();
        let total: f64 = weights.iter().sum();
        let mut notes = Vec::new();
        for (j, pole) in [(0, 0.0), (ng - 1, 180.0)] {
            if self.gamma_deg[j] != pole {
                continue;
            }
            let values: Vec<f64> = (0..nc).map(|i| self.cd[i * ng + j]).collect();
            let mean = values.iter().zip(&weights).map(|(v, w)| v * w).sum::<f64>() / total;
            let (lo, hi) = values.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), v| (lo.min(*v), hi.max(*v)));
            if hi - lo > 0.01 * hi {
                notes
                    .push(format!("at γ = {pole}° the planes give {lo}–{hi} cd; the web uses their mean {mean:.4} cd"));
            }
            for i in 0..nc {
                self.cd[i * ng + j] = mean;
            }
        }
        self.pole_note = (!notes.is_empty()).then(|| notes.join("; "));
    }

    /// Width in degrees of the C-interval that starts at plane `i`.
    fn c_cell_width(&self, i: usize) -> f64 {
        let nc = self.c_deg.len();
        if i + 1 < nc {
            self.c_deg[i + 1] - self.c_deg[i]
        } else if self.periodic {
            self.c_deg[0] + 360.0 - self.c_deg[i]
        } else {
            0.0
        }
    }

    /// How (C, γ) map to directions.
    pub fn axes(&self) -> &WebAxes {
        &self.axes
    }
    /// Plane angles C of the grid, degrees, increasing.
    pub fn c_deg(&self) -> &[f64] {
        &self.c_deg
    }
    /// Polar angles γ of the grid, degrees, increasing.
    pub fn gamma_deg(&self) -> &[f64] {
        &self.gamma_deg
    }
    /// True when the planes cover the full circle (C and C + 360° are the same plane).
    pub fn periodic(&self) -> bool {
        self.periodic
    }
    /// Intensity at node (plane i, polar angle j), cd.
    pub fn node(&self, i: usize, j: usize) -> f64 {
        self.cd[i * self.gamma_deg.len() + j]
    }
    /// Set when the planes disagreed at a pole (see the module docs).
    pub fn pole_note(&self) -> Option<&str> {
        self.pole_note.as_deref()
    }

    /// The web with every intensity multiplied by `k`.
    pub fn scaled(mut self, k: f64) -> PhotometricWeb {
        self.cd.iter_mut().for_each(|x| *x *= k);
        self
    }

    /// The grid cells, plane-interval by plane-interval.
    pub fn cells(&self) -> impl Iterator<Item = Cell> + '_ {
        let (nc, ng) = (self.c_deg.len(), self.gamma_deg.len());
        let c_cells = if self.periodic { nc } else { nc - 1 };
        (0..c_cells).flat_map(move |i| {
            let i1 = (i + 1) % nc;
            let (c0, c1) = (self.c_deg[i], self.c_deg[i] + self.c_cell_width(i));
            (0..ng - 1).map(move |j| Cell {
                c0,
                c1,
                z0: self.cos_gamma[j],
                z1: self.cos_gamma[j + 1],
                cd: [self.node(i, j), self.node(i1, j), self.node(i, j + 1), self.node(i1, j + 1)],
            })
        })
    }

    /// Φ = ∫ I dω by the web's own quadrature (module docs), lm.
    pub fn flux_lm(&self) -> f64 {
        self.cells().map(|c| c.flux()).sum()
    }

    /// ∫ I dω over the directions with cos γ in [z_lo, z_hi] (exact for the interpolant, which is
    /// linear in cos γ within a cell), lm.
    pub fn flux_between_lm(&self, z_lo: f64, z_hi: f64) -> f64 {
        let mut sum = 0.0;
        for cell in self.cells() {
            let (a, b) = (cell.z1.max(z_lo), cell.z0.min(z_hi));
            if b <= a {
                continue;
            }
            let at = |z: f64| {
                let t = (cell.z0 - z) / (cell.z0 - cell.z1);
                let top = 0.5 * (cell.cd[0] + cell.cd[1]);
                let bottom = 0.5 * (cell.cd[2] + cell.cd[3]);
                top + t * (bottom - top)
            };
            sum += (cell.c1 - cell.c0).to_radians() * (b - a) * 0.5 * (at(a) + at(b));
        }
        sum
    }

    /// Intensity at (C, cos γ) by bilinear interpolation in (C, cos γ); cd.
    pub fn intensity_cos(&self, c_deg: f64, cos_gamma: f64) -> f64 {
        let Some((j, t)) = self.gamma_slot(cos_gamma) else {
            return 0.0;
        };
        let Some((i, i1, s)) = self.c_slot(c_deg) else {
            return 0.0;
        };
        let lerp = |a: f64, b: f64, t: f64| a + t * (b - a);
        let top = lerp(self.node(i, j), self.node(i1, j), s);
        let bottom = lerp(self.node(i, j + 1), self.node(i1, j + 1), s);
        lerp(top, bottom, t)
    }

    /// Intensity at (C, γ) in degrees, cd.
    pub fn intensity_at(&self, c_deg: f64, gamma_deg: f64) -> f64 {
        if !(self.gamma_deg[0]..=self.gamma_deg[self.gamma_deg.len() - 1]).contains(&gamma_deg) {
            return 0.0;
        }
        self.intensity_cos(c_deg, gamma_deg.to_radians().cos())
    }

    /// Intensity toward the unit direction `d` of the luminaire frame, cd.
    pub fn intensity(&self, d: DVec3) -> f64 {
        let (c, z) = self.axes.angles_cos(d);
        self.intensity_cos(c, z)
    }

    /// The polar interval j and the fraction t of the way from cos γ_j to cos γ_{j+1}.
    fn gamma_slot(&self, z: f64) -> Option<(usize, f64)> {
        let zs = &self.cos_gamma;
        let n = zs.len();
        // cos γ descends; tolerate rounding at the ends.
        let eps = 1e-12;
        if z > zs[0] + eps || z < zs[n - 1] - eps {
            return None;
        }
        let j = zs.partition_point(|&x| x > z).saturating_sub(1).min(n - 2);
        let t = ((zs[j] - z) / (zs[j] - zs[j + 1])).clamp(0.0, 1.0);
        Some((j, t))
    }

    /// Planes i and i1 around C and the fraction s of the way from i to i1.
    fn c_slot(&self, c_deg: f64) -> Option<(usize, usize, f64)> {
        let cs = &self.c_deg;
        let n = cs.len();
        let x = cs[0] + (c_deg - cs[0]).rem_euclid(360.0);
        if n == 1 {
            return Some((0, 0, 0.0));
        }
        if !self.periodic && x > cs[n - 1] {
            // Rounding can put a direction on the first plane at c0 + 360°.
            return ((x - cs[0] - 360.0).abs() < 1e-9).then_some((0, 1, 0.0));
        }
        let i = cs.partition_point(|&c| c <= x).saturating_sub(1);
        let i1 = (i + 1) % n;
        let w = self.c_cell_width(i);
        let s = if w > 0.0 { ((x - cs[i]) / w).clamp(0.0, 1.0) } else { 0.0 };
        Some((i, i1, s))
    }

    /// The largest node intensity and its (C, γ), in the web's own angles.
    pub fn peak(&self) -> (f64, f64, f64) {
        let ng = self.gamma_deg.len();
        let (mut best, mut at) = (-1.0, (0.0, 0.0));
        for (k, &v) in self.cd.iter().enumerate() {
            if v > best {
                best = v;
                at = (self.c_deg[k / ng], self.gamma_deg[k % ng]);
            }
        }
        (best.max(0.0), at.0, at.1)
    }
}

fn strictly_ascending(v: &[f64]) -> bool {
    v.windows(2).all(|w| w[0] < w[1])
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    fn grid(n: usize, lo: f64, hi: f64) -> Vec<f64> {
        (0..n).map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64).collect()
    }

    fn web_from(c: Vec<f64>, periodic: bool, g: Vec<f64>, f: impl Fn(f64, f64) -> f64) -> PhotometricWeb {
        let cd = c.iter().flat_map(|ci| g.iter().map(|gj| f(*ci, *gj)).collect::<Vec<_>>()).collect();
        PhotometricWeb::new(WebAxes::TYPE_C, c, periodic, g, cd).unwrap()
    }

    #[test]
    fn an_isotropic_web_has_flux_four_pi_i_and_is_exact_everywhere() {
        let w = web_from(vec![0.0], true, grid(3, 0.0, 180.0), |_, _| 100.0);
        assert!((w.flux_lm() - 400.0 * PI).abs() < 1e-9);
        for (c, g) in [(0.0, 0.0), (123.0, 45.0), (359.9, 180.0), (-20.0, 90.0)] {
            assert!((w.intensity_at(c, g) - 100.0).abs() < 1e-12);
        }
    }

    #[test]
    fn a_cosine_web_integrates_to_pi_i0_in_the_lower_hemisphere() {
        // I = I0 cos γ for γ ≤ 90°: Φ = 2π I0 ∫₀¹ z dz = π I0; linear in cos γ, so exact.
        let w = web_from(vec![0.0, 90.0, 180.0, 270.0], true, grid(7, 0.0, 90.0), |_, g| 50.0 * g.to_radians().cos());
        assert!((w.flux_lm() - 50.0 * PI).abs() < 1e-9, "{}", w.flux_lm());
        assert!((w.flux_between_lm(0.0, 1.0) - 50.0 * PI).abs() < 1e-9);
        // Half the flux lies within cos γ ≥ 1/√2: ∫ z dz from 1/√2 to 1 = 1/4 = half of 1/2.
        assert!((w.flux_between_lm(0.5f64.sqrt(), 1.0) - 25.0 * PI).abs() < 1e-9);
        assert_eq!(w.intensity_at(0.0, 120.0), 0.0);
    }

    #[test]
    fn interpolation_hits_the_nodes_and_wraps_in_c() {
        let c = vec![0.0, 90.0, 180.0, 270.0];
        let w = web_from(c, true, grid(3, 0.0, 90.0), |c, g| 1.0 + c + 1000.0 * g / 90.0);
        // Poles are unified: at γ = 0 every plane gives the weighted mean of 1, 91, 181, 271.
        assert!((w.intensity_at(0.0, 0.0) - 136.0).abs() < 1e-9);
        assert!((w.intensity_at(90.0, 45.0) - 591.0).abs() < 1e-9);
        assert!((w.intensity_at(270.0, 90.0) - 1271.0).abs() < 1e-9);
        // Between C270 and C360 = C0 the planes wrap: halfway at C315, γ = 90°.
        assert!((w.intensity_at(315.0, 90.0) - 0.5 * (1271.0 + 1001.0)).abs() < 1e-9);
        assert!((w.intensity_at(-45.0, 90.0) - 0.5 * (1271.0 + 1001.0)).abs() < 1e-9);
        assert!(w.pole_note().is_some(), "planes disagreed at the nadir");
    }

    #[test]
    fn directions_and_angles_round_trip_for_every_type() {
        for axes in [WebAxes::TYPE_A, WebAxes::TYPE_B, WebAxes::TYPE_C] {
            for (c, g) in [(10.0, 20.0), (200.0, 100.0), (359.0, 179.0), (90.0, 90.0)] {
                let d = axes.direction(c, g);
                assert!((d.length() - 1.0).abs() < 1e-12);
                let (c2, z) = axes.angles_cos(d);
                assert!((c2 - c).abs() < 1e-9 && (z - g.to_radians().cos()).abs() < 1e-12, "{axes:?} {c} {g}");
            }
        }
        // Type C: γ = 0 is nadir, C90 is +y. Type B: H = V = 0 is nadir, V = 90° (γ = 0) is +y.
        assert!((WebAxes::TYPE_C.direction(0.0, 0.0) - DVec3::NEG_Z).length() < 1e-12);
        assert!((WebAxes::TYPE_C.direction(90.0, 90.0) - DVec3::Y).length() < 1e-12);
        assert!((WebAxes::TYPE_B.direction(0.0, 90.0) - DVec3::NEG_Z).length() < 1e-12);
        assert!((WebAxes::TYPE_B.direction(90.0, 90.0) - DVec3::X).length() < 1e-12);
        assert!((WebAxes::TYPE_A.direction(90.0, 90.0) - DVec3::NEG_Y).length() < 1e-12);
    }

    #[test]
    fn a_partial_web_is_dark_outside_its_planes() {
        let w = web_from(vec![-90.0, 0.0, 90.0], false, grid(5, 0.0, 180.0), |_, _| 10.0);
        assert_eq!(w.intensity_at(120.0, 90.0), 0.0);
        assert_eq!(w.intensity_at(-45.0, 90.0), 10.0);
        // Half the sphere: 2π sr × 10 cd.
        assert!((w.flux_lm() - 20.0 * PI).abs() < 1e-9);
    }

    #[test]
    fn bad_grids_are_rejected_with_a_reason() {
        let bad = |c: Vec<f64>, p, g: Vec<f64>, n| PhotometricWeb::new(WebAxes::TYPE_C, c, p, g, vec![1.0; n]);
        assert!(bad(vec![], true, vec![0.0, 90.0], 0).is_err());
        assert!(bad(vec![0.0], false, vec![0.0, 90.0], 2).is_err());
        assert!(bad(vec![0.0], true, vec![0.0], 1).is_err());
        assert!(bad(vec![0.0, 0.0], true, vec![0.0, 90.0], 4).is_err());
        assert!(bad(vec![0.0, 360.0], true, vec![0.0, 90.0], 4).is_err());
        assert!(bad(vec![0.0], true, vec![0.0, 190.0], 2).is_err());
        assert!(bad(vec![0.0], true, vec![0.0, 90.0], 3).is_err());
        let neg = PhotometricWeb::new(WebAxes::TYPE_C, vec![0.0], true, vec![0.0, 90.0], vec![1.0, -1.0]);
        assert!(neg.unwrap_err().contains("≥ 0"));
        let huge = PhotometricWeb::new(WebAxes::TYPE_C, vec![0.0], true, vec![0.0, 90.0], vec![1e308, 1e308]);
        assert!(huge.unwrap_err().contains("overflows"));
    }

    #[test]
    fn peak_names_the_largest_node() {
        let w = web_from(
            vec![0.0, 180.0],
            true,
            grid(4, 0.0, 90.0),
            |c, g| if c == 180.0 && g == 60.0 { 9.0 } else { 1.0 },
        );
        assert_eq!(w.peak(), (9.0, 180.0, 60.0));
    }
}
