//! The one propagation interface for photons and eye rays.
//!
//! From a ray state (position, direction, wavelength, current medium)
//! [`Propagator::next_event_with`] follows light to what it meets next — a surface, an
//! interaction in a medium, or escape — handing every straight chord of the path to a visitor on
//! the way. The visitor is how media act: a photon's free-flight sampler stops the path at an
//! interaction; an eye ray's marcher accumulates transmittance and in-scattered light. No tracer
//! assumes a path is `o + t·d`:
//! - in a medium whose refractive index is constant (or has none) the path is one straight
//!   chord per event and no ODE runs;
//! - in a medium with a refractive-index field ([`crate::media::refractive_index`]) the path follows
//!   Fermat's ray equation d/ds(n dr/ds) = ∇n ([`curved`]), integrated step by step ([`crate::ode`]:
//!   Dormand–Prince RK5(4)7M by default); each step's arc is cut into chords within the scene's
//!   arc tolerance (`arc`), and the same visitors and segment queries
//!   ([`crate::geometry::Bvh::intersect`]) see those chords. Outside the field's
//!   [`crate::field::GradientRegion`] the path is straight again, seamlessly (n is
//!   continuous there).
//!
//! Free-flight distances and marching are measured along the path (the sum of chord lengths,
//! within the arc tolerance of the arc length). Media extend to the *world sphere* (twice the
//! radius of the sphere bounding the scene and the camera); a path leaving it escapes.

mod arc;
mod cost;
pub mod curved;
pub mod far;
pub mod kink;
pub mod projection;
pub mod shell;
pub mod trace;

pub use cost::{CurvedWork, CurvedWorkTotals, RayCounts};

use crate::field::GradientRegion;
use crate::geometry::{Hit, Ray};
use crate::media::refractive_index::IndexField;
use crate::media::tracking;
use crate::ode::CurvedSettings;
use crate::rng::Rng;
use crate::spectrum::MAX_BANDS;
use crate::world::World;
use glam::DVec3;

/// A ray state: where light is, where it goes, at which wavelength (`None` while nothing on the
/// path depends on wavelength: an eye path carrying all bands), and in which medium.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RayState {
    /// Position, m.
    pub position: DVec3,
    /// Unit direction of travel.
    pub dir: DVec3,
    /// Wavelength, nm; `None` while nothing on the path depends on wavelength.
    pub wavelength_nm: Option<f64>,
    /// Index of the medium light is in (into the world's media); `None`: vacuum.
    pub medium: Option<u32>,
}

/// A straight piece of a path inside one medium (or vacuum).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Chord {
    /// Start point, m.
    pub origin: DVec3,
    /// Unit direction.
    pub dir: DVec3,
    /// Length, m.
    pub length: f64,
    /// The medium it runs through (`None`: vacuum).
    pub medium: Option<u32>,
    /// `Some(C)`: the chord stands for a curved path across the layered upper air, from its
    /// origin to its end, whose density column ∫d ds is C, m ([`shell::LayeredShell::ascend`]):
    /// its optical depth is σ_t(λ)·C, not the straight segment's. Only a propagator built with
    /// [`Propagator::with_upward_shell`]`(.., true)` hands such chords to its visitors.
    pub column_m: Option<f64>,
    /// The normal of the surface the chord ends on (either orientation), `None` where it ends
    /// inside its medium (a step of a curved path, the edge of a gradient region, the world's
    /// sphere): where the medium it runs through may end.
    pub end_normal: Option<DVec3>,
}

/// What light meets next.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Event {
    /// A surface; `dir` is the unit direction of travel on arrival, `path_length` the distance
    /// travelled along the path (arc length once paths curve), `medium` the medium it came
    /// through.
    Surface {
        /// The surface hit.
        hit: Hit,
        /// Unit direction of travel on arrival.
        dir: DVec3,
        /// Distance travelled along the path (arc length once paths curve), m.
        path_length: f64,
        /// The medium it came through (`None`: vacuum).
        medium: Option<u32>,
    },
    /// The visitor stopped the path inside `medium` (a photon's interaction).
    Medium {
        /// Where the path stopped, m.
        position: DVec3,
        /// Unit direction of travel there.
        dir: DVec3,
        /// Distance travelled along the path, m.
        path_length: f64,
        /// The medium it stopped in.
        medium: u32,
    },
    /// Nothing more is hit; `dir` is the final direction of travel.
    Escape {
        /// Final unit direction of travel.
        dir: DVec3,
    },
    /// The path could not be followed (the integrator failed: a field gave a non-finite value);
    /// counted in [`CurvedWorkTotals::lost`] and ended.
    Lost {
        /// Where the integrator failed, m.
        position: DVec3,
    },
}

/// The kink spheres of a radial field (its kinks and the peaks of its thin layers), if it has
/// any, each probed at the reference wavelength.
fn kink_spheres(f: &IndexField) -> Option<kink::KinkSpheres> {
    let (radii, layers) = (f.kink_radii_m(), f.thin_layer_radii_m());
    if radii.is_empty() && layers.is_empty() {
        return None;
    }
    let sample = |p: DVec3| f.n_grad(curved::REFERENCE_WAVELENGTH_NM, p);
    Some(kink::KinkSpheres::new(&sample, f.radial_centre()?, &radii).with_layers(&sample, &layers))
}

/// What a medium's curved paths are followed with besides its field.
#[derive(Clone, Debug, Default)]
struct Aids {
    /// With a radial field: the spheres where its gradient jumps, where integrator steps end
    /// ([`kink`]).
    kinks: Option<kink::KinkSpheres>,
    /// In an atmosphere of height alone: its index tabulated
    /// ([`crate::atmosphere::RadialTable`]), to the integrator's rtol.
    table: Option<crate::atmosphere::RadialTable>,
}

/// Moves light through a world.
pub struct Propagator<'a> {
    world: &'a World,
    /// How curved paths are followed; `None` when every path is straight.
    curved: Option<&'a CurvedSettings>,
    world_centre: DVec3,
    world_radius: f64,
    /// Per medium: where its index field bends light, if it does and the plan follows it.
    regions: Vec<Option<GradientRegion>>,
    /// Per medium: whether it neither absorbs nor scatters (nothing happens in it but bending).
    clear: Vec<bool>,
    /// Per medium with a radial field: the cone of finite geometry, past which a path trapped
    /// in a duct escapes ([`far`]).
    far: Vec<Option<far::FarCone>>,
    /// Per medium: what makes its curved paths cheaper (kinks as step ends, a tabulated index).
    aids: Vec<Aids>,
    /// The layered upper air photons cross in one move, when the pass asked for it
    /// ([`Propagator::with_layered_shell`]) and the scene has one ([`shell`]).
    shell: Option<Box<shell::LayeredShell>>,
    /// Whether the visitors take column chords ([`Chord::column_m`]), so that paths may climb
    /// out of absorbing air in one move too ([`Propagator::with_upward_shell`]).
    columns: bool,
    /// Integrator work along curved paths.
    pub work: CurvedWork,
}

impl<'a> Propagator<'a> {
    /// A propagator through `world`; paths curve where a medium's index field bends them and
    /// `curved` says how to follow them (`None`: the effect plan keeps every path straight).
    pub fn new(world: &'a World, curved: Option<&'a CurvedSettings>) -> Propagator<'a> {
        let regions = world
            .media
            .iter()
            .map(|m| m.index.as_ref().filter(|f| curved.is_some() && !f.is_uniform()).map(|f| f.gradient_region()))
            .collect();
        let clear = world.media.iter().map(|m| m.is_clear()).collect();
        // Only fields whose paths are followed as curves need the cone and the kinks.
        let bending = |m: &'a crate::media::Medium| m.index.as_ref().filter(|f| curved.is_some() && !f.is_uniform());
        let far = world.media.iter().map(|m| bending(m).and_then(|f| far::FarCone::new(world, f))).collect();
        let aids = world
            .media
            .iter()
            .map(|m| Aids {
                kinks: bending(m).and_then(kink_spheres),
                table: match (bending(m), curved) {
                    (Some(IndexField::Atmosphere(a)), Some(c)) => crate::atmosphere::RadialTable::new(a, c.rtol),
                    _ => None,
                },
            })
            .collect();
        Propagator {
            world,
            curved,
            world_centre: world.reach.centre,
            world_radius: world.reach.radius,
            regions,
            clear,
            far,
            aids,
            shell: None,
            columns: false,
            work: CurvedWork::default(),
        }
    }

    /// This propagator with the layered upper air of the first medium that has one
    /// ([`shell::LayeredShell::of`]), tabulated for wavelengths `range_nm`: photon passes cross it
    /// by the ray invariant ([`Propagator::layered_shell`]).
    pub fn with_layered_shell(mut self, range_nm: (f64, f64)) -> Propagator<'a> {
        let Some(c) = self.curved else { return self };
        self.shell = self.aids.iter().enumerate().find_map(|(i, a)| {
            let table = a.table.as_ref().filter(|_| self.regions[i].is_some())?;
            shell::LayeredShell::of(self.world, i as u32, table, range_nm, c.rtol).map(Box::new)
        });
        self
    }

    /// This propagator with the layered upper air of [`Propagator::with_layered_shell`] where
    /// paths may leave it upward in one move — its air clear, or absorbing where the caller's
    /// visitors take `columns` ([`Chord::column_m`]) — and without it elsewhere, where the
    /// tables would serve no path (an eye pass: its paths do not come down from above the air).
    pub fn with_upward_shell(mut self, range_nm: (f64, f64), columns: bool) -> Propagator<'a> {
        self.columns = columns;
        let wanted = (0..self.world.media.len() as u32)
            .any(|i| (columns || self.clear[i as usize]) && shell::LayeredShell::candidate(self.world, i).is_some());
        if wanted { self.with_layered_shell(range_nm) } else { self }
    }

    /// The layered upper air of medium `medium` if paths there leave it upward in one move:
    /// clear air, or absorbing air whose optical depth the visitors take as a column.
    fn upward_shell(&self, medium: u32) -> Option<&shell::LayeredShell> {
        self.shell.as_deref().filter(|s| s.medium() == medium && (self.columns || self.clear[medium as usize]))
    }

    /// The layered upper air, if [`Propagator::with_layered_shell`] found one.
    pub fn layered_shell(&self) -> Option<&shell::LayeredShell> {
        self.shell.as_deref()
    }

    /// Whether medium `m` neither absorbs nor scatters light.
    pub fn is_clear(&self, m: u32) -> bool {
        self.clear[m as usize]
    }

    /// The world light moves through.
    pub fn world(&self) -> &'a World {
        self.world
    }

    /// How curved paths are followed (`None`: every path is straight).
    pub fn curved_settings(&self) -> Option<&'a CurvedSettings> {
        self.curved
    }

    /// The index field of `medium` and where it bends light, when paths in it curve.
    fn curved_field(&self, medium: Option<u32>) -> Option<(&IndexField, &GradientRegion)> {
        let m = medium? as usize;
        let region = self.regions[m].as_ref()?;
        Some((self.world.media[m].index.as_ref()?, region))
    }

    /// Whether a path in `medium` bends differently at each wavelength, so that an eye path
    /// carrying several must split into one path per wavelength before entering it.
    pub fn splits_wavelengths(&self, medium: Option<u32>) -> bool {
        self.curved_field(medium).is_some_and(|(f, _)| f.is_dispersive())
    }

    /// The refractive index of `medium` at `p` and `wavelength_nm`: its field's n, or 1 for
    /// vacuum and media without a field.
    pub fn n_at(&self, medium: Option<u32>, wavelength_nm: f64, p: DVec3) -> f64 {
        self.world.medium(medium).and_then(|m| m.index.as_ref()).map_or(1.0, |f| f.n(wavelength_nm, p))
    }

    /// The factor (n_from/n_to)² by which radiance seen across a boundary from medium `from`
    /// into medium `to` at `p` scales: the basic radiance L/n² is what a refracting boundary
    /// conserves (less the Fresnel loss), not L (Veach 1997, §5.2; Nicodemus 1963). 1 where the
    /// two media are the same (a reflection) or agree in n.
    pub fn radiance_scale(&self, from: Option<u32>, to: Option<u32>, wavelength_nm: f64, p: DVec3) -> f64 {
        if from == to {
            return 1.0;
        }
        let ratio = self.n_at(from, wavelength_nm, p) / self.n_at(to, wavelength_nm, p);
        ratio * ratio
    }

    /// The next event from `state`, not stopping in media.
    pub fn next_event(&self, state: &RayState) -> Event {
        self.next_event_with(state, &mut |_| None)
    }

    /// The next event from `state`; each chord of the path inside a medium is handed to `visit`,
    /// which returns the distance along the chord at which the path stops, if it does.
    pub fn next_event_with(&self, state: &RayState, visit: &mut dyn FnMut(&Chord) -> Option<f64>) -> Event {
        if let Some((field, region)) = self.curved_field(state.medium) {
            return curved::next_event(self, state, field, region, visit);
        }
        let ray = Ray::new(state.position, state.dir);
        let hit = self.world.bvh.intersect(&self.world.shapes, &ray, f64::INFINITY);
        if let Some(m) = state.medium {
            let length = hit.map_or_else(|| self.world_exit(state.position, state.dir), |h| h.t);
            let chord = Chord {
                origin: state.position,
                dir: state.dir,
                length,
                medium: state.medium,
                column_m: None,
                end_normal: hit.map(|h| h.normal),
            };
            if let Some(t) = visit(&chord).filter(|t| *t < length) {
                return Event::Medium { position: ray.at(t), dir: state.dir, path_length: t, medium: m };
            }
        }
        match hit {
            Some(hit) => Event::Surface { hit, dir: state.dir, path_length: hit.t, medium: state.medium },
            None => Event::Escape { dir: state.dir },
        }
    }

    /// Whether `p` lies outside the world sphere.
    fn outside_world(&self, p: DVec3) -> bool {
        (p - self.world_centre).length_squared() > self.world_radius * self.world_radius
    }

    /// Distance from `p` along `dir` to the world sphere (0 if `p` is outside it).
    fn world_exit(&self, p: DVec3, dir: DVec3) -> f64 {
        let oc = p - self.world_centre;
        let b = oc.dot(dir);
        let c = oc.length_squared() - self.world_radius * self.world_radius;
        if c > 0.0 {
            return 0.0;
        }
        -b + (b * b - c).max(0.0).sqrt()
    }

    /// The refractive index on the front side of primitive `prim` (its exterior medium) at `p`:
    /// what a dielectric material's index is relative to.
    pub fn n_outside(&self, prim: u32, wavelength_nm: f64, p: DVec3) -> f64 {
        self.n_at(self.world.prims[prim as usize].exterior, wavelength_nm, p)
    }

    /// Whether crossing the index-matched boundary `prim` at `p` refracts (the media on its two
    /// sides differ in n there at `wavelength_nm`).
    pub fn boundary_refracts(&self, prim: u32, wavelength_nm: f64, p: DVec3) -> bool {
        let pr = &self.world.prims[prim as usize];
        let (front, back) = (self.n_at(pr.exterior, wavelength_nm, p), self.n_at(pr.interior, wavelength_nm, p));
        (front - back).abs() > 1e-12 * front
    }

    /// Whether that refraction depends on wavelength (a path carrying several must split).
    pub fn boundary_is_dispersive(&self, prim: u32) -> bool {
        let pr = &self.world.prims[prim as usize];
        let dispersive =
            |m: Option<u32>| self.world.medium(m).and_then(|m| m.index.as_ref()).is_some_and(|f| f.is_dispersive());
        dispersive(pr.exterior) || dispersive(pr.interior)
    }

    /// A path crossing the boundary `hit` without a material (between two media): straight on
    /// when n is the same on both sides; else reflected with the Fresnel probability (staying
    /// in `medium`) or refracted by Snell's law with the local n of both sides. Returns the new
    /// direction and medium (weight 1).
    pub fn cross(
        &self,
        hit: &Hit,
        dir: DVec3,
        medium: Option<u32>,
        wavelength_nm: f64,
        u: f64,
    ) -> (DVec3, Option<u32>) {
        let across = self.world.medium_across(hit.prim, dir, hit.normal);
        if !self.boundary_refracts(hit.prim, wavelength_nm, hit.point) {
            return (dir, across);
        }
        let pr = &self.world.prims[hit.prim as usize];
        let front = self.n_at(pr.exterior, wavelength_nm, hit.point);
        let back = self.n_at(pr.interior, wavelength_nm, hit.point);
        let s = crate::material::fresnel_sample(dir, hit.normal, back / front, u);
        (s.dir, if s.transmitted { across } else { medium })
    }

    /// The state leaving surface `hit` in direction `dir`, in `medium`, offset so it does not
    /// re-hit the surface it leaves.
    pub fn leave(&self, hit: &Hit, dir: DVec3, wavelength_nm: Option<f64>, medium: Option<u32>) -> RayState {
        RayState { position: hit.spawn_origin(&self.world.shapes, dir), dir, wavelength_nm, medium }
    }

    /// The first surface other than an index-matched boundary along the straight ray from `start`
    /// (on surface `from`, if any) toward `dir` — `None` inside when the ray leaves the scene —
    /// with the transmittance per lane of the media crossed on the way; `None` if the ray
    /// crosses too many boundaries to follow. Only valid while paths are straight.
    pub fn first_opaque_hit(
        &self,
        start: DVec3,
        from: Option<&Hit>,
        dir: DVec3,
        medium: Option<u32>,
        wavelengths_nm: &[f64],
        rng: &mut Rng,
    ) -> Option<(Option<Hit>, [f64; MAX_BANDS])> {
        let mut tr = [1.0; MAX_BANDS];
        let mut origin = from.map_or(start, |h| h.spawn_origin(&self.world.shapes, dir));
        let mut medium = medium;
        let mut travelled = 0.0;
        for _ in 0..64 {
            let hit = self.world.bvh.intersect(&self.world.shapes, &Ray::new(origin, dir), f64::INFINITY);
            let seg = hit.map_or_else(|| self.world_exit(origin, dir), |h| h.t);
            if let Some(m) = self.world.medium(medium) {
                tracking::transmittances(m, wavelengths_nm, origin, dir, seg, rng, &mut tr);
            }
            let Some(mut h) = hit else { return Some((None, tr)) };
            travelled += h.t;
            let p = &self.world.prims[h.prim as usize];
            if p.material.is_some() || p.light.is_some() {
                h.t = travelled;
                return Some((Some(h), tr));
            }
            medium = self.world.medium_across(h.prim, dir, h.normal);
            origin = h.spawn_origin(&self.world.shapes, dir);
        }
        None
    }

    /// Transmittance per lane (`wavelengths_nm`) along the straight segment from a point toward
    /// `wi` for `dist` (less a relative margin, so the target itself does not count), through
    /// media and index-matched boundaries; `None` if anything else blocks it. `from` is the
    /// surface the segment starts on, if any. Only valid while paths are straight: the effect
    /// plan turns shadow rays off when they curve.
    #[allow(clippy::too_many_arguments)]
    pub fn shadow(
        &self,
        start: DVec3,
        from: Option<&Hit>,
        wi: DVec3,
        dist: f64,
        medium: Option<u32>,
        wavelengths_nm: &[f64],
        rng: &mut Rng,
    ) -> Option<[f64; MAX_BANDS]> {
        let mut tr = [1.0; MAX_BANDS];
        let mut origin = from.map_or(start, |h| h.spawn_origin(&self.world.shapes, wi));
        let mut left = if dist.is_finite() { (dist - (origin - start).length()) * (1.0 - 1e-7) } else { f64::INFINITY };
        let mut medium = medium;
        for _ in 0..64 {
            if left <= 0.0 {
                return Some(tr);
            }
            let hit = self.world.bvh.intersect(&self.world.shapes, &Ray::new(origin, wi), left);
            let seg = hit.map_or_else(|| left.min(self.world_exit(origin, wi)), |h| h.t);
            if let Some(m) = self.world.medium(medium) {
                tracking::transmittances(m, wavelengths_nm, origin, wi, seg, rng, &mut tr);
            }
            let Some(h) = hit else { return Some(tr) };
            let p = &self.world.prims[h.prim as usize];
            if p.material.is_some() || p.light.is_some() {
                return None;
            }
            medium = self.world.medium_across(h.prim, wi, h.normal);
            origin = h.spawn_origin(&self.world.shapes, wi);
            left -= h.t;
        }
        None
    }
}
