//! A directional light: parallel rays of spectral irradiance E(λ) (normal to the beam) from
//! infinitely far away.
//!
//! Photons start on a rectangle perpendicular to the beam, one scene radius upstream of the
//! scene: by default the square around the scene's bounding sphere, so the emitted flux is
//! Φ = A_beam ∫E dλ; a directional light's power is only defined relative to the region it
//! lights, and `report.json` states it. A scene may limit the beam to the rays through a target
//! box (`target_min`, `target_max` — e.g. a window): photons then start on the box's shadow on
//! the emitting plane (the convex hull of its corners' projections, in the frame of the smallest
//! rectangle around it: [`crate::geometry::min_rect`]), so every straight photon path crosses
//! the box and none is spent on walls no camera sees, and shadow rays see the light only inside
//! that beam, so both passes simulate the same, limited, light.
//!
//! A light of finite angular size (the sun: angular diameter 0.53°) is a uniformly bright disc
//! of angular radius θ_m: its rays cross the beam plane with the direction density
//! cos θ/(π sin²θ_m) about the axis ([`crate::sampling::cosine_cone`]), and an eye ray looking
//! into the disc sees the radiance L(λ) = E(λ)/(π sin²θ_m), since E = ∫_disc L cos θ dω.
//! With limb darkening ([`LimbDarkening`]) the disc's radiance falls toward its edge as the
//! law's P(λ, μ), scaled so that E stays the same: L(λ, r) = E(λ) P(λ, μ(r))/(π sin²θ_m F(λ)).
//! Photons then draw their direction from P at their own wavelength (weight 1 again), and shadow
//! rays draw it from P at the middle of the simulated range, tabulated ([`DiskTable`]: density q
//! relative to uniform in projected solid angle), with the weight (P/F)/q per wavelength
//! ([`DirectionalLight::disc_factor`] and the sample's weight).

use crate::geometry::Frame;
use crate::geometry::convex_polygon::ConvexPolygon;
use glam::DVec3;

use super::limb_darkening::DiskTable;
use super::{Incident, LightSpectrum, LimbDarkening};

/// Parallel light from infinitely far away, possibly a disc of finite angular size (see the module
/// docs).
#[derive(Clone, Debug)]
pub struct DirectionalLight {
    /// Unit direction the light travels in.
    pub dir: DVec3,
    /// Centre and radius of the scene's bounding sphere.
    pub scene_centre: DVec3,
    /// Radius of the scene's bounding sphere, m.
    pub scene_radius: f64,
    /// The frame of the beam's cross-section: `n` = `dir`; with a target, `s` and `t` along the
    /// sides of the smallest rectangle around the target's projection.
    pub frame: Frame,
    /// The beam's cross-section in `frame`: (s, t) ranges.
    pub beam: [[f64; 2]; 2],
    /// Spectral irradiance normal to the beam, W m⁻² nm⁻¹.
    pub emission: LightSpectrum,
    /// sin θ_m of the disc's angular radius; 0 for a collimated beam.
    pub sin_max: f64,
    /// How the disc's radiance falls from its centre to its edge.
    pub limb: LimbDarkening,
    /// With limb darkening: where shadow rays sample the disc ([`DiskTable`]).
    pub disk: Option<DiskTable>,
    /// The box the beam is aimed at, if the scene gave one.
    pub target: Option<crate::geometry::Aabb>,
    /// With a target (and a shadow of some area): the target box's shadow along the light in
    /// `frame`'s (s, t), the convex polygon photons start from unless a projection map's cells
    /// replace it.
    pub shadow: Option<Box<ConvexPolygon>>,
    /// Where paths curve, the cells of the beam whose light reaches the target (a projection
    /// map, see [`crate::raypath::projection`]); `None`: the whole rectangle.
    pub cells: Option<Box<BeamCells>>,
}

/// A projection map of a beam: the cells of a regular grid over the beam's cross-section from
/// which light reaches the target, drawn uniformly (each cell has the same area).
#[derive(Clone, Debug, PartialEq)]
pub struct BeamCells {
    /// The grid's corner (s, t) and cell size, m.
    pub origin: [f64; 2],
    /// Cell size along s and t, m.
    pub size: [f64; 2],
    /// The (i, j) indices of the cells that emit.
    pub cells: Vec<[u32; 2]>,
    /// For a disc (the sun): how far, in (s, t), the cells move for a direction at the disc's
    /// edge toward +s and toward +t — its rays cross the air elsewhere and bend differently (a
    /// low sun's lower limb is lifted more than its upper) — interpolated linearly over the disc.
    pub disc_shift: Option<[[f64; 2]; 2]>,
}

impl BeamCells {
    /// Emitting area of the beam: cells × cell area, m².
    pub fn area(&self) -> f64 {
        self.cells.len() as f64 * self.size[0] * self.size[1]
    }

    /// A uniform point (s, t) on the marked cells.
    fn sample(&self, u: [f64; 2]) -> [f64; 2] {
        let k = self.cells.len() as f64 * u[0];
        let i = (k as usize).min(self.cells.len() - 1);
        let v = k - i as f64;
        let [ci, cj] = self.cells[i];
        [self.origin[0] + (ci as f64 + v) * self.size[0], self.origin[1] + (cj as f64 + u[1]) * self.size[1]]
    }

    fn contains(&self, s: f64, t: f64) -> bool {
        let i = ((s - self.origin[0]) / self.size[0]).floor();
        let j = ((t - self.origin[1]) / self.size[1]).floor();
        i >= 0.0 && j >= 0.0 && self.cells.binary_search(&[i as u32, j as u32]).is_ok()
    }
}

impl DirectionalLight {
    /// A light covering the scene's bounding sphere, or only the beam through `target`.
    pub fn new(
        dir: DVec3,
        scene_centre: DVec3,
        scene_radius: f64,
        target: Option<(DVec3, DVec3)>,
        emission: LightSpectrum,
    ) -> DirectionalLight {
        let base = Frame::from_normal(dir);
        let (frame, beam, shadow) = match target {
            None => (base, [[-scene_radius, scene_radius], [-scene_radius, scene_radius]], None),
            Some((lo, hi)) => aimed_beam(&base, scene_centre, lo, hi),
        };
        let target = target.map(|(min, max)| crate::geometry::Aabb { min, max });
        DirectionalLight {
            dir,
            scene_centre,
            scene_radius,
            frame,
            beam,
            emission,
            sin_max: 0.0,
            limb: LimbDarkening::Uniform,
            disk: None,
            target,
            shadow,
            cells: None,
        }
    }

    /// The same light as a uniformly bright disc of angular diameter `diameter_deg`.
    pub fn with_angular_diameter(mut self, diameter_deg: f64) -> DirectionalLight {
        self.sin_max = (0.5 * diameter_deg).to_radians().sin();
        self
    }

    /// The same disc with the limb darkening `limb`; shadow rays sample it as its law has it at
    /// `reference_nm` (the middle of the simulated range, say).
    pub fn with_limb_darkening(mut self, limb: LimbDarkening, reference_nm: f64) -> DirectionalLight {
        self.limb = limb;
        self.disk = (limb != LimbDarkening::Uniform).then(|| DiskTable::new(limb, reference_nm));
        self
    }

    /// A direction of travel: the axis for a collimated beam, else cosine-distributed within the
    /// disc's cone about it (uniform in projected solid angle), for shadow rays and for a
    /// uniformly bright disc's photons.
    pub fn sample_dir(&self, u: [f64; 2]) -> DVec3 {
        if self.sin_max == 0.0 {
            return self.dir;
        }
        Frame::from_normal(self.dir).to_world(crate::sampling::cosine_cone(u, self.sin_max)).normalize()
    }

    /// A photon's direction of travel at `wavelength_nm`: distributed as the disc's L cos θ, that
    /// is, uniform in projected solid angle for a uniform disc, P(λ, μ)/F for a limb-darkened one.
    pub fn sample_photon_dir(&self, u: [f64; 2], wavelength_nm: f64) -> DVec3 {
        if self.sin_max == 0.0 || self.limb == LimbDarkening::Uniform {
            return self.sample_dir(u);
        }
        let [x, y] = self.limb.sample_disk(wavelength_nm, u);
        self.disk_dir(x, y)
    }

    /// The direction of travel through point (x, y) of the unit disk of the disc's projected
    /// solid angle.
    fn disk_dir(&self, x: f64, y: f64) -> DVec3 {
        let (x, y) = (x * self.sin_max, y * self.sin_max);
        let local = DVec3::new(x, y, (1.0 - x * x - y * y).max(0.0).sqrt());
        Frame::from_normal(self.dir).to_world(local).normalize()
    }

    /// The factor L/E seen by an eye ray travelling along `view_dir` at `wavelength_nm`:
    /// P/(π sin²θ_m F) inside the disc (1/(π sin²θ_m) for a uniform one), 0 outside it and for a
    /// collimated beam (which no ray can hit).
    pub fn radiance_factor(&self, view_dir: DVec3, wavelength_nm: f64) -> f64 {
        let cos_max = (1.0 - self.sin_max * self.sin_max).sqrt();
        if self.sin_max > 0.0 && -view_dir.dot(self.dir) >= cos_max {
            self.disc_factor(-view_dir, wavelength_nm) / (std::f64::consts::PI * self.sin_max * self.sin_max)
        } else {
            0.0
        }
    }

    /// The disc's radiance toward `wi` (the direction from a receiver toward the light) over
    /// its mean radiance, P/F at `wavelength_nm`: exactly 1 for a uniform disc and a collimated
    /// beam. A shadow ray's sample carries this factor beside its weight 1/q.
    pub fn disc_factor(&self, wi: DVec3, wavelength_nm: f64) -> f64 {
        if self.limb == LimbDarkening::Uniform || self.sin_max == 0.0 {
            return 1.0;
        }
        // sin θ from the cross product: accurate for the sun's small angles.
        let r = (wi.cross(-self.dir).length() / self.sin_max).min(1.0);
        self.limb.relative_radiance(wavelength_nm, r)
    }

    /// Area of the beam's cross-section (of its projection map's cells, when it has one), m².
    pub fn beam_area(&self) -> f64 {
        match (&self.cells, &self.shadow) {
            (Some(c), _) => c.area(),
            (None, Some(p)) => p.area(),
            (None, None) => (self.beam[0][1] - self.beam[0][0]) * (self.beam[1][1] - self.beam[1][0]),
        }
    }

    /// With a target and no projection map: the fraction of the beam's photons whose straight
    /// paths cross the target box (its shadow's area over the beam's: 1 when the beam is the
    /// shadow).
    pub fn on_target(&self) -> Option<f64> {
        let shadow = self.shadow.as_ref()?;
        self.cells.is_none().then(|| shadow.area() / self.beam_area())
    }

    /// The point of the emitting plane at beam coordinates (s, t).
    pub fn plane_point(&self, s: f64, t: f64) -> DVec3 {
        self.scene_centre - self.dir * (1.001 * self.scene_radius) + s * self.frame.s + t * self.frame.t
    }

    /// Φ = A_beam ∫ E dλ within the scene's wavelength range, W.
    pub fn power_w(&self) -> f64 {
        self.beam_area() * self.emission.integral()
    }

    /// A photon's origin and direction: a uniform point (s, t) of the beam's cross-section (or
    /// its projection map's cells) from `u_pos`, a direction from `u_dir`. A direction off the
    /// axis is aimed through the same (s, t) at the depth of the target (the scene's centre
    /// without one): the origin moves by (axis − ω)·L on the emitting plane, L the distance from
    /// the plane to that depth. So every direction of the disc lights the target with E — as
    /// the sun's rays from each point of its disc all reach the target — instead of spreading
    /// by ±θ_m·L around it (±50 km from a plane 11 000 km upstream in an Earth-sized scene).
    pub fn emit(&self, u_pos: [f64; 2], u_dir: [f64; 2], wavelength_nm: f64) -> (DVec3, DVec3) {
        let dir = self.sample_photon_dir(u_dir, wavelength_nm);
        let [mut s, mut t] = self.emit_st(u_pos);
        if let Some([ds, dt]) = self.cells.as_ref().and_then(|c| c.disc_shift)
            && self.sin_max > 0.0
        {
            let (x, y) = (dir.dot(self.frame.s) / self.sin_max, dir.dot(self.frame.t) / self.sin_max);
            s += x * ds[0] + y * dt[0];
            t += x * ds[1] + y * dt[1];
        }
        (self.aimed_origin(self.plane_point(s, t), dir), dir)
    }

    /// Where a ray of direction `dir` starts on the emitting plane so that it crosses the aim
    /// plane (L along the axis) where the axial ray from `origin` does: the ray origin′ + ω·x
    /// meets it at origin + axis·L when origin′ = origin + (axis − ω/(ω·axis))·L.
    pub fn aimed_origin(&self, origin: DVec3, dir: DVec3) -> DVec3 {
        if self.sin_max == 0.0 {
            return origin;
        }
        origin + (self.dir - dir / dir.dot(self.dir)) * self.aim_distance()
    }

    /// Distance along the axis from the emitting plane to the depth photons are aimed at: the
    /// target box's centre, else the scene's centre.
    fn aim_distance(&self) -> f64 {
        let plane = self.plane_point(0.0, 0.0);
        let aim = self.target.as_ref().map_or(self.scene_centre, |b| 0.5 * (b.min + b.max));
        (aim - plane).dot(self.dir)
    }

    /// A uniform point (s, t) of the beam's cross-section or of its projection map's cells.
    fn emit_st(&self, u: [f64; 2]) -> [f64; 2] {
        match (&self.cells, &self.shadow) {
            (Some(c), _) => c.sample(u),
            (None, Some(p)) => p.sample(u),
            (None, None) => [
                self.beam[0][0] + u[0] * (self.beam[0][1] - self.beam[0][0]),
                self.beam[1][0] + u[1] * (self.beam[1][1] - self.beam[1][0]),
            ],
        }
    }

    /// Whether the beam passes through `p` (along straight rays: used by shadow rays, which
    /// only run where paths are straight).
    pub fn lights(&self, p: DVec3) -> bool {
        let (s, t) = ((p - self.scene_centre).dot(self.frame.s), (p - self.scene_centre).dot(self.frame.t));
        let in_rect =
            (self.beam[0][0]..=self.beam[0][1]).contains(&s) && (self.beam[1][0]..=self.beam[1][1]).contains(&t);
        let in_shadow = || self.shadow.as_ref().is_none_or(|p| p.contains([s, t], SHADOW_EDGE_M));
        in_rect
            && match &self.cells {
                Some(c) => c.contains(s, t),
                None => in_shadow(),
            }
    }

    /// Irradiance normal to the beam is E, so weight = 1 toward −dir (or toward a direction
    /// sampled in the disc, whose cosine density makes the weight 1 again) at infinite distance.
    /// A limb-darkened disc is sampled from its [`DiskTable`], the weight 1/q.
    pub fn incident(&self, p: DVec3, u: [f64; 2]) -> Option<Incident> {
        if !self.lights(p) {
            return None;
        }
        match (&self.disk, self.sin_max > 0.0) {
            (Some(table), true) => {
                let ([x, y], q) = table.sample(u);
                let wi = -self.disk_dir(x, y);
                Some(Incident { wi, dist: f64::INFINITY, weight: 1.0 / q })
            }
            _ => Some(Incident { wi: -self.sample_dir(u), dist: f64::INFINITY, weight: 1.0 }),
        }
    }
}

/// How far outside the shadow's edges a point still counts as lit, m (rounding of the
/// projection of points on the target's faces).
const SHADOW_EDGE_M: f64 = 1e-9;

/// The beam aimed at the box [`lo`, `hi`]: the smallest rectangle around the projection of its
/// corners along the light onto the plane of `base` (about `centre`), its frame, and the shadow
/// (the projection's convex hull) in that frame ([`crate::geometry::min_rect`]).
fn aimed_beam(base: &Frame, centre: DVec3, lo: DVec3, hi: DVec3) -> (Frame, [[f64; 2]; 2], Option<Box<ConvexPolygon>>) {
    use crate::geometry::min_rect::min_area_rect;
    let corners: Vec<[f64; 2]> = (0..8)
        .map(|i| {
            let c = DVec3::new(
                if i & 1 == 0 { lo.x } else { hi.x },
                if i & 2 == 0 { lo.y } else { hi.y },
                if i & 4 == 0 { lo.z } else { hi.z },
            );
            [(c - centre).dot(base.s), (c - centre).dot(base.t)]
        })
        .collect();
    let rect = min_area_rect(&corners);
    let (sin, cos) = rect.angle_rad.sin_cos();
    let frame = Frame { s: cos * base.s + sin * base.t, t: -sin * base.s + cos * base.t, n: base.n };
    let in_frame: Vec<[f64; 2]> = corners.iter().map(|c| rect.coords(*c)).collect();
    (frame, rect.extent, ConvexPolygon::hull_of(&in_frame).map(Box::new))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::{Rng, Stream};
    use crate::spectrum::Spectrum;

    #[test]
    fn every_direction_of_the_disc_is_aimed_at_the_target() {
        // A sun 10 000 km upstream of a 2 m box (as in an Earth-sized scene): each photon's
        // straight ray crosses the plane through the box's centre inside the beam's rectangle
        // (here the box's shadow, ±1 m), whatever its direction in the 0.533° disc; before
        // aiming, they spread by ±0.27° × 10⁷ m ≈ ±47 km.
        let dir = DVec3::new(0.6, -0.8, 0.0);
        let emission = LightSpectrum::new(Spectrum::Constant(1.0), 400.0, 700.0).expect("spectrum");
        let target = (DVec3::new(-1.0, -1.0, -1.0), DVec3::new(1.0, 1.0, 1.0));
        let light = DirectionalLight::new(dir, DVec3::new(0.0, -1e7, 0.0), 1e7, Some(target), emission)
            .with_angular_diameter(0.533);
        let frame = light.frame;
        let mut rng = Rng::for_task(3, Stream::Test, 0);
        let cos_max = (1.0 - light.sin_max * light.sin_max).sqrt();
        for _ in 0..10_000 {
            let (o, w) = light.emit(rng.uniform2(), rng.uniform2(), 550.0);
            assert!(w.dot(dir) >= cos_max - 1e-15, "direction inside the disc");
            let x = (DVec3::ZERO - o).dot(dir) / w.dot(dir);
            let p = o + w * x;
            assert!(p.dot(dir).abs() < 1e-6, "on the aim plane");
            let (s, t) = ((p - light.scene_centre).dot(frame.s), (p - light.scene_centre).dot(frame.t));
            let inside = |v: f64, r: [f64; 2]| v >= r[0] - 1e-6 && v <= r[1] + 1e-6;
            assert!(inside(s, light.beam[0]) && inside(t, light.beam[1]), "({s}, {t}) outside {:?}", light.beam);
        }
    }
}
