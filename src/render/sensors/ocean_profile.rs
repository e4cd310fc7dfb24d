//! Evaluating an [`OceanProfile`] sensor against the volume photon map: the collision estimator
//! of the irradiances and the next-event estimator of L_u described in
//! [`crate::sensor::ocean_profile`], and E_d(0+) by shadow rays.

use super::super::direct::{ShadowOrigin, sample_lights};
use super::super::photon_pass::Maps;
use crate::geometry::spawn_origin;
use crate::light::{Incident, Light};
use crate::raypath::Propagator;
use crate::rng::{Rng, Stream};
use crate::scene::Scene;
use crate::sensor::ocean_profile::LU_CONE_DEG;
use crate::sensor::{OceanProfile, ProfileReading, ProfileRow};
use crate::spectrum::BandValues;
use glam::DVec3;

/// Measures the profile; sensor `index` and the pass's `seed` seed the shadow rays.
pub fn evaluate(s: &OceanProfile, (scene, seed): (&Scene, u64), maps: &Maps, name: &str, index: u64) -> ProfileReading {
    let bands = scene.bands;
    let mut depths = s.depths_m.clone();
    depths.push(0.0);
    let mut sums = vec![[0.0f64; 5]; depths.len() * bands.count];
    if let Some(map) = &maps.volume {
        for i in 0..map.len() as u32 {
            let p = map.record(i);
            let mut rng = Rng::for_task(seed, Stream::Sensor, (index << 40) | u64::from(i));
            tally(s, scene, &p, &depths, &mut sums, &mut rng);
        }
    }
    let area = s.u.cross(s.v).length();
    let lu_scale = 1.0 / (area * bands.width_nm());
    let row = |k: usize, b: usize| {
        let sum = sums[k * bands.count + b];
        let scale = 1.0 / (area * s.slab_thickness_m(depths[k]) * bands.width_nm());
        ProfileRow {
            depth_m: depths[k],
            wavelength_nm: bands.centre_nm(b),
            ed: sum[0] * scale,
            eu: sum[1] * scale,
            eod: sum[2] * scale,
            eou: sum[3] * scale,
            lu: sum[4] * lu_scale,
        }
    };
    let rows =
        (0..s.depths_m.len()).flat_map(|k| (0..bands.count).map(move |b| (k, b))).map(|(k, b)| row(k, b)).collect();
    let ed0 = ed_above(s, (scene, seed), index);
    let t = 1.0 - ((s.ior - 1.0) / (s.ior + 1.0)).powi(2);
    let surface = (0..bands.count)
        .map(|b| {
            let lu0 = row(depths.len() - 1, b).lu;
            let lw = lu0 * t / (s.ior * s.ior);
            [bands.centre_nm(b), ed0[b], lu0, lw, if ed0[b] > 0.0 { lw / ed0[b] } else { 0.0 }]
        })
        .collect();
    ProfileReading { name: name.to_string(), rows, surface, std_error: None }
}

/// Adds one stored photon to every slab and band it belongs to, and its upward scattering
/// to L_u at every depth above it.
fn tally(
    s: &OceanProfile,
    scene: &Scene,
    p: &crate::photon_map::PhotonRecord,
    depths: &[f64],
    sums: &mut [[f64; 5]],
    rng: &mut Rng,
) {
    let bands = scene.bands;
    let Some(b) = bands.index_of(p.wavelength_nm) else { return };
    let rel = p.position - s.origin;
    let depth = -rel.dot(s.up);
    let (su, sv) = (rel.dot(s.u) / s.u.length_squared(), rel.dot(s.v) / s.v.length_squared());
    if su.abs() > 0.5 || sv.abs() > 0.5 {
        return;
    }
    let Some(m) = scene.world.medium(scene.world.medium_at(p.position)) else { return };
    let at = m.at(p.position);
    let sigma_t = at.sigma_t(p.wavelength_nm) * at.density();
    if sigma_t <= 0.0 {
        return;
    }
    let mu = p.dir.dot(s.up);
    let w = p.power_w / sigma_t;
    let l = p.wavelength_nm;
    let up_elastic = at.albedo(l) * cone_mean_phase(at.choose_phase(l, rng), l, p.dir, s.up, rng) * p.power_w;
    let mut up_inelastic = [0.0; crate::spectrum::MAX_BANDS];
    if let Some(t) = &m.inelastic.transfer {
        t.add_photon(&m.inelastic, &mut up_inelastic, l, mu, p.power_w);
    }
    let density = at.density();
    for (k, z) in depths.iter().enumerate() {
        if depth > *z {
            let h = depth - z;
            sums[k * bands.count + b][4] += up_elastic * (-sigma_t * h).exp();
            for (j, v) in up_inelastic.iter().enumerate().take(bands.count).filter(|(_, v)| **v > 0.0) {
                sums[k * bands.count + j][4] += v * (-at.sigma_t(bands.centre_nm(j)) * density * h).exp();
            }
        }
        // The slab clipped to the water (photons above the surface are not in it).
        if (depth - z).abs() > 0.5 * s.slab_m || depth < 0.0 {
            continue;
        }
        let slot = &mut sums[k * bands.count + b];
        if mu < 0.0 {
            slot[0] += w * -mu;
            slot[2] += w;
        } else {
            slot[1] += w * mu;
            slot[3] += w;
        }
    }
}

/// E_d(0+) per band from the lights, by shadow rays from just above the surface.
fn ed_above(s: &OceanProfile, (scene, seed): (&Scene, u64), index: u64) -> Vec<f64> {
    let bands = scene.bands;
    let prop = Propagator::new(&scene.world, scene.curved());
    let p = spawn_origin(s.origin, s.up, s.up);
    let medium = scene.world.medium_at(p);
    let mut rng = Rng::for_task(seed, Stream::Sensor, (index << 40) | 0xED);
    (0..bands.count)
        .map(|b| {
            let (lo, hi) = bands.edges_nm(b);
            let mut sum = 0.0;
            for _ in 0..s.samples {
                let l = lo + (hi - lo) * rng.uniform();
                let at = ShadowOrigin { p, from: None, medium, wavelengths_nm: &[l], light_u: None };
                let mut add = |light: &Light, inc: &Incident, cos: f64, tr: &BandValues| {
                    sum += light.spectrum().spectrum.eval(l) * inc.weight * light.disc_factor(inc, l) * cos * tr[0];
                };
                let cos = |_: &Light, inc: &Incident| inc.wi.dot(s.up);
                sample_lights(&prop, &scene.world.lights, &at, &mut rng, &mut 0, &cos, &mut add);
            }
            sum / s.samples as f64
        })
        .collect()
}

/// Phase-function samples for photons travelling within 4 cone half-angles of up.
const CONE_SAMPLES: usize = 64;

/// The mean of p(ω_p · ω) over the directions ω within [`LU_CONE_DEG`] of `up`: for a photon
/// travelling near `up`, where a forward-peaked phase function (Petzold's reaches 10⁴ times its
/// mean) would make p(μ) a heavy-tailed weight, the fraction of [`CONE_SAMPLES`] directions drawn
/// from p about ω_p that fall in the cone, over the cone's solid angle (unbiased, bounded by
/// 1/Ω_c); farther away, p at the cone's axis (p is smooth there).
fn cone_mean_phase(phase: &crate::media::phase::PhaseFunction, l: f64, dir: DVec3, up: DVec3, rng: &mut Rng) -> f64 {
    let cos_c = LU_CONE_DEG.to_radians().cos();
    let mu = dir.dot(up);
    if mu < (4.0 * LU_CONE_DEG).to_radians().cos() {
        return phase.eval(l, mu);
    }
    let hits = (0..CONE_SAMPLES).filter(|_| phase.sample(l, dir, rng.uniform2()).0.dot(up) > cos_c).count();
    hits as f64 / CONE_SAMPLES as f64 / (2.0 * std::f64::consts::PI * (1.0 - cos_c))
}
