//! Every refractive-index field's analytic gradient against central finite differences at random
//! points and wavelengths (the property the ray equation relies on), plus the region and
//! validation contracts of `IndexField`.
//!
//! Each check uses a step h chosen for the field's length scale L (h ≈ 1e-4…1e-3 L), so the
//! truncation error of the central difference, ~h²|∇³n|/6 ≈ (h/L)²|∇n|/6, is below 1e-6 |∇n|;
//! the rounding error of n (≈ 1 ulp of 1 per evaluation) adds 8ε/(2h) to the allowance.

use glam::DVec3;
use morgana::atmosphere::edit::{Bubble, GridEdit, HotSurface, Inversion, Offset};
use morgana::atmosphere::{AirDispersion, Atmosphere, BaseProfile, Earth, Edit, TableProfile, usa76};
use morgana::field::{Bump, GradientRegion, Interpolation, Lattice};
use morgana::geometry::Aabb;
use morgana::material::Ior;
use morgana::media::refractive_index::{
    Constant, Exponential, GridPressure, IndexField, Linear, Profile, Sum, TemperatureGrid,
};
use morgana::rng::{Rng, Stream};

/// Relative tolerance of the gradient check.
const RTOL: f64 = 2e-6;

struct Check<'a> {
    name: &'a str,
    field: &'a IndexField,
    /// Finite-difference step, m.
    step: f64,
}

impl Check<'_> {
    /// Compares ∇n with central differences at `p`; also that `n` agrees with `n_grad`.
    fn at(&self, wavelength_nm: f64, p: DVec3) {
        let (n, g) = self.field.n_grad(wavelength_nm, p);
        assert!(n.is_finite() && g.is_finite(), "{}: n = {n}, ∇n = {g} at {p}", self.name);
        assert_eq!(n, self.field.n(wavelength_nm, p), "{}: n and n_grad disagree at {p}", self.name);
        let h = self.step;
        let fd = DVec3::new(
            self.diff(wavelength_nm, p, DVec3::X),
            self.diff(wavelength_nm, p, DVec3::Y),
            self.diff(wavelength_nm, p, DVec3::Z),
        );
        let allowed = RTOL * g.length() + 8.0 * f64::EPSILON * n.abs() / (2.0 * h);
        let err = (g - fd).length();
        assert!(
            err <= allowed,
            "{}: at {p}, λ = {wavelength_nm} nm: ∇n = {g:?}, central difference {fd:?}, |error| {err:e} > {allowed:e}",
            self.name
        );
    }

    fn diff(&self, wavelength_nm: f64, p: DVec3, e: DVec3) -> f64 {
        let h = self.step;
        (self.field.n(wavelength_nm, p + h * e) - self.field.n(wavelength_nm, p - h * e)) / (2.0 * h)
    }
}

/// `count` random (λ, point) pairs: λ uniform in 380–780 nm, the point from `point(u)`.
fn samples(seed: u64, count: u64, point: impl Fn([f64; 3]) -> DVec3) -> Vec<(f64, DVec3)> {
    (0..count)
        .map(|i| {
            let mut rng = Rng::for_task(seed, Stream::Test, i);
            let l = 380.0 + 400.0 * rng.uniform();
            (l, point([rng.uniform(), rng.uniform(), rng.uniform()]))
        })
        .collect()
}

fn spread(u: [f64; 3], half: DVec3, centre: DVec3) -> DVec3 {
    centre + half * (2.0 * DVec3::from_array(u) - DVec3::ONE)
}

#[test]
fn constant_fields_have_zero_gradient_and_dispersion_when_asked() {
    let glass = IndexField::Constant(Constant::Ior(Ior::Sellmeier {
        b: [1.039_612_12, 0.231_792_344, 1.010_469_45],
        c_um2: [0.006_000_698_67, 0.020_017_914_4, 103.560_653],
    }));
    let check = Check { name: "constant (N-BK7)", field: &glass, step: 1e-3 };
    for (l, p) in samples(1, 50, |u| spread(u, DVec3::splat(10.0), DVec3::ZERO)) {
        check.at(l, p);
    }
    assert!(glass.is_uniform() && glass.is_dispersive());
    assert!(glass.n(450.0, DVec3::ZERO) > glass.n(650.0, DVec3::ZERO));
}

#[test]
fn constant_air_is_uniform_and_dispersive() {
    let air =
        IndexField::Constant(Constant::Air { dispersion: AirDispersion::ciddor(450.0).unwrap(), density_kg_m3: 1.225 });
    let check = Check { name: "constant air", field: &air, step: 1e-3 };
    for (l, p) in samples(11, 20, |u| spread(u, DVec3::splat(10.0), DVec3::ZERO)) {
        check.at(l, p);
    }
    assert!(air.is_uniform() && air.is_dispersive());
    let domain = Aabb { min: DVec3::splat(-1.0), max: DVec3::splat(1.0) };
    let e = air.validate(&domain, (100.0, 800.0), false).unwrap_err();
    assert!(e.contains("200") && e.contains("100"), "{e}");
}

#[test]
fn linear_field_gradient_matches_differences() {
    let dir = DVec3::new(0.3, 1.0, -0.2);
    let f = IndexField::Linear(Linear::new(1.0, 0.1, dir).unwrap());
    let check = Check { name: "linear", field: &f, step: 1e-3 };
    for (l, p) in samples(2, 200, |u| spread(u, DVec3::splat(5.0), DVec3::ZERO)) {
        check.at(l, p);
    }
    let (_, g) = f.n_grad(500.0, DVec3::ZERO);
    assert!((g - 0.1 * dir.normalize()).length() < 1e-16);
    assert_eq!(f.gradient_region(), GradientRegion::Everywhere);
    assert!(!f.is_uniform() && !f.is_dispersive());
}

#[test]
fn exponential_field_gradient_matches_differences_on_flat_and_spherical_earths() {
    for (name, earth) in [("exponential, flat", Earth::flat_y()), ("exponential, spherical", Earth::standard())] {
        let f = IndexField::Exponential(Exponential::new(1.000_293, 8_000.0, earth).unwrap());
        let check = Check { name, field: &f, step: 10.0 };
        // Heights 100 m – 30 km, up to 50 km sideways.
        for (l, p) in samples(3, 200, |u| DVec3::new(1e5 * (u[0] - 0.5), 100.0 + 29_900.0 * u[1], 1e5 * (u[2] - 0.5))) {
            check.at(l, p);
        }
    }
}

#[test]
fn tabulated_profile_gradient_matches_differences_away_from_knots() {
    let h: Vec<f64> = (0..=20).map(|i| 100.0 * i as f64).collect();
    let n: Vec<f64> = h.iter().map(|z| 1.0 + 2.9e-4 * (-z / 8_000.0).exp() + 3e-6 * (z / 300.0).sin()).collect();
    for (name, earth) in [("profile, flat", Earth::flat_y()), ("profile, spherical", Earth::standard())] {
        let f = IndexField::Profile(Profile::new(h.clone(), n.clone(), earth).unwrap());
        let check = Check { name, field: &f, step: 1e-2 };
        let mut tested = 0;
        for (l, p) in samples(4, 400, |u| DVec3::new(200.0 * (u[0] - 0.5), 2000.0 * u[1], 200.0 * (u[2] - 0.5))) {
            let z = earth.height(p);
            // A difference straddling a knot sees the jump in n″ (PCHIP is C¹, not C²).
            if h.iter().any(|k| (z - k).abs() < 0.05) {
                continue;
            }
            check.at(l, p);
            tested += 1;
        }
        assert!(tested > 300, "{name}: only {tested} points tested");
    }
}

/// A warm plume in a 24×16×20 lattice (0.5 m cells) over 280 K ground air.
fn plume_lattice() -> Lattice {
    let origin = DVec3::new(-6.0, 0.0, -5.0);
    Lattice::from_fn([24, 16, 20], origin, DVec3::splat(0.5), |p| {
        280.0 + 25.0 * (-(p.x * p.x + p.z * p.z) / 8.0 - p.y / 3.0).exp() + 0.5 * (1.3 * p.x + 0.7 * p.z).sin()
    })
    .unwrap()
}

#[test]
fn temperature_grid_gradient_matches_differences() {
    let cases = [
        ("grid, trilinear, 1 atm", Interpolation::Trilinear, GridPressure::Constant { pressure_pa: 101_325.0 }),
        ("grid, tricubic, 1 atm", Interpolation::Tricubic, GridPressure::Constant { pressure_pa: 101_325.0 }),
        ("grid, tricubic, USA76 flat", Interpolation::Tricubic, GridPressure::Usa76 { earth: Earth::flat_y() }),
        ("grid, trilinear, USA76 sphere", Interpolation::Trilinear, GridPressure::Usa76 { earth: Earth::standard() }),
    ];
    for (seed, (name, interp, pressure)) in cases.into_iter().enumerate() {
        let dispersion = AirDispersion::ciddor(450.0).unwrap();
        let grid = TemperatureGrid::new(plume_lattice(), interp, pressure, dispersion).unwrap();
        let f = IndexField::TemperatureGrid(Box::new(grid));
        let check = Check { name, field: &f, step: 1e-5 };
        let mut tested = 0;
        for (l, p) in
            samples(20 + seed as u64, 400, |u| spread(u, DVec3::new(5.5, 3.6, 4.5), DVec3::new(-0.25, 3.75, -0.25)))
        {
            // Central differences straddling a cell face see the interpolant's kink (trilinear)
            // or the jump in its second derivative (Catmull–Rom).
            let cell = (p - DVec3::new(-6.0, 0.0, -5.0)) / 0.5;
            let frac = cell - cell.floor();
            if frac.min_element() < 1e-3 || frac.max_element() > 1.0 - 1e-3 {
                continue;
            }
            check.at(l, p);
            tested += 1;
        }
        assert!(tested > 380, "{name}: {tested}");
    }
}

#[test]
fn temperature_grid_region_and_temperature_checks() {
    let flat = Lattice::from_fn([6, 6, 6], DVec3::ZERO, DVec3::ONE, |p| {
        let inside = (p - DVec3::splat(2.5)).length() < 1.5;
        if inside { 300.0 } else { 290.0 }
    })
    .unwrap();
    let air = AirDispersion::CauchyBornWolf;
    let g =
        TemperatureGrid::new(flat.clone(), Interpolation::Tricubic, GridPressure::Constant { pressure_pa: 9e4 }, air)
            .unwrap();
    let bounds = flat.bounds();
    let f = IndexField::TemperatureGrid(Box::new(g));
    assert_eq!(f.gradient_region(), GradientRegion::Box(bounds));
    for p in [DVec3::new(-1.0, 2.0, 2.0), DVec3::new(7.0, 3.0, 1.0), DVec3::new(2.0, -3.0, 9.0)] {
        assert_eq!(f.n_grad(550.0, p).1, DVec3::ZERO, "gradient outside the box at {p}");
    }
    // n is continuous across the box faces.
    let face = DVec3::new(0.0, 2.3, 2.7);
    let (a, b) = (f.n(550.0, face - 1e-9 * DVec3::X), f.n(550.0, face + 1e-9 * DVec3::X));
    assert!((a - b).abs() < 1e-15);
    // At constant pressure n − 1 ∝ 1/T (Stam & Languenou): 290 K air vs 300 K air.
    let cold = f.n(550.0, DVec3::new(0.0, 0.0, 0.0)) - 1.0;
    let hot = f.n(550.0, DVec3::splat(2.0)) - 1.0;
    assert!((hot / cold - 290.0 / 300.0).abs() < 1e-12, "{}", hot / cold);
    // With hydrostatic pressure the gradient is everywhere.
    let g = TemperatureGrid::new(
        flat.clone(),
        Interpolation::Trilinear,
        GridPressure::Usa76 { earth: Earth::flat_y() },
        air,
    )
    .unwrap();
    assert_eq!(IndexField::TemperatureGrid(Box::new(g)).gradient_region(), GradientRegion::Everywhere);
    // Temperatures that Catmull–Rom could drive to zero are rejected; trilinear is fine.
    let spiky =
        Lattice::from_fn([6, 6, 6], DVec3::ZERO, DVec3::ONE, |p| if p.x == 2.0 { 400.0 } else { 20.0 }).unwrap();
    let p = GridPressure::Constant { pressure_pa: 1e5 };
    let e = TemperatureGrid::new(spiky.clone(), Interpolation::Tricubic, p, air).unwrap_err();
    assert!(e.contains("positive"), "{e}");
    assert!(TemperatureGrid::new(spiky, Interpolation::Trilinear, p, air).is_ok());
}

#[test]
fn catmull_rom_stays_above_the_stated_overshoot_bound() {
    // Random lattices: the interpolant never falls below min − 0.48·min(range, 9·max step), the
    // bound `TemperatureGrid` relies on.
    for seed in 0..20 {
        let mut rng = Rng::for_task(seed, Stream::Test, 999);
        let vals: Vec<f64> = (0..5 * 5 * 5).map(|_| if rng.uniform() < 0.3 { 10.0 } else { 0.0 }).collect();
        let l = Lattice::new([5, 5, 5], DVec3::ZERO, DVec3::ONE, vals).unwrap();
        let (lo, hi) = l.value_range();
        let bound = lo - 0.48 * (hi - lo).min(9.0 * l.max_step());
        for i in 0..2000 {
            let mut r = Rng::for_task(seed, Stream::Test, i);
            let p = DVec3::new(r.uniform(), r.uniform(), r.uniform()) * 4.0;
            let v = l.value_grad(p, Interpolation::Tricubic, morgana::field::Beyond::Clamp).0;
            assert!(v >= bound, "{v} < {bound}");
        }
    }
}

#[test]
fn sum_of_base_and_bumps_gradient_matches_differences() {
    let base = IndexField::Exponential(Exponential::new(1.000_29, 8_000.0, Earth::flat_y()).unwrap());
    let bumps = vec![
        Bump::new(DVec3::new(0.0, 3.0, 0.0), 2.0, -2e-5).unwrap(),
        Bump::new(DVec3::new(1.0, 4.0, 0.5), 1.5, 1e-5).unwrap(),
    ];
    let f = IndexField::Sum(Sum { base: Box::new(base), bumps });
    let check = Check { name: "sum with bumps", field: &f, step: 1e-4 };
    for (l, p) in samples(5, 400, |u| spread(u, DVec3::new(3.0, 3.0, 3.0), DVec3::new(0.5, 3.5, 0.2))) {
        check.at(l, p);
    }
    // The bump ends smoothly: n and ∇n are continuous at r = R.
    let edge = DVec3::new(0.0, 3.0, 2.0);
    let inside = f.n_grad(550.0, edge - DVec3::Z * 1e-9);
    let outside = f.n_grad(550.0, edge + DVec3::Z * 1e-9);
    assert!((inside.0 - outside.0).abs() < 1e-15 && (inside.1 - outside.1).length() < 1e-12);
}

#[test]
fn gradient_regions_bound_where_the_gradient_is_non_zero() {
    let h = vec![10.0, 20.0, 40.0];
    let profile = IndexField::Profile(Profile::new(h, vec![1.0003, 1.0002, 1.0001], Earth::flat_y()).unwrap());
    let r = profile.gradient_region();
    assert_eq!(r, GradientRegion::Slab { up: DVec3::Y, h_min: 10.0, h_max: 40.0 });
    for y in [0.0, 5.0, 45.0, 100.0] {
        assert_eq!(profile.n_grad(500.0, DVec3::new(0.0, y, 0.0)).1, DVec3::ZERO);
        assert!(!r.contains(DVec3::new(0.0, y, 0.0)));
    }
    // Continuity across the region boundary.
    let below = profile.n(500.0, DVec3::new(0.0, 10.0 - 1e-9, 0.0));
    let above = profile.n(500.0, DVec3::new(0.0, 10.0 + 1e-9, 0.0));
    assert!((below - above).abs() < 1e-12);

    // The exponential field is held at n₀ below the ground: its region is h ≥ 0.
    let exp = IndexField::Exponential(Exponential::new(1.0003, 8000.0, Earth::flat_y()).unwrap());
    assert_eq!(exp.gradient_region(), GradientRegion::Slab { up: DVec3::Y, h_min: 0.0, h_max: f64::INFINITY });
    assert_eq!(exp.n_grad(500.0, DVec3::new(0.0, -3.0, 0.0)).1, DVec3::ZERO);

    let sum = IndexField::Sum(Sum {
        base: Box::new(IndexField::Constant(Constant::Ior(Ior::Constant { n: 1.33 }))),
        bumps: vec![Bump::new(DVec3::new(5.0, 0.0, 0.0), 1.0, 1e-3).unwrap()],
    });
    let r = sum.gradient_region();
    assert_eq!(r, GradientRegion::Shell { centre: DVec3::new(5.0, 0.0, 0.0), r_min: 0.0, r_max: 1.0 });
    assert_eq!(r.entry_distance(DVec3::ZERO, DVec3::X, 100.0), Some(4.0));
    assert!(!sum.is_uniform());
}

#[test]
fn validation_rejects_n_below_one_and_non_positive_n() {
    let domain = Aabb { min: DVec3::splat(-10.0), max: DVec3::splat(10.0) };
    let vis = (380.0, 780.0);
    let lin = IndexField::Linear(Linear::new(1.0, 0.01, DVec3::Y).unwrap());
    let e = lin.validate(&domain, vis, false).unwrap_err();
    assert!(e.contains("below 1") && e.contains("0.9"), "{e}");
    assert!(lin.validate(&domain, vis, true).is_ok());
    let steep = IndexField::Linear(Linear::new(1.0, 0.2, DVec3::Y).unwrap());
    let e = steep.validate(&domain, vis, true).unwrap_err();
    assert!(e.contains("must be positive"), "{e}");
    let air = IndexField::Exponential(Exponential::new(1.0003, 8000.0, Earth::standard()).unwrap());
    assert!(air.validate(&domain, vis, false).is_ok());
    let water = IndexField::Constant(Constant::Ior(Ior::Constant { n: 1.33 }));
    assert!(water.validate(&domain, vis, false).is_ok());
    assert!(IndexField::Constant(Constant::Ior(Ior::Constant { n: f64::NAN })).validate(&domain, vis, true).is_err());
}

// ---------------------------------------------------------------------------------------------
// Atmospheres.

fn atmosphere(earth: Earth, edits: Vec<Edit>, dispersion: AirDispersion) -> IndexField {
    IndexField::Atmosphere(Box::new(
        Atmosphere::new("test", earth, BaseProfile::Usa76, edits, dispersion, 86_000.0).unwrap(),
    ))
}

/// Geometric heights of the USA76 layer bases, where the lapse rate (so ∇n) has a kink.
fn usa76_kinks() -> Vec<f64> {
    [11_000.0, 20_000.0, 32_000.0, 47_000.0, 51_000.0, 71_000.0].iter().map(|h| usa76::geometric_m(*h)).collect()
}

#[test]
fn usa76_atmosphere_gradient_matches_differences_from_the_ground_to_the_top() {
    let ciddor = AirDispersion::ciddor(450.0).unwrap();
    let kinks: Vec<f64> = usa76_kinks().into_iter().chain([85_000.0, 86_000.0]).collect();
    for (name, earth, disp) in [
        ("USA76, flat, Ciddor", Earth::flat_y(), ciddor),
        ("USA76, spherical, Cauchy", Earth::standard(), AirDispersion::CauchyBornWolf),
    ] {
        let f = atmosphere(earth, vec![], disp);
        let check = Check { name, field: &f, step: 1.0 };
        for (l, p) in samples(30, 600, |u| DVec3::new(4e5 * (u[0] - 0.5), 87_000.0 * u[1], 4e5 * (u[2] - 0.5))) {
            let z = earth.height(p);
            if z < 0.0 || kinks.iter().any(|k| (z - k).abs() < 3.0) {
                continue;
            }
            check.at(l, p);
        }
    }
}

type EditCase = (&'static str, Earth, Vec<Edit>, f64, DVec3, DVec3);

#[test]
fn edited_atmospheres_gradient_matches_differences() {
    let d = AirDispersion::ciddor(450.0).unwrap();
    let hot = Edit::HotSurface(HotSurface::new(12.0, 0.5).unwrap());
    let inv = |dt, h, w| Edit::Inversion(Inversion::new(dt, h, w).unwrap());
    let bubble = Edit::Bubble(Bubble::new(DVec3::new(0.0, 5.0, 0.0), 4.0, 5.0).unwrap());
    let lattice = Lattice::from_fn([12, 10, 12], DVec3::new(-3.0, 0.5, -3.0), DVec3::splat(0.5), |p| {
        let r2 = p.x * p.x + (p.y - 2.75).powi(2) + p.z * p.z;
        let s = (1.0 - r2 / 4.0).max(0.0);
        8.0 * s * s * s
    })
    .unwrap();
    // (name, Earth, edits, FD step, half-size and centre of the sampled box)
    let cases: Vec<EditCase> = vec![
        (
            "hot road, flat",
            Earth::flat_y(),
            vec![hot.clone()],
            1e-4,
            DVec3::new(50.0, 1.5, 50.0),
            DVec3::new(0.0, 1.5, 0.0),
        ),
        (
            "hot road, spherical",
            Earth::standard(),
            vec![hot.clone()],
            1e-4,
            DVec3::new(50.0, 1.5, 50.0),
            DVec3::new(0.0, 1.5, 0.0),
        ),
        (
            "inversion",
            Earth::flat_y(),
            vec![inv(10.0, 30.0, 3.0)],
            1e-3,
            DVec3::new(100.0, 30.0, 100.0),
            DVec3::new(0.0, 30.0, 0.0),
        ),
        (
            "fata morgana (two inversions, offset)",
            Earth::standard(),
            vec![Edit::Offset(Offset { dt_k: -10.0 }), inv(8.0, 100.0, 10.0), inv(12.0, 400.0, 20.0)],
            1e-2,
            DVec3::new(1e4, 300.0, 1e4),
            DVec3::new(0.0, 300.0, 0.0),
        ),
        ("bubble", Earth::flat_y(), vec![bubble], 1e-4, DVec3::new(5.0, 5.0, 5.0), DVec3::new(0.0, 5.0, 0.0)),
    ];
    for (seed, (name, earth, edits, step, half, centre)) in cases.into_iter().enumerate() {
        let f = atmosphere(earth, edits, d);
        let check = Check { name, field: &f, step };
        for (l, p) in samples(40 + seed as u64, 400, |u| spread(u, half, centre)) {
            if earth.height(p) < 2.0 * step {
                continue;
            }
            check.at(l, p);
        }
    }
    for (seed, interp) in [Interpolation::Trilinear, Interpolation::Tricubic].into_iter().enumerate() {
        let edit = Edit::Grid(GridEdit::new(lattice.clone(), interp).unwrap());
        let f = atmosphere(Earth::flat_y(), vec![edit], d);
        let check = Check { name: interp.name(), field: &f, step: 1e-5 };
        for (l, p) in
            samples(50 + seed as u64, 400, |u| spread(u, DVec3::new(3.5, 3.0, 3.5), DVec3::new(0.0, 3.0, 0.0)))
        {
            let cell = (p - DVec3::new(-3.0, 0.5, -3.0)) / 0.5;
            let frac = cell - cell.floor();
            if frac.min_element() < 1e-3 || frac.max_element() > 1.0 - 1e-3 {
                continue;
            }
            check.at(l, p);
        }
    }
}

#[test]
fn tabulated_base_atmosphere_gradient_matches_differences() {
    // A tropical-like table (every 1 km, 0–20 km): T falls 6 K/km to a cold tropopause, ln P falls
    // with a 7.5 km scale height.
    let z: Vec<f64> = (0..=20).map(|i| 1000.0 * i as f64).collect();
    let t: Vec<f64> = z.iter().map(|z| 300.0 - 6e-3 * z.min(17_000.0) + 2e-3 * (z - 17_000.0).max(0.0)).collect();
    let p: Vec<f64> = z.iter().map(|z| 101_300.0 * (-z / 7_500.0).exp()).collect();
    let base = BaseProfile::Table(TableProfile::new(z.clone(), t, p).unwrap());
    let a = Atmosphere::new("table", Earth::standard(), base, vec![], AirDispersion::ciddor(400.0).unwrap(), 20_000.0)
        .unwrap();
    let f = IndexField::Atmosphere(Box::new(a));
    let check = Check { name: "table base", field: &f, step: 0.1 };
    for (l, pt) in samples(60, 500, |u| DVec3::new(1e5 * (u[0] - 0.5), 20_500.0 * u[1], 1e5 * (u[2] - 0.5))) {
        let h = Earth::standard().height(pt);
        if z.iter().chain([19_000.0].iter()).any(|k| (h - k).abs() < 1.0) || h < 1.0 {
            continue;
        }
        check.at(l, pt);
    }
}

#[test]
fn bumps_on_a_dispersive_atmosphere_keep_both_gradients_and_regions() {
    let base = atmosphere(
        Earth::standard(),
        vec![Edit::HotSurface(HotSurface::new(10.0, 2.0).unwrap())],
        AirDispersion::CauchyBornWolf,
    );
    let bump = Bump::new(DVec3::new(0.0, 3.0, 0.0), 2.0, 5e-6).unwrap();
    let f = IndexField::Sum(Sum { base: Box::new(base), bumps: vec![bump] });
    let check = Check { name: "atmosphere + bump", field: &f, step: 1e-4 };
    for (l, p) in samples(70, 300, |u| spread(u, DVec3::splat(2.5), DVec3::new(0.0, 3.0, 0.0))) {
        if p.y > 1e-3 {
            check.at(l, p);
        }
    }
    assert!(f.is_dispersive());
    assert!(!f.gradient_region().contains(DVec3::new(0.0, 1e5, 0.0)));
    assert!(f.gradient_region().contains(DVec3::new(0.0, 3.0, 0.0)));
}

#[test]
fn every_field_is_finite_at_extreme_points() {
    // Far away, deep underground, at the Earth's centre, on the ground, exactly at the top:
    // no field may return NaN or Inf (the ODE must never see one).
    let earth = Earth::standard();
    let r = morgana::atmosphere::EARTH_RADIUS_M;
    let points = [
        DVec3::ZERO,
        DVec3::new(0.0, -r, 0.0),
        DVec3::new(0.0, -0.5 * r, 0.0),
        DVec3::new(1e12, 1e12, -1e12),
        DVec3::new(0.0, 86_000.0, 0.0),
        DVec3::new(0.0, -1e4, 0.0),
        DVec3::new(3e6, 0.0, 0.0),
    ];
    let d = AirDispersion::ciddor(450.0).unwrap();
    let fields = [
        IndexField::Exponential(Exponential::new(1.0003, 8000.0, earth).unwrap()),
        IndexField::Profile(Profile::new(vec![0.0, 100.0], vec![1.0003, 1.0002], earth).unwrap()),
        IndexField::TemperatureGrid(Box::new(
            TemperatureGrid::new(plume_lattice(), Interpolation::Tricubic, GridPressure::Usa76 { earth }, d).unwrap(),
        )),
        atmosphere(
            earth,
            vec![
                Edit::HotSurface(HotSurface::new(30.0, 0.01).unwrap()),
                Edit::Inversion(Inversion::new(20.0, 10.0, 1e-3).unwrap()),
                Edit::Bubble(Bubble::new(DVec3::ZERO, 1.0, 5.0).unwrap()),
            ],
            d,
        ),
        IndexField::Atmosphere(Box::new(Atmosphere::builtin("tropical").unwrap())),
    ];
    for (i, f) in fields.iter().enumerate() {
        for p in points {
            for l in [200.0, 550.0, 2000.0] {
                let (n, g) = f.n_grad(l, p);
                assert!(
                    n.is_finite() && g.is_finite() && n >= 1.0 - 1e-15,
                    "field #{i} at {p}, {l} nm: n = {n}, ∇n = {g}"
                );
            }
        }
    }
}

#[test]
fn profiles_and_temperature_grids_load_from_files() {
    use morgana::field::grid_file::{self, Encoding, Quantity};
    let dir = std::env::temp_dir().join(format!("morgana-fields-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    std::fs::write(dir.join("n.csv"), "height_m,n\n0,1.0003\n50,1.00029\n").unwrap();
    let p = Profile::load(&dir.join("n.csv"), Earth::flat_y()).unwrap();
    assert_eq!(p.height_range(), (0.0, 50.0));
    std::fs::write(dir.join("bad.csv"), "height_m,n\n0,1.0003\n50\n").unwrap();
    let e = Profile::load(&dir.join("bad.csv"), Earth::flat_y()).unwrap_err().to_string();
    assert!(e.contains("bad.csv:3") && e.contains("expected 2 numbers"), "{e}");
    let path = dir.join("t.mfield");
    grid_file::write(&path, Quantity::TemperatureK, &plume_lattice(), Encoding::F64Le).unwrap();
    let press = GridPressure::Constant { pressure_pa: 101_325.0 };
    let g = TemperatureGrid::load(&path, Interpolation::Trilinear, press, AirDispersion::CauchyBornWolf).unwrap();
    assert_eq!(g.lattice(), &plume_lattice());
    grid_file::write(&path, Quantity::DeltaTemperatureK, &plume_lattice(), Encoding::F64Le).unwrap();
    let e = TemperatureGrid::load(&path, Interpolation::Trilinear, press, AirDispersion::CauchyBornWolf).unwrap_err();
    assert!(e.to_string().contains("needs quantity temperature_k"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}
