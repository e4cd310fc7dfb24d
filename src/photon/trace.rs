//! Tracing one photon and the storage rules of each map (Jensen 2001, §5.2).
//!
//! Power is carried unchanged; Russian roulette decides survival with the surface's
//! reflectance at the photon's wavelength (diffuse: ρ(λ); mirror: R(λ); glass: reflection or
//! refraction chosen by the Fresnel reflectance), so every stored photon of a pass carries the
//! power it was emitted with.

use crate::geometry::spawn_origin;
use crate::light::Emission;
use crate::material::Lambertian;
use crate::photon_map::PhotonRecord;
use crate::raypath::{Event, Propagator, RayState};
use crate::rng::Rng;
use crate::scene::Scene;
use serde::Serialize;

/// Which map a pass fills, and so which hits it stores.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum MapKind {
    /// Every diffuse hit, or (with `store_direct` false) only those after a diffuse bounce —
    /// the indirect part, when direct light and caustics come from elsewhere.
    Global { store_direct: bool },
    /// The first diffuse hit after one or more specular bounces (L S+ D); the photon then stops.
    Caustic,
}

/// Bounces after which a photon is dropped (its power is counted as truncated). Roulette ends
/// almost every path long before; this bounds pathological scenes (a mirror-lined box).
pub const MAX_PHOTON_BOUNCES: usize = 512;

/// What happened to a pass's photons. Powers are in W; emitted = absorbed + escaped + truncated
/// + missed (targeted caustic photons that found no specular surface).
#[derive(Clone, Debug, Default, PartialEq, Serialize)]
pub struct PhotonStats {
    pub emitted: u64,
    pub stored: u64,
    pub power_per_photon_w: f64,
    pub absorbed_w: f64,
    pub escaped_w: f64,
    pub truncated_w: f64,
    /// Photons that did not contribute to a caustic map (first hit diffuse, or aimed nowhere).
    pub missed: u64,
    pub bounces: u64,
}

impl PhotonStats {
    pub fn add(&mut self, o: &PhotonStats) {
        self.stored += o.stored;
        self.absorbed_w += o.absorbed_w;
        self.escaped_w += o.escaped_w;
        self.truncated_w += o.truncated_w;
        self.missed += o.missed;
        self.bounces += o.bounces;
    }
}

/// Traces one photon of power `power_w` from `em`, appending stored photons to `out`.
#[allow(clippy::too_many_arguments)]
pub fn trace(
    scene: &Scene,
    prop: &Propagator,
    em: &Emission,
    power_w: f64,
    kind: MapKind,
    rng: &mut Rng,
    out: &mut Vec<PhotonRecord>,
    st: &mut PhotonStats,
) {
    let lambda = em.wavelength_nm;
    let origin = if em.normal == glam::DVec3::ZERO { em.origin } else { spawn_origin(em.origin, em.normal, em.dir) };
    let mut state = RayState { position: origin, dir: em.dir, wavelength_nm: Some(lambda) };
    let (mut diffuse_bounces, mut specular_bounces) = (0usize, 0usize);
    for _ in 0..MAX_PHOTON_BOUNCES {
        let (hit, dir) = match prop.next_event(&state) {
            Event::Escape { .. } => {
                st.escaped_w += power_w;
                return;
            }
            Event::Surface { hit, dir, .. } => (hit, dir),
        };
        st.bounces += 1;
        let Some(material) = scene.material_of(hit.prim) else {
            st.absorbed_w += power_w;
            return;
        };
        let new_dir = if material.is_diffuse() {
            let store = match kind {
                MapKind::Global { store_direct } => store_direct || diffuse_bounces > 0,
                MapKind::Caustic => specular_bounces > 0,
            };
            if store {
                out.push(PhotonRecord { position: hit.point, dir, normal: hit.normal, wavelength_nm: lambda, power_w });
                st.stored += 1;
            }
            if kind == MapKind::Caustic {
                if !store {
                    st.missed += 1;
                }
                return;
            }
            if rng.uniform() >= material.diffuse_reflectance(lambda) {
                st.absorbed_w += power_w;
                return;
            }
            diffuse_bounces += 1;
            Lambertian::sample(dir, hit.normal, rng.uniform2())
        } else {
            let Some(s) = material.sample_specular(dir, hit.normal, lambda, rng.uniform()) else {
                return;
            };
            if rng.uniform() >= s.weight {
                st.absorbed_w += power_w;
                return;
            }
            specular_bounces += 1;
            s.dir
        };
        state = prop.leave(&hit, new_dir, Some(lambda));
    }
    st.truncated_w += power_w;
}
