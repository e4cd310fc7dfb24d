//! Tracing one photon and the storage rules of each map (Jensen 2001, §5.2; Jensen &
//! Christensen 1998, §4.2; Gutierrez et al. 2005, §3).
//!
//! Power is carried unchanged; Russian roulette decides survival: at a diffuse surface with its
//! reflectance ρ(λ), at a mirror with R(λ), at glass between reflection and refraction by the
//! Fresnel reflectance, and in a medium — where the free-flight distance is sampled along each
//! chord of the path — with the single-scattering albedo σ_s/σ_t (the first roulette). In a
//! medium with inelastic components, an interaction that is not an elastic scattering goes to
//! the second roulette ([`super::inelastic`]): a re-emitted photon continues at its new
//! wavelength with its power times the component's energy factor. Every stored photon of a pass
//! carries the power it had when it arrived there (the emitted power unless an inelastic event
//! changed it), tagged with its [`PhotonPath`].

use super::PassSettings;
use crate::geometry::spawn_origin;
use crate::light::Emission;
use crate::material::Lambertian;
use crate::media::tracking;
use crate::photon_map::{PhotonBeam, PhotonPath, PhotonRecord};
use crate::raypath::{Event, Propagator, RayState};
use crate::rng::Rng;
use crate::world::World;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// Which map a pass fills, and so which hits it stores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Every diffuse surface hit (surface map) and every interaction in a medium (volume map),
    /// tagged with the photon's path so estimates can leave out what shadow rays compute.
    Global,
    /// The first diffuse hit after one or more specular events and nothing else (L S+ D); the
    /// photon then stops, as it does when it scatters in a medium.
    Caustic,
}

/// Bounces after which a photon is dropped (its power is counted as truncated). Roulette ends
/// almost every path long before; this bounds pathological scenes (a mirror-lined box).
pub const MAX_PHOTON_BOUNCES: usize = 4096;

/// What happened to a pass's photons. Powers are in W; for the global pass
/// emitted = absorbed at surfaces + absorbed in media + escaped + truncated.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct PhotonStats {
    /// Photons emitted.
    pub emitted: u64,
    /// Photons stored on surfaces.
    pub stored: u64,
    /// Photons stored in media.
    pub stored_volume: u64,
    /// Power each photon started with, W.
    pub power_per_photon_w: f64,
    /// Power absorbed at surfaces, W.
    pub absorbed_surface_w: f64,
    /// Power absorbed in media, W.
    pub absorbed_medium_w: f64,
    /// Power that left the world, W.
    pub escaped_w: f64,
    /// Power dropped: paths over the bounce limit, or lost by the ray integrator, W.
    pub truncated_w: f64,
    /// Caustic-pass photons that did not make a caustic (first hit diffuse, scattered in a
    /// medium, or aimed nowhere).
    pub missed: u64,
    /// Batches not shot because the run's time budget (`--max-seconds`) ran out.
    #[serde(default)]
    pub stopped_batches: u64,
    /// Surface interactions.
    pub bounces: u64,
    /// Interactions in media.
    pub medium_interactions: u64,
    /// Photons that crossed the layered upper air by its ray invariant ([`crate::raypath::shell`]).
    #[serde(default)]
    pub shell_descents: u64,
    /// Integrator work along curved paths (zero where every path is straight).
    pub curved: crate::raypath::CurvedWorkTotals,
    /// Photons re-emitted by fluorescence, and Raman scatterings (see `inelastic`).
    pub reemitted: u64,
    /// Raman scatterings.
    pub raman_events: u64,
    /// Per inelastic component (empty when no medium is inelastic).
    pub inelastic: Vec<super::inelastic::InelasticTally>,
}

impl PhotonStats {
    /// Adds another batch's counts and powers (`emitted`, `power_per_photon_w` and `curved` are set
    /// once per pass and not added).
    pub fn add(&mut self, o: &PhotonStats) {
        self.stored += o.stored;
        self.stored_volume += o.stored_volume;
        self.absorbed_surface_w += o.absorbed_surface_w;
        self.absorbed_medium_w += o.absorbed_medium_w;
        self.escaped_w += o.escaped_w;
        self.truncated_w += o.truncated_w;
        self.missed += o.missed;
        self.stopped_batches += o.stopped_batches;
        self.bounces += o.bounces;
        self.medium_interactions += o.medium_interactions;
        self.shell_descents += o.shell_descents;
        self.reemitted += o.reemitted;
        self.raman_events += o.raman_events;
        if self.inelastic.len() < o.inelastic.len() {
            self.inelastic.resize(o.inelastic.len(), Default::default());
        }
        for (a, b) in self.inelastic.iter_mut().zip(&o.inelastic) {
            a.add(b);
        }
    }
}

/// Where a pass puts its photons.
#[derive(Default)]
pub struct PhotonSink {
    /// Photons stored on surfaces (global or caustic map).
    pub surface: Vec<PhotonRecord>,
    /// Photons stored in media (volume map).
    pub volume: Vec<PhotonRecord>,
    /// The photons' flights through media, chord by chord, where the pass keeps photon beams
    /// ([`PassSettings::photon_beams`]).
    pub beams: Vec<PhotonBeam>,
}

/// One photon in flight.
struct Flight<'a> {
    world: &'a World,
    pass: &'a PassSettings<'a>,
    kind: MapKind,
    lambda: f64,
    power_w: f64,
    path: PhotonPath,
}

impl Flight<'_> {
    fn record(&self, position: DVec3, dir: DVec3, normal: DVec3) -> PhotonRecord {
        PhotonRecord { position, dir, normal, wavelength_nm: self.lambda, power_w: self.power_w, path: self.path }
    }

    /// Keeps the part of chord `c` the photon flies along before its interaction at `t` (if
    /// any) as a photon beam.
    fn keep_beam(&self, c: &crate::raypath::Chord, t: Option<f64>, beams: &mut Vec<PhotonBeam>) {
        let length = t.map_or(c.length, |t| t.min(c.length));
        if let Some(medium) = c.medium.filter(|_| length > 0.0 && length.is_finite()) {
            beams.push(PhotonBeam {
                origin: c.origin,
                dir: c.dir,
                length,
                wavelength_nm: self.lambda,
                power_w: self.power_w,
                path: self.path,
                medium,
            });
        }
    }

    fn after(&mut self, path: PhotonPath) {
        self.path = match (self.path, path) {
            (PhotonPath::Diffuse, _) | (_, PhotonPath::Diffuse) => PhotonPath::Diffuse,
            _ => PhotonPath::Specular,
        };
    }
}

/// Traces one photon of power `power_w` from `em`, starting in `medium`.
#[allow(clippy::too_many_arguments)]
pub fn trace(
    world: &World,
    pass: &PassSettings,
    prop: &Propagator,
    em: &Emission,
    medium: Option<u32>,
    power_w: f64,
    kind: MapKind,
    rng: &mut Rng,
    out: &mut PhotonSink,
    st: &mut PhotonStats,
) {
    let mut f = Flight { world, pass, kind, lambda: em.wavelength_nm, power_w, path: PhotonPath::Direct };
    let origin = if em.normal == DVec3::ZERO { em.origin } else { spawn_origin(em.origin, em.normal, em.dir) };
    let mut state = RayState { position: origin, dir: em.dir, wavelength_nm: Some(f.lambda), medium };
    let store_volume = pass.volume_map;
    let keep_beams = store_volume && pass.photon_beams && kind == MapKind::Global;
    // The layered upper air, crossed in one move (the pass asks for it only when no sensor
    // counts photons: the shell's medium then keeps none).
    let shell = prop.layered_shell();
    for _ in 0..MAX_PHOTON_BOUNCES {
        if let Some(s) = shell.filter(|s| state.medium == Some(s.medium())) {
            if let Some(top) = s.enter(state.position, state.dir) {
                state.position = top;
            }
            if !cross_shell(&f, s, &mut state, rng, st) {
                return;
            }
        }
        let event = prop.next_event_with(&state, &mut |c| {
            let m = world.medium(c.medium)?;
            let t = tracking::sample_interaction(m, f.lambda, c.origin, c.dir, c.length, rng);
            if keep_beams && c.column_m.is_none() && m.keeps_photons(pass.photon_sensors) {
                f.keep_beam(c, t, &mut out.beams);
            }
            t
        });
        let next = match event {
            Event::Escape { .. } => {
                st.escaped_w += f.power_w;
                return;
            }
            Event::Lost { .. } => {
                st.truncated_w += f.power_w;
                return;
            }
            Event::Medium { position, dir, medium, .. } => {
                st.medium_interactions += 1;
                if f.kind == MapKind::Caustic {
                    st.missed += 1;
                    return;
                }
                let m = &world.media[medium as usize];
                if store_volume && m.keeps_photons(pass.photon_sensors) {
                    out.volume.push(f.record(position, dir, DVec3::ZERO));
                    st.stored_volume += 1;
                }
                let at = m.at(position);
                let wo = if rng.uniform() < at.albedo(f.lambda) {
                    at.choose_phase(f.lambda, rng).sample(f.lambda, dir, rng.uniform2()).0
                } else if m.inelastic.is_empty() {
                    st.absorbed_medium_w += f.power_w;
                    return;
                } else {
                    match reemit(&mut f, m, medium, dir, rng, st) {
                        Some(wo) => wo,
                        None => return,
                    }
                };
                f.after(PhotonPath::Diffuse);
                RayState { position, dir: wo, wavelength_nm: Some(f.lambda), medium: Some(medium) }
            }
            Event::Surface { hit, dir, medium, .. } => {
                st.bounces += 1;
                match surface(&mut f, prop, &hit, dir, medium, rng, out, st) {
                    Some(s) => s,
                    None => return,
                }
            }
        };
        state = next;
    }
    st.truncated_w += f.power_w;
}

/// Moves a photon that has just entered the layered upper air `shell` going down to where it
/// leaves the shell's bottom, if it gets there ([`crate::raypath::shell`]): it crosses with
/// probability e^(−τ), τ = σ_t(λ)·C, and is otherwise absorbed in the shell's medium (which does
/// not scatter). Returns false when the photon ends there; a photon elsewhere is left as it is.
fn cross_shell(
    f: &Flight,
    shell: &crate::raypath::shell::LayeredShell,
    state: &mut RayState,
    rng: &mut Rng,
    st: &mut PhotonStats,
) -> bool {
    let Some(d) = shell.descend(state.position, state.dir, f.lambda) else { return true };
    st.shell_descents += 1;
    let tau = f.world.media[shell.medium() as usize].sigma_t(f.lambda) * d.column_m;
    if rng.uniform() < (-tau).exp() {
        state.position = d.position;
        state.dir = d.dir;
        return true;
    }
    st.medium_interactions += 1;
    if f.kind == MapKind::Caustic {
        st.missed += 1;
    } else {
        st.absorbed_medium_w += f.power_w;
    }
    false
}

/// The second roulette: the direction a re-emitted photon leaves in (its wavelength and power
/// updated in `f`), or `None` when it stays absorbed.
fn reemit(
    f: &mut Flight,
    m: &crate::media::Medium,
    medium: u32,
    dir: DVec3,
    rng: &mut Rng,
    st: &mut PhotonStats,
) -> Option<DVec3> {
    let r = super::inelastic::after_absorption(
        f.world,
        f.pass.range_nm,
        m,
        medium,
        f.lambda,
        dir,
        f.power_w,
        rng,
        &mut st.inelastic,
    );
    let r = match r {
        Ok(r) => r,
        Err(absorbed_w) => {
            st.absorbed_medium_w += absorbed_w;
            return None;
        }
    };
    match r.process {
        crate::media::inelastic::Process::Raman => st.raman_events += 1,
        crate::media::inelastic::Process::Fluorescence => st.reemitted += 1,
    }
    f.lambda = r.wavelength_nm;
    f.power_w = r.power_w;
    Some(r.dir)
}

/// What a photon does at a surface: the state it leaves in, or `None` when it stops there.
#[allow(clippy::too_many_arguments)]
fn surface(
    f: &mut Flight,
    prop: &Propagator,
    hit: &crate::geometry::Hit,
    dir: DVec3,
    medium: Option<u32>,
    rng: &mut Rng,
    out: &mut PhotonSink,
    st: &mut PhotonStats,
) -> Option<RayState> {
    let world = f.world;
    let lambda = Some(f.lambda);
    let Some(material) = world.material_of(hit.prim) else {
        if world.prims[hit.prim as usize].light.is_some() {
            st.absorbed_surface_w += f.power_w;
            return None;
        }
        // A boundary between two media: straight on, or refracted where their n differ.
        let (d, across) = prop.cross(hit, dir, medium, f.lambda, rng.uniform());
        return Some(prop.leave(hit, d, lambda, across));
    };
    if material.is_diffuse() {
        let store = match f.kind {
            MapKind::Global => true,
            MapKind::Caustic => f.path == PhotonPath::Specular,
        };
        if store {
            out.surface.push(f.record(hit.point, dir, hit.normal));
            st.stored += 1;
        }
        if f.kind == MapKind::Caustic {
            if !store {
                st.missed += 1;
            }
            return None;
        }
        if rng.uniform() >= material.diffuse_reflectance(f.lambda) {
            st.absorbed_surface_w += f.power_w;
            return None;
        }
        f.after(PhotonPath::Diffuse);
        return Some(prop.leave(hit, Lambertian::sample(dir, hit.normal, rng.uniform2()), lambda, medium));
    }
    let n_out = prop.n_outside(hit.prim, f.lambda, hit.point);
    let s = material.sample_specular_in(dir, hit.normal, f.lambda, material.specular_u(rng), n_out)?;
    if s.weight > 1.0 {
        // A rough surface's throughput can exceed 1 for one facet (it is 1 on average at
        // most): the photon carries it, as a roulette cannot.
        f.power_w *= s.weight;
    } else if rng.uniform() >= s.weight {
        st.absorbed_surface_w += f.power_w;
        return None;
    }
    f.after(PhotonPath::Specular);
    let next_medium = if s.transmitted { world.medium_across(hit.prim, dir, hit.normal) } else { medium };
    Some(prop.leave(hit, s.dir, lambda, next_medium))
}
