//! Free-flight sampling and transmittance along a straight segment of a medium.
//!
//! - Free flight: where a photon first interacts, p(t) = σ_t(t) T(0, t). Homogeneous media are
//!   sampled exactly (t = −ln(1 − ξ)/σ_t); otherwise by delta tracking (Woodcock et al. 1965;
//!   Novák et al. 2018, "Monte Carlo Methods for Physically Based Volume Rendering", §4.1):
//!   tentative collisions at rate σ̄ (the majorant of each interval), accepted as real with
//!   probability σ_t(x)/σ̄.
//! - Transmittance T = exp(−∫σ_t): in closed form where the density has one (uniform,
//!   exponential), else by ratio tracking (Cramer 1978; Novák et al. 2014), an unbiased estimator
//!   T̂ = Π (1 − σ_t(x_i)/σ̄) over the tentative collisions.

use super::constituents::{Constituents, PerConstituent};
use super::density::Density;
use super::medium::{Coefficients, Medium};
use crate::rng::Rng;
use glam::DVec3;

/// σ_t(λ, x) of a medium at one wavelength: its extinction at density 1 times the density
/// field, or the sum over an atmosphere's constituents.
enum Extinction<'a> {
    Scaled { sigma_t: f64, density: &'a Density },
    Constituents { c: &'a Constituents, sigma: PerConstituent },
}

impl<'a> Extinction<'a> {
    fn of(m: &'a Medium, wavelength_nm: f64) -> Extinction<'a> {
        match &m.coefficients {
            Coefficients::Constituents(c) => Extinction::Constituents { c, sigma: c.extinction(wavelength_nm) },
            _ => Extinction::Scaled { sigma_t: m.sigma_t(wavelength_nm), density: &m.density },
        }
    }

    /// True when σ_t(λ) vanishes everywhere.
    fn is_zero(&self) -> bool {
        match self {
            Extinction::Scaled { sigma_t, .. } => *sigma_t <= 0.0,
            Extinction::Constituents { sigma, .. } => sigma.iter().all(|s| *s <= 0.0),
        }
    }

    /// σ_t(λ, x).
    fn at(&self, p: DVec3) -> f64 {
        match self {
            Extinction::Scaled { sigma_t, density } => sigma_t * density.at(p),
            Extinction::Constituents { c, sigma } => c.sigma_t_at(sigma, p),
        }
    }

    /// Intervals of the ray with a majorant σ̄ ≥ σ_t on each.
    fn majorant_intervals(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        match self {
            Extinction::Scaled { sigma_t, density } => {
                density.majorant_intervals(o, dir, t_max, &mut |t0, t1, bound| visit(t0, t1, sigma_t * bound))
            }
            Extinction::Constituents { c, sigma } => c.majorant_intervals(sigma, o, dir, t_max, visit),
        }
    }

    /// ∫₀ᵗ σ_t ds where it is known without sampling (`tabulated`: an atmosphere's columns to
    /// the top read from its tables, [`Density::integral_tabulated`]).
    fn optical_depth_exact(&self, o: DVec3, dir: DVec3, t: f64, tabulated: bool) -> Option<f64> {
        match self {
            Extinction::Scaled { sigma_t, density } => {
                let d =
                    if tabulated { density.integral_tabulated(o, dir, t) } else { density.integral_exact(o, dir, t) };
                d.map(|d| sigma_t * d)
            }
            Extinction::Constituents { c, sigma } => Some(c.optical_depth(sigma, o, dir, t, tabulated)),
        }
    }
}

/// Distance to the first real interaction along `o + t·dir` within [0, t_max], if any.
pub fn sample_interaction(
    m: &Medium,
    wavelength_nm: f64,
    o: DVec3,
    dir: DVec3,
    t_max: f64,
    rng: &mut Rng,
) -> Option<f64> {
    let field = Extinction::of(m, wavelength_nm);
    if field.is_zero() {
        return None;
    }
    if let (true, Extinction::Scaled { sigma_t, .. }) = (m.is_homogeneous(), &field) {
        let t = -(-rng.uniform()).ln_1p() / sigma_t;
        return (t < t_max).then_some(t);
    }
    delta_tracking_field(&field, o, dir, t_max, rng)
}

/// Tentative collisions along `o + t·dir` within [0, t_max] at the rate of each majorant
/// interval σ̄ (exponential steps −ln(1 − ξ)/σ̄); at each one `visit(t, σ_t(x), σ̄)` is called
/// with the real collision rate at x, and returns whether to go on. The one loop under delta and
/// ratio tracking (Novák et al. 2018, §4).
fn tentative_collisions(
    field: &Extinction,
    o: DVec3,
    dir: DVec3,
    t_max: f64,
    rng: &mut Rng,
    visit: &mut dyn FnMut(f64, f64, f64, &mut Rng) -> bool,
) {
    field.majorant_intervals(o, dir, t_max, &mut |t0, t1, majorant| {
        if majorant <= 0.0 {
            return true;
        }
        let mut t = t0;
        loop {
            t += -(-rng.uniform()).ln_1p() / majorant;
            if t >= t1 {
                return true;
            }
            if !visit(t, field.at(o + t * dir), majorant, rng) {
                return false;
            }
        }
    });
}

/// Delta tracking over the density's majorant intervals of a medium with extinction `sigma_t`
/// at density 1: a tentative collision is real with probability σ_t(x)/σ̄.
pub fn delta_tracking(m: &Medium, sigma_t: f64, o: DVec3, dir: DVec3, t_max: f64, rng: &mut Rng) -> Option<f64> {
    delta_tracking_field(&Extinction::Scaled { sigma_t, density: &m.density }, o, dir, t_max, rng)
}

fn delta_tracking_field(field: &Extinction, o: DVec3, dir: DVec3, t_max: f64, rng: &mut Rng) -> Option<f64> {
    let mut found = None;
    tentative_collisions(field, o, dir, t_max, rng, &mut |t, rate, majorant, rng| {
        if rng.uniform() * majorant < rate {
            found = Some(t);
            return false;
        }
        true
    });
    found
}

/// Transmittance exp(−∫₀ᵗ σ_t ds) along `o + s·dir`: exact where possible (an atmosphere's
/// columns to its top from its tables, [`crate::media::density::ColumnTable`]), else ratio
/// tracking.
pub fn transmittance(m: &Medium, wavelength_nm: f64, o: DVec3, dir: DVec3, t: f64, rng: &mut Rng) -> f64 {
    Attenuation::of(m, wavelength_nm).transmittance(o, dir, t, rng)
}

/// A medium's extinction at one wavelength, looked up once for many segments: what
/// [`transmittance`] computes for each segment, to the bit, without evaluating σ_t(λ) again
/// (the beam estimate carries a chord's transmittance from photon to photon).
pub struct Attenuation<'a>(Extinction<'a>);

impl<'a> Attenuation<'a> {
    /// The extinction of `m` at `wavelength_nm`.
    pub fn of(m: &'a Medium, wavelength_nm: f64) -> Attenuation<'a> {
        Attenuation(Extinction::of(m, wavelength_nm))
    }

    /// [`transmittance`] of the segment o + s·dir, s in [0, t].
    pub fn transmittance(&self, o: DVec3, dir: DVec3, t: f64, rng: &mut Rng) -> f64 {
        if self.0.is_zero() || t <= 0.0 {
            return 1.0;
        }
        match self.0.optical_depth_exact(o, dir, t, true) {
            Some(depth) => (-depth).exp(),
            None => ratio_tracking_field(&self.0, o, dir, t, rng),
        }
    }
}

/// [`transmittance`] at each of `wavelengths_nm` in turn, multiplied into `tr` (to the bit, with
/// the same random numbers), but the density's integral along the segment, which does not
/// depend on the wavelength, is found once for all of them where it is exact: a shadow ray
/// through an atmosphere costs one quadrature, not one per band.
#[allow(clippy::too_many_arguments)]
pub fn transmittances(m: &Medium, wavelengths_nm: &[f64], o: DVec3, dir: DVec3, t: f64, rng: &mut Rng, tr: &mut [f64]) {
    if t <= 0.0 {
        return;
    }
    let (mut density_column, mut columns) = (None, None);
    for (x, l) in tr.iter_mut().zip(wavelengths_nm) {
        let field = Extinction::of(m, *l);
        if field.is_zero() {
            continue;
        }
        let depth = match &field {
            Extinction::Scaled { sigma_t, density } => {
                (*density_column.get_or_insert_with(|| density.integral_tabulated(o, dir, t))).map(|d| sigma_t * d)
            }
            Extinction::Constituents { c, sigma } => {
                Some(Constituents::dot(sigma, columns.get_or_insert_with(|| c.columns(o, dir, t, true))))
            }
        };
        *x *= match depth {
            Some(depth) => (-depth).exp(),
            None => ratio_tracking_field(&field, o, dir, t, rng),
        };
    }
}

/// The transmittances of a path of several chords through one medium at several wavelengths:
/// what multiplying [`transmittances`] over the chords gives (to rounding, where the integrals
/// are exact), with the part that does not depend on the wavelength summed over the chords
/// first — one density integral (or one set of constituent columns) per chord, then one σ_t(λ)
/// and one exponential per wavelength for the whole path: exp(−σ_t(λ)·Σ_chords ∫d ds). A chord
/// without an exact integral is ratio-tracked at each wavelength, as there.
pub struct PathDepth<'m> {
    m: &'m Medium,
    /// Σ ∫ d ds over the chords with an exact integral (scaled media).
    column: f64,
    /// Σ of the constituents' columns (atmospheres of constituents).
    columns: PerConstituent,
    /// Product of the ratio-tracking estimates, per wavelength.
    tracked: [f64; crate::spectrum::MAX_BANDS],
}

impl<'m> PathDepth<'m> {
    /// An empty path in `m`.
    pub fn new(m: &'m Medium) -> PathDepth<'m> {
        PathDepth {
            m,
            column: 0.0,
            columns: [0.0; super::constituents::MAX_CONSTITUENTS],
            tracked: [1.0; crate::spectrum::MAX_BANDS],
        }
    }

    /// Adds a density column ∫d ds already integrated along a curved path (the layered upper
    /// air's, [`crate::raypath::Chord::column_m`]), m: for a medium whose extinction is
    /// σ_t(λ)·d.
    pub fn add_column(&mut self, column_m: f64) {
        self.column += column_m;
    }

    /// Adds the chord `o + s·dir`, s ∈ [0, t], at `wavelengths_nm` (the same at every call).
    pub fn add(&mut self, wavelengths_nm: &[f64], o: DVec3, dir: DVec3, t: f64, rng: &mut Rng) {
        if t <= 0.0 {
            return;
        }
        if let Coefficients::Constituents(c) = &self.m.coefficients {
            for (sum, x) in self.columns.iter_mut().zip(c.columns(o, dir, t, true)) {
                *sum += x;
            }
            return;
        }
        if let Some(d) = self.m.density.integral_tabulated(o, dir, t) {
            self.column += d;
            return;
        }
        for (x, l) in self.tracked.iter_mut().zip(wavelengths_nm) {
            let field = Extinction::of(self.m, *l);
            if !field.is_zero() {
                *x *= ratio_tracking_field(&field, o, dir, t, rng);
            }
        }
    }

    /// Multiplies the path's transmittance at each of `wavelengths_nm` into `tr`.
    pub fn transmittances(&self, wavelengths_nm: &[f64], tr: &mut [f64]) {
        for ((x, l), tracked) in tr.iter_mut().zip(wavelengths_nm).zip(&self.tracked) {
            let depth = match Extinction::of(self.m, *l) {
                Extinction::Scaled { sigma_t, .. } => sigma_t * self.column,
                Extinction::Constituents { sigma, .. } => Constituents::dot(&sigma, &self.columns),
            };
            *x *= tracked * (-depth).exp();
        }
    }
}

/// The optical depth ∫₀ᵗ σ_t ds along `o + s·dir` where it can be computed without sampling
/// (homogeneous media, height profiles, atmospheres); `None` where only ratio tracking can.
pub fn optical_depth_exact(m: &Medium, wavelength_nm: f64, o: DVec3, dir: DVec3, t: f64) -> Option<f64> {
    let field = Extinction::of(m, wavelength_nm);
    if field.is_zero() || t <= 0.0 {
        return Some(0.0);
    }
    field.optical_depth_exact(o, dir, t, false)
}

/// Ratio tracking estimate of the transmittance of a medium with extinction `sigma_t` at
/// density 1: T̂ = Π (1 − σ_t(x_i)/σ̄) over the tentative collisions.
pub fn ratio_tracking(m: &Medium, sigma_t: f64, o: DVec3, dir: DVec3, t_max: f64, rng: &mut Rng) -> f64 {
    ratio_tracking_field(&Extinction::Scaled { sigma_t, density: &m.density }, o, dir, t_max, rng)
}

fn ratio_tracking_field(field: &Extinction, o: DVec3, dir: DVec3, t_max: f64, rng: &mut Rng) -> f64 {
    let mut tr = 1.0;
    tentative_collisions(field, o, dir, t_max, rng, &mut |_, rate, majorant, _| {
        tr *= 1.0 - rate / majorant;
        tr > 0.0
    });
    tr.max(0.0)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::media::Coefficients;
    use crate::media::density::{Density, ExponentialHeight};
    use crate::media::phase::PhaseFunction;
    use crate::rng::Stream;
    use crate::spectrum::Spectrum;
    use crate::testing::chi2::chi2_1d;

    fn exponential_fog() -> Medium {
        Medium {
            name: "haze".into(),
            coefficients: Coefficients::AbsorptionScattering {
                sigma_a: Spectrum::Constant(0.3),
                sigma_s: Spectrum::Constant(0.5),
            },
            phase: PhaseFunction::isotropic(),
            density: Density::ExponentialHeight(ExponentialHeight {
                up: DVec3::Y,
                reference_m: 0.0,
                scale_height_m: 2.0,
            }),
            index: None,
            inelastic: crate::media::inelastic::Inelastic::none(),
        }
    }

    /// Optical depth along a slanted ray through the exponential profile, in closed form:
    /// τ(t) = σ_t d(o) H/μ (1 − e^{−μt/H}).
    fn tau(o: DVec3, dir: DVec3, t: f64) -> f64 {
        let (h, mu) = (2.0, dir.y);
        0.8 * (-o.y / h).exp() * h / mu * (1.0 - (-mu * t / h).exp())
    }

    #[test]
    fn delta_tracking_samples_the_exponential_free_flight_density() {
        let m = exponential_fog();
        let (o, dir, t_max) = (DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.6, 0.8, 0.0), 6.0);
        let mut rng = Rng::for_task(51, Stream::Test, 0);
        // Density of the interaction distance: σ_t(t) e^{−τ(t)}; no interaction has mass e^{−τ(t_max)}.
        let pdf = |t: f64| 0.8 * (-(o.y + t * dir.y) / 2.0).exp() * (-tau(o, dir, t)).exp();
        let p = chi2_1d((0.0, t_max), 40, 200_000, || delta_tracking(&m, 0.8, o, dir, t_max, &mut rng), pdf);
        assert!(p > 1e-3, "p = {p}");
        // The generic path (delta tracking) and exact transmittance agree on the escape fraction.
        let mut rng = Rng::for_task(52, Stream::Test, 0);
        let n = 200_000;
        let escaped = (0..n).filter(|_| delta_tracking(&m, 0.8, o, dir, t_max, &mut rng).is_none()).count();
        let expect = (-tau(o, dir, t_max)).exp();
        let se = (expect * (1.0 - expect) / n as f64).sqrt();
        assert!((escaped as f64 / n as f64 - expect).abs() < 4.0 * se);
    }

    #[test]
    fn ratio_tracking_is_unbiased_for_the_exponential_transmittance() {
        let m = exponential_fog();
        let mut rng = Rng::for_task(53, Stream::Test, 0);
        for (o, dir, t) in [
            (DVec3::new(0.0, -1.0, 0.0), DVec3::new(0.6, 0.8, 0.0), 6.0),
            (DVec3::new(0.0, 3.0, 0.0), DVec3::new(0.0, -0.6, 0.8), 7.0),
            (DVec3::new(0.0, 0.5, 0.0), DVec3::X, 3.0),
        ] {
            let exact = (-tau(o, dir, t)).exp();
            let closed = transmittance(&m, 550.0, o, dir, t, &mut rng);
            if dir.y != 0.0 {
                assert!((closed - exact).abs() < 1e-12, "closed form {closed} vs {exact}");
            }
            let n = 100_000;
            let est: Vec<f64> = (0..n).map(|_| ratio_tracking(&m, 0.8, o, dir, t, &mut rng)).collect();
            let mean = est.iter().sum::<f64>() / n as f64;
            let var = est.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1) as f64;
            let reference = if dir.y != 0.0 { exact } else { (-0.8 * (-0.25f64).exp() * t).exp() };
            assert!((mean - reference).abs() < 4.0 * (var / n as f64).sqrt() + 1e-12, "{mean} vs {reference}");
        }
    }

    #[test]
    fn homogeneous_free_flight_is_exponential() {
        let m = Medium { density: Density::Uniform, ..exponential_fog() };
        let mut rng = Rng::for_task(54, Stream::Test, 0);
        let p = chi2_1d(
            (0.0, 3.0),
            30,
            100_000,
            || sample_interaction(&m, 550.0, DVec3::ZERO, DVec3::X, 3.0, &mut rng),
            |t| 0.8 * (-0.8 * t).exp(),
        );
        assert!(p > 1e-3, "p = {p}");
    }

    /// The chords of a bent path: a polyline of `n` pieces from `o`, turning a little at each.
    fn polyline(o: DVec3, n: usize) -> Vec<(DVec3, DVec3, f64)> {
        let mut p = o;
        (0..n)
            .map(|i| {
                let a = 0.3 + 0.15 * i as f64;
                let dir = DVec3::new(a.cos(), 0.2 - 0.1 * i as f64, a.sin()).normalize();
                let len = 0.7 + 0.2 * i as f64;
                let c = (p, dir, len);
                p += len * dir;
                c
            })
            .collect()
    }

    /// Multiplies `transmittances` over the chords, the way a march does.
    fn chord_by_chord(m: &Medium, nm: &[f64], chords: &[(DVec3, DVec3, f64)], rng: &mut Rng) -> Vec<f64> {
        let mut tr = vec![1.0; nm.len()];
        for (o, d, t) in chords {
            transmittances(m, nm, *o, *d, *t, rng, &mut tr);
        }
        tr
    }

    fn whole_path(m: &Medium, nm: &[f64], chords: &[(DVec3, DVec3, f64)], rng: &mut Rng) -> Vec<f64> {
        let mut depth = PathDepth::new(m);
        for (o, d, t) in chords {
            depth.add(nm, *o, *d, *t, rng);
        }
        let mut tr = vec![1.0; nm.len()];
        depth.transmittances(nm, &mut tr);
        tr
    }

    #[test]
    fn a_paths_depth_summed_over_its_chords_gives_each_chords_transmittances_multiplied() {
        let nm = [400.0, 550.0, 700.0];
        let chords = polyline(DVec3::new(0.0, 1.0, 0.0), 6);
        // Exact integrals: the exponential profile, and a zero extinction at one wavelength.
        let mut m = exponential_fog();
        m.coefficients = Coefficients::AbsorptionScattering {
            sigma_a: Spectrum::Tabulated(crate::spectrum::Tabulated::new(vec![400.0, 700.0], vec![0.0, 0.9]).unwrap()),
            sigma_s: Spectrum::Constant(0.0),
        };
        let mut rng = Rng::for_task(7, Stream::Test, 0);
        let (a, b) = (chord_by_chord(&m, &nm, &chords, &mut rng), whole_path(&m, &nm, &chords, &mut rng));
        assert_eq!(a[0], 1.0);
        assert_eq!(b[0], 1.0);
        for (a, b) in a.iter().zip(&b).skip(1) {
            assert!((a / b - 1.0).abs() < 1e-13 && *b < 1.0, "{a} vs {b}");
        }
        // Ratio tracking where the density has no closed form: the same random numbers in the
        // same order (chord by chord, then wavelength by wavelength), so the same estimates.
        let fbm = Medium { density: Density::Fbm(Box::new(crate::media::density::Fbm::new(0.5, 0.5, 0.7, 3, 5))), ..m };
        let a = chord_by_chord(&fbm, &nm, &chords, &mut Rng::for_task(8, Stream::Test, 0));
        let b = whole_path(&fbm, &nm, &chords, &mut Rng::for_task(8, Stream::Test, 0));
        assert_eq!(a, b);
        assert!(a[1] < 1.0 && a[2] < a[1], "{a:?}");
    }
}
