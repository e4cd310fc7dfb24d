//! Eye paths inside a medium: the adaptive march along a chord (JC98 §4.4), single scattering
//! by shadow rays at its samples, the volume photon map read at each sample or along the whole
//! chord (the beam estimate's discs, photon beams' tubes), the transmittance it carries and the
//! Russian roulette that ends it.

use super::super::direct::{ShadowOrigin, sample_lights};
use super::super::lanes::Lanes;
use super::{Along, At, EyeTracer, Mode, Scratch, add_by_band, add_by_lane, power_heuristic};
use crate::light::{Incident, Light};
use crate::media::{Coefficients, Medium, tracking};
use crate::photon_map::{BandValues, ChordEstimate, Estimator, SegmentEnds, Walls};
use crate::raypath::Chord;
use crate::rng::Rng;
use crate::spectrum::MAX_BANDS;
use glam::DVec3;

/// A gather ray's chord is marched in this many jittered steps (at least `march_step` each):
/// its radiance is averaged over many gather rays, so a coarse quadrature suffices.
const GATHER_STEPS: f64 = 4.0;

/// Relative change of the in-scattered light between march samples above which the step is
/// halved (JC98 §4.4), below which it is doubled back, and the most halvings.
const ADAPT_REFINE: f64 = 0.5;
const ADAPT_RELAX: f64 = 0.1;
const MAX_REFINE: u32 = 4;

/// The most steps the mean-free-path rule may add to a camera ray's march over one chord: a
/// step is shortened to a quarter of the mean free path only down to a this-many-th of the
/// chord (never below what `march_step` itself gives). A step's sample point is jittered
/// uniformly within it, so T(s)·h estimates ∫ T over the step without bias at any length; short
/// steps only lower the noise. Without this bound a dye whose σ_a reaches 2 × 10⁸ m⁻¹ at one
/// wavelength held a 4 × 4 render's rays to 5 nm steps: 65 million steps (the render fuzzer,
/// seed 2, case 22244).
const MAX_MARCH_STEPS: f64 = 1e4;

/// Transmittance below which a marched path is continued by Russian roulette.
const ROULETTE_TRANSMITTANCE: f64 = 1e-3;

impl EyeTracer<'_> {
    /// Single scattering toward travel direction `wo` at `x` in medium `id`, per unit length:
    /// σ_s(λ, x) ∫ f(λ; ω_l·ω_o) L_light(λ) T(λ) dω, estimated by one shadow ray per light and,
    /// for area lights, one phase-sampled ray, combined by the power heuristic (light sampling
    /// alone has infinite variance near an emitting surface). `unit_sigma_s`: σ_s of each lane
    /// at density 1 where it does not vary along the chord (every medium but an atmosphere of
    /// constituents), computed once per chord by the caller.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn single_scattering(
        &self,
        x: DVec3,
        wo: DVec3,
        (id, m): (u32, &Medium),
        unit_sigma_s: Option<&BandValues>,
        lanes: &Lanes,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let mut out = [0.0; MAX_BANDS];
        let here = m.at(x);
        let d = here.density();
        if d <= 0.0 {
            return out;
        }
        let sigma_s: BandValues = match unit_sigma_s {
            Some(u) => *u,
            None => std::array::from_fn(|i| if i < lanes.len { here.sigma_s(lanes.nm[i]) } else { 0.0 }),
        };
        let nm = &lanes.nm[..lanes.len];
        let phase = |l: f64, light_travel: DVec3| here.phase_eval(l, light_travel.dot(wo));
        // The phase function differs per lane, so `add` applies it (and its MIS weight) itself.
        let at = ShadowOrigin { p: x, from: None, medium: Some(id), wavelengths_nm: nm, light_u: None };
        let mut add = |light: &Light, inc: &Incident, _: f64, tr: &BandValues| {
            let s = &light.spectrum().spectrum;
            for i in 0..lanes.len {
                let l = lanes.nm[i];
                let f = phase(l, -inc.wi);
                let mis = if light.is_delta() { 1.0 } else { power_heuristic(1.0 / inc.weight, f) };
                out[i] += mis * d * sigma_s[i] * f * s.eval(l) * inc.weight * light.disc_factor(inc, l) * tr[i];
            }
        };
        sample_lights(&self.prop, &self.scene.world.lights, &at, rng, &mut sc.rays.shadow, &|_, _| 1.0, &mut add);
        if self.scene.world.lights.iter().any(|l| !l.is_delta()) {
            // Phase sampling, for the lane-0 wavelength's phase function, toward area lights.
            let (wi, pdf) = here.phase_sample(lanes.nm[0], wo, rng.uniform2());
            let to_light = -wi;
            sc.rays.shadow += 1;
            match self.prop.first_opaque_hit(x, None, to_light, Some(id), nm, rng) {
                Some((Some(hit), tr)) => {
                    if let Some(light) = self.scene.world.area_light_of(hit.prim) {
                        let cos = light.emitted_cos(hit.normal, wi);
                        if cos > 0.0 && pdf > 0.0 {
                            let p_light = hit.t * hit.t / (cos * light.shape.area());
                            let mis = power_heuristic(pdf, p_light);
                            let le = |l: f64| light.emission.spectrum.eval(l);
                            for i in 0..lanes.len {
                                let l = lanes.nm[i];
                                out[i] += mis * d * sigma_s[i] * phase(l, wi) / pdf * le(l) * tr[i];
                            }
                        }
                    }
                }
                Some((None, tr)) if pdf > 0.0 => {
                    for sky in self
                        .scene
                        .world
                        .lights
                        .iter()
                        .filter_map(|l| if let Light::Sky(s) = l { Some(s) } else { None })
                    {
                        let mis = power_heuristic(pdf, sky.pdf(to_light));
                        if mis > 0.0 {
                            for i in 0..lanes.len {
                                let l = lanes.nm[i];
                                let le = sky.emission.spectrum.eval(l);
                                out[i] += mis * d * sigma_s[i] * phase(l, wi) / pdf * le * tr[i];
                            }
                        }
                    }
                }
                _ => {}
            }
        }
        out
    }

    /// Marches chord `c` (JC98 §4.4): one sample per step, jittered independently in each (one
    /// offset shared by every step, as JC98 has it, leaves the first-order error
    /// (ξ − ½)·h·[g(end) − g(start)] of the whole chord in each estimate: ±7 % per sample for
    /// a sky seen from the ground in 2 km steps, against ±2.6 % with independent offsets); the
    /// step halves after a large
    /// change of the in-scattered light and relaxes back after small ones (see
    /// [`EyeTracer::step_length`]); transmittance carried exactly where the medium allows, by
    /// ratio tracking otherwise; Russian roulette once it is negligible.
    ///
    /// `start`: the normal of the surface the chord starts on, if it does (with the chord's
    /// own end, where the volume estimates end: the beam estimate's tube of discs, the point
    /// estimate's ball; [`SegmentEnds`]).
    pub(super) fn march(
        &self,
        c: &Chord,
        start: Option<DVec3>,
        at: At,
        along: &mut Along,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) {
        let Some(id) = c.medium.filter(|m| !self.prop.is_clear(*m)) else { return };
        let m = &self.scene.world.media[id as usize];
        let lanes = at.lanes;
        if let Some(column) = c.column_m {
            // The layered upper air crossed in one move (it only absorbs, σ_t(λ)·d): its
            // transmittance from the path's density column.
            for (t, l) in along.tr.iter_mut().zip(&lanes.nm[..lanes.len]) {
                *t *= (-m.sigma_t(*l) * column).exp();
            }
            return;
        }
        if !m.scatters() {
            // A medium that only absorbs sends nothing toward the eye: its transmittance, in one
            // piece (no steps, no roulette on a deep optical depth).
            self.attenuate(m, c, 0.0, c.length, lanes, along, rng);
            return;
        }
        let shadow = at.mode == Mode::Camera && self.scene.plan.shadow_rays.on;
        // Estimates end on the surfaces the chord starts and ends on (edge_correction).
        let ends = match self.scene.integrator.edge_correction {
            true => SegmentEnds { start, end: c.end_normal },
            false => SegmentEnds::default(),
        };
        // Gather rays keep the point estimate at a few coarse steps: they are averaged by the
        // dozen at each shading point, and a whole chord's tube of discs costs more than that.
        let chord_estimate = match (&self.beam, &self.tubes, at.mode) {
            (Some(b), _, Mode::Camera) => {
                let mut hits = std::mem::take(&mut sc.hits);
                let tr = self.beam_chord(b, &mut hits, (c, ends), (id, m), lanes, along, rng, sc);
                sc.hits = hits;
                Some(tr)
            }
            (None, Some(b), Mode::Camera) => {
                let mut hits = std::mem::take(&mut sc.tubes);
                let tr = self.beam_chord(b, &mut hits, (c, ends), (id, m), lanes, along, rng, sc);
                sc.tubes = hits;
                Some(tr)
            }
            _ => None,
        };
        if let Some(tr) = chord_estimate {
            if shadow {
                // Single scattering by shadow rays keeps its own jittered steps along the chord.
                self.march_steps((c, &Walls::default()), (id, m), at, None, along, rng, sc);
            } else {
                along.tr.iter_mut().zip(&tr).take(lanes.len).for_each(|(a, t)| *a *= t);
            }
            return;
        }
        let est = match at.mode {
            Mode::Camera => self.volume.as_ref(),
            Mode::Gather => self.volume_all.as_ref(),
        };
        let walls = est.map_or_else(Walls::default, |_| ends.walls(c.origin, c.dir, c.length));
        self.march_steps((c, &walls), (id, m), at, est, along, rng, sc);
    }

    /// A whole-chord estimate `b` along chord `c` — the beam estimate's discs
    /// ([`crate::photon_map::beam`]) or photon beams' tubes ([`TubeEstimator`]), gathered into
    /// the scratch `hits`: adds Σ_p T(0→t_p) L_p to `along.l` (weighted by the transmittance
    /// carried so far) and returns the chord's transmittance per lane. Each lane's transmittance
    /// is carried from hit to hit in order along the chord, so a heterogeneous medium is tracked
    /// once per lane.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn beam_chord<E: ChordEstimate>(
        &self,
        b: &E,
        hits: &mut Vec<E::Hit>,
        (c, ends): (&Chord, SegmentEnds),
        (id, m): (u32, &Medium),
        lanes: &Lanes,
        along: &mut Along,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) -> BandValues {
        let n = lanes.len;
        let (mut t_at, mut tr) = ([0.0f64; MAX_BANDS], [1.0f64; MAX_BANDS]);
        // Each lane's extinction once per chord (an ocean's σ_t(λ) is several table look-ups).
        let lane_attenuation: Vec<tracking::Attenuation> =
            lanes.nm[..n].iter().map(|l| tracking::Attenuation::of(m, *l)).collect();
        let mut advance = |i: usize, t: f64, rng: &mut Rng| {
            if t > t_at[i] {
                tr[i] *= lane_attenuation[i].transmittance(c.origin + t_at[i] * c.dir, c.dir, t - t_at[i], rng);
                t_at[i] = t;
            }
            tr[i]
        };
        b.gather(c.origin, c.dir, c.length, ends, hits);
        sc.rays.medium_steps += 1;
        let mut tmp = [0.0; MAX_BANDS];
        let wo = -c.dir;
        for h in hits.iter() {
            let t = E::t(h);
            b.radiance(h, c.origin + t * c.dir, wo, (id, m), &mut tmp, &mut |band, l| {
                for i in (0..n).filter(|i| lanes.band[*i] as usize == band) {
                    along.l[i] += along.tr[i] * advance(i, t, rng) * l;
                }
            });
        }
        for i in 0..n {
            advance(i, c.length, rng);
        }
        tr
    }

    /// The ray march of [`EyeTracer::march`] over chord `c` in medium `(id, m)`, reading the
    /// point estimate `est` (if any; in front of `walls`, the surfaces the chord starts and ends
    /// on) and shadow rays (if the plan has them) at every step.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn march_steps(
        &self,
        (c, walls): (&Chord, &Walls),
        (id, m): (u32, &Medium),
        at: At,
        est: Option<&Estimator>,
        along: &mut Along,
        rng: &mut Rng,
        sc: &mut Scratch,
    ) {
        let lanes = at.lanes;
        let shadow = at.mode == Mode::Camera && self.scene.plan.shadow_rays.on;
        let wo = -c.dir;
        let mut sigma_t = [0.0; MAX_BANDS];
        for (s, l) in sigma_t.iter_mut().zip(&lanes.nm[..lanes.len]) {
            *s = m.sigma_t(*l);
        }
        let unit_sigma_s = (shadow && !matches!(m.coefficients, Coefficients::Constituents(_)))
            .then(|| std::array::from_fn(|i| if i < lanes.len { m.sigma_s(lanes.nm[i]) } else { 0.0 }));
        // Only the part of the chord where the medium is not empty is marched (an atmosphere's
        // air ends at its top): elsewhere nothing scatters and the transmittance is 1.
        let Some((a, b)) = m.support(c.origin, c.dir, c.length) else { return };
        let (mut t0, mut t_prev) = (a, a);
        let mut level = 0u32;
        let mut last: Option<f64> = None;
        while t0 < b {
            // Steps resolve the lanes that still carry light: a lane the medium has made opaque
            // (σ_t = 10¹² m⁻¹ at the excitation of a dye) must not hold the others to its steps.
            let sigma_t_max = (0..lanes.len).filter(|i| along.tr[*i] > 0.0).map(|i| sigma_t[i]).fold(0.0, f64::max);
            let h = self.step_length(m, c, (t0, b - a), sigma_t_max, level, at.mode);
            let t1 = (t0 + h).min(b);
            let s = t0 + rng.uniform() * (t1 - t0);
            sc.rays.medium_steps += 1;
            self.attenuate(m, c, t_prev, s, lanes, along, rng);
            t_prev = s;
            if !self.roulette(along, lanes, rng) {
                return;
            }
            let x = c.origin + s * c.dir;
            let mut src = [0.0; MAX_BANDS];
            if let Some(e) = est {
                let (v, _) = e.volume_scattered_within(x, wo, (id, m), walls, &mut sc.nb);
                add_by_band(&mut src, &v, lanes, &|_| 1.0);
            }
            if shadow {
                let ss = self.single_scattering(x, wo, (id, m), unit_sigma_s.as_ref(), lanes, rng, sc);
                add_by_lane(&mut src, &ss, lanes, &|_| 1.0);
            }
            for ((l, tr), s) in along.l.iter_mut().zip(&along.tr).zip(&src).take(lanes.len) {
                *l += tr * s * (t1 - t0);
            }
            // Adapt to the light: refine after a large change of the source, relax after a small one.
            let total: f64 = src[..lanes.len].iter().sum();
            if let Some(prev) = last {
                let change = (total - prev).abs() / prev.abs().max(total.abs()).max(f64::MIN_POSITIVE);
                if change > ADAPT_REFINE && level < MAX_REFINE {
                    level += 1;
                } else if change < ADAPT_RELAX && level > 0 {
                    level -= 1;
                }
            }
            last = Some(total);
            t0 = t1;
        }
        self.attenuate(m, c, t_prev, b, lanes, along, rng);
    }

    /// The next step from `t0` on a marched span of length `span`: `march_step` halved `level`
    /// times, capped where an atmosphere's density changes ([`Medium::climb_step`]) and at a
    /// quarter of the local mean free path, but not by the latter rules below a
    /// [`MAX_MARCH_STEPS`]th of the span — or, for a gather ray, the span in [`GATHER_STEPS`]
    /// steps.
    pub(super) fn step_length(
        &self,
        m: &Medium,
        c: &Chord,
        (t0, span): (f64, f64),
        sigma_t_max: f64,
        level: u32,
        mode: Mode,
    ) -> f64 {
        let h_max = self.scene.integrator.march_step_m;
        if mode == Mode::Gather {
            return h_max.max(span / GATHER_STEPS);
        }
        let mut h = h_max / f64::from(1u32 << level);
        let floor = h.min(span / MAX_MARCH_STEPS);
        h = h.min(m.climb_step(c.origin + t0 * c.dir, c.dir));
        let local = sigma_t_max * m.density.at(c.origin + t0 * c.dir);
        if local > 0.0 {
            h = h.min(0.25 / local);
        }
        h.max(1e-6 * h_max).max(floor)
    }

    /// Multiplies the carried transmittance by that of the chord between `a` and `b`.
    #[allow(clippy::too_many_arguments)]
    pub(super) fn attenuate(
        &self,
        m: &Medium,
        c: &Chord,
        a: f64,
        b: f64,
        lanes: &Lanes,
        along: &mut Along,
        rng: &mut Rng,
    ) {
        let o = c.origin + a * c.dir;
        tracking::transmittances(m, &lanes.nm[..lanes.len], o, c.dir, b - a, rng, &mut along.tr[..lanes.len]);
    }

    /// Russian roulette on negligible transmittance: continue with probability 1/2 and double
    /// the weight, or stop (false), which is unbiased.
    pub(super) fn roulette(&self, along: &mut Along, lanes: &Lanes, rng: &mut Rng) -> bool {
        if along.tr[..lanes.len].iter().any(|t| *t >= ROULETTE_TRANSMITTANCE) {
            return true;
        }
        if rng.uniform() < 0.5 {
            along.tr.iter_mut().for_each(|t| *t = 0.0);
            return false;
        }
        along.tr.iter_mut().for_each(|t| *t *= 2.0);
        true
    }
}
