//! The sun: a directional light of finite angular size, seen directly and lighting a plane.

mod common;

use common::{render_with, scene};
use glam::DVec3;
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};

/// A camera looking straight at a sun 30° up, with a field of view of 1.2° (the disc is 0.53°
/// across), over a black floor far below.
fn sun_in_view(method: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.0, 0.5, -0.8660254037844386]
fov_deg = 1.2
width = 48
height = 48

[output]
bands = 1
min_nm = 540.0
max_nm = 560.0

[integrator]
method = "{method}"
photons = 1000
spp = 16

{floor}

[[light]]
type = "sun"
elevation_deg = 30.0
azimuth_deg = 0.0
spectrum = 1.0
scale = 2.0
"#,
        floor = common::black_quad([-1.0, -10.0, -1.0], [0.0, 0.0, 2.0], [2.0, 0.0, 0.0]),
    )
}

/// Σ L·Ω over the pixels: the irradiance normal to the view axis that the image collects.
fn collected_irradiance(toml: &str) -> f64 {
    let s = scene(toml);
    let r = render_with(&s, 2);
    let c = &s.camera;
    let tan_half = (0.5 * c.fov_deg.to_radians()).tan();
    let pixel = 2.0 * tan_half / c.height as f64;
    let mut e = 0.0;
    for y in 0..c.height {
        for x in 0..c.width {
            let sx = (x as f64 + 0.5 - 0.5 * c.width as f64) * pixel;
            let sy = (y as f64 + 0.5 - 0.5 * c.height as f64) * pixel;
            // Solid angle of a pixel of side `pixel` on the image plane at distance 1, times the
            // cosine to the axis: Ω cos θ = pixel² cos⁴θ.
            let cos = 1.0 / (1.0 + sx * sx + sy * sy).sqrt();
            e += r.image.data[y * c.width + x] as f64 * pixel * pixel * cos.powi(4);
        }
    }
    e
}

#[test]
fn the_camera_sees_a_disc_whose_radiance_integrates_to_the_suns_irradiance() {
    // E = ∫_disc L cos θ dω with L = E/(π sin²θ_m): summing the image gives E = 2 W m⁻² nm⁻¹
    // back, up to the disc's edge pixels (16 jittered samples each: ≈ 0.1% over the ~100 edge
    // pixels of a disc covering ~600).
    for method in ["photon_map", "path"] {
        let e = collected_irradiance(&sun_in_view(method));
        assert!((e / 2.0 - 1.0).abs() < 0.01, "{method}: collected {e}, expected 2");
    }
}

#[test]
fn the_disc_is_as_wide_as_the_suns_angular_diameter() {
    // The middle row crosses the disc's diameter: 0.533° of the 1.2° field, so 21.3 of 48 pixels.
    let s = scene(&sun_in_view("path"));
    let r = render_with(&s, 2);
    let row = s.camera.height / 2;
    let lit = (0..s.camera.width).filter(|x| r.image.data[row * s.camera.width + x] > 0.0).count() as f64;
    let expected = morgana::spectrum::solar::ANGULAR_DIAMETER_DEG / 1.2 * s.camera.width as f64;
    assert!((lit - expected).abs() <= 1.5, "{lit} pixels lit, expected {expected:.1}");
}

#[test]
fn sun_photons_carry_its_irradiance_within_its_disc() {
    // A black 2 m plate under a sun at the zenith: 4 m² × E = 8 W arrive, and every photon's
    // direction lies within the disc's 0.2665° radius of straight down.
    let toml = r#"
[camera]
position = [0.0, 3.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 60.0
width = 8
height = 8

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[shape]]
type = "quad"
origin = [-1.0, 0.0, -1.0]
u = [0.0, 0.0, 2.0]
v = [2.0, 0.0, 0.0]
material = "black"

[[light]]
type = "sun"
direction = [0.0, -1.0, 0.0]
spectrum = "D65"
irradiance_w_m2 = 2.0
target_min = [-1.0, -0.01, -1.0]
target_max = [1.0, 0.01, 1.0]
"#;
    let s = scene(toml);
    let (sink, _) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 20_000, 8, &|_| {});
    let stored: f64 = sink.surface.iter().map(|p| p.power_w).sum();
    // Photons tilted off the axis can miss the plate's edge: the share is ~ the edge strip of
    // width h·tan θ over the plate (h ≈ 2.5 m upstream: under 1%).
    assert!((stored / 8.0 - 1.0).abs() < 0.01, "stored {stored} W, expected 8 W");
    let cos_max = (0.5 * morgana::spectrum::solar::ANGULAR_DIAMETER_DEG).to_radians().cos();
    assert!(sink.surface.iter().all(|p| -p.dir.y >= cos_max - 1e-12));
    let tilted = sink.surface.iter().filter(|p| -p.dir.y < 1.0 - 1e-9).count();
    assert!(tilted > sink.surface.len() / 2, "directions should spread over the disc");
    assert!(s.world.lights[0].incident(DVec3::new(0.5, 0.0, 0.2), [0.3, 0.7]).is_some_and(|i| i.wi.y >= cos_max));
}

#[test]
fn a_sun_needs_a_direction_or_both_angles() {
    let bad = sun_in_view("path").replace("azimuth_deg = 0.0\n", "");
    let e = common::scene_error(&bad);
    assert!(e.contains("elevation_deg and azimuth_deg"), "{e}");
}

#[test]
fn a_sun_without_a_spectrum_shines_with_the_extraterrestrial_solar_irradiance() {
    // Over 380–780 nm (the default output range) ASTM G173-03's extraterrestrial column carries
    // 655.9 W m⁻² (the integral its generator recorded).
    let toml = sun_in_view("path")
        .replace("spectrum = 1.0\nscale = 2.0\n", "")
        .replace("[output]\nbands = 1\nmin_nm = 540.0\nmax_nm = 560.0\n", "");
    let s = scene(&toml);
    let e = s.world.lights[0].spectrum().integral();
    let want = morgana::spectrum::solar::ETR_INTEGRAL_380_780_W_M2;
    assert!((e / want - 1.0).abs() < 1e-6, "∫E dλ = {e} W/m², table {want}");
}

/// Neckel & Labs (1994)'s row at `nm` (a tabulated wavelength): A₀…A₅ and their printed
/// mean-to-centre ratio F (`morgana::light::NECKEL_LABS_1994` holds the published table).
fn neckel_labs_row(nm: f64) -> ([f64; 6], f64) {
    let row = morgana::light::NECKEL_LABS_1994.iter().find(|r| r[0] == nm).expect("a tabulated wavelength");
    ([row[1], row[2], row[3], row[4], row[5], row[6]], row[7])
}

/// `sun_in_view` with limb darkening, seen in one 1 nm band centred on `nm`, with a field of
/// `fov_deg` and `pixels` across.
fn limb_darkened_sun(method: &str, nm: f64, fov_deg: f64, pixels: u32) -> String {
    sun_in_view(method)
        .replace("min_nm = 540.0\nmax_nm = 560.0", &format!("min_nm = {}\nmax_nm = {}", nm - 0.5, nm + 0.5))
        .replace(
            "fov_deg = 1.2\nwidth = 48\nheight = 48",
            &format!("fov_deg = {fov_deg}\nwidth = {pixels}\nheight = {pixels}"),
        )
        .replace("scale = 2.0\n", "scale = 2.0\nlimb_darkening = \"neckel_labs_1994\"\n")
}

#[test]
fn a_limb_darkened_disc_still_delivers_the_suns_irradiance() {
    // E = ∫_disc L cos θ dω holds for any law once the centre radiance is E/(π sin²θ_m F):
    // summing the image gives E = 2 W m⁻² nm⁻¹ back, as for the uniform disc (edge pixels:
    // ≈ 0.1%, darker at the limb here, so less).
    for (method, nm) in [("path", 541.76), ("photon_map", 416.319)] {
        let e = collected_irradiance(&limb_darkened_sun(method, nm, 1.2, 48));
        assert!((e / 2.0 - 1.0).abs() < 0.01, "{method} at {nm} nm: collected {e}, expected 2");
    }
}

#[test]
fn the_disc_integral_of_the_limb_darkened_radiance_is_the_irradiance() {
    // ∫ L cos θ dω over the disc, in the variable μ of the solar surface (sin θ = sin θ_m r,
    // r = √(1 − μ²), so cos θ sin θ dθ = sin²θ_m μ dμ): 2π sin²θ_m ∫₀¹ (L/E) μ dμ = 1 to 1e-6,
    // by 64 panels of 16-point Gauss–Legendre over the light's own radiance factor, at a
    // tabulated and an interpolated wavelength.
    for nm in [541.76, 623.0] {
        let s = scene(&limb_darkened_sun("path", nm, 1.2, 8));
        let morgana::light::Light::Directional(sun) = &s.world.lights[0] else { panic!("a sun") };
        let frame = morgana::geometry::Frame::from_normal(sun.dir);
        let factor = |mu: f64| {
            let sin_t = sun.sin_max * (1.0 - mu * mu).max(0.0).sqrt();
            let w = sun.dir * (1.0 - sin_t * sin_t).sqrt() + frame.s * sin_t;
            sun.radiance_factor(-w, nm) * mu
        };
        let total = 2.0
            * std::f64::consts::PI
            * sun.sin_max.powi(2)
            * morgana::quadrature::gauss_legendre(&factor, 0.0, 1.0, 64);
        assert!((total - 1.0).abs() < 1e-6, "{nm} nm: ∫ L cos θ dω / E = {total}");
    }
}

#[test]
fn the_camera_sees_the_published_limb_darkening() {
    // A 0.6° field of 64 pixels around the sun (its disc 28 pixels in radius), in 1 nm bands
    // at two of Neckel & Labs's wavelengths, where their limb is 26% (541.76 nm) and 38%
    // (700.875 nm) of the centre. Expected pixel values: L = E P(μ)/(π sin²θ_m F) with the
    // published row and its printed F, averaged over 16 × 16 points of each pixel; the image's
    // sums over three rings (by pixel centre: r < 0.5, 0.5–0.8, 0.8–1.05 of the disc's radius)
    // must match within 1% (16 jittered samples per pixel; the rings hold 600–1200 pixels).
    let (fov, n) = (0.6f64, 64usize);
    for nm in [541.76, 700.875] {
        let s = scene(&limb_darkened_sun("path", nm, fov, n as u32));
        let r = render_with(&s, 2);
        let (a, f) = neckel_labs_row(nm);
        let sin_m = (0.5 * morgana::spectrum::solar::ANGULAR_DIAMETER_DEG).to_radians().sin();
        let radiance = |sx: f64, sy: f64| {
            // A pixel offset (sx, sy) on the image plane at distance 1: sin θ = ρ/√(1 + ρ²).
            let rho2 = sx * sx + sy * sy;
            let rr = (rho2 / (1.0 + rho2)).sqrt() / sin_m;
            if rr > 1.0 {
                return 0.0;
            }
            let mu = (1.0 - rr * rr).sqrt();
            let p: f64 = a.iter().rev().fold(0.0, |acc, c| acc * mu + c);
            2.0 * p / (std::f64::consts::PI * sin_m * sin_m * f)
        };
        let pixel = 2.0 * (0.5 * fov.to_radians()).tan() / n as f64;
        let disc_px = sin_m / pixel;
        let (mut got, mut want) = ([0.0; 3], [0.0; 3]);
        for y in 0..n {
            for x in 0..n {
                let (cx, cy) = (x as f64 + 0.5 - 0.5 * n as f64, y as f64 + 0.5 - 0.5 * n as f64);
                let ring = match (cx * cx + cy * cy).sqrt() / disc_px {
                    q if q < 0.5 => 0,
                    q if q < 0.8 => 1,
                    q if q < 1.05 => 2,
                    _ => continue,
                };
                got[ring] += r.image.data[y * n + x] as f64;
                let mut sum = 0.0;
                for j in 0..16 {
                    for i in 0..16 {
                        let sx = (cx - 0.5 + (i as f64 + 0.5) / 16.0) * pixel;
                        let sy = (cy - 0.5 + (j as f64 + 0.5) / 16.0) * pixel;
                        sum += radiance(sx, sy);
                    }
                }
                want[ring] += sum / 256.0;
            }
        }
        for k in 0..3 {
            assert!(
                (got[k] / want[k] - 1.0).abs() < 0.01,
                "{nm} nm, ring {k}: image {} against the law {}",
                got[k],
                want[k]
            );
        }
        // The limb is darker relative to the centre in green than in the red.
        eprintln!("{nm} nm: ring sums {got:?}, law {want:?}");
    }
}

#[test]
fn limb_darkened_photons_leave_the_disc_as_the_published_law() {
    // Photon directions about the sun's axis: the fractional radius r = sin θ/sin θ_m has the
    // density 2r P(μ(r))/F on [0, 1] (Neckel & Labs's row at 541.76 nm and its printed F; a
    // 1 nm band around it). Chi-square over 40 bins, 100 000 photons.
    let s = scene(&limb_darkened_sun("path", 541.76, 1.2, 8));
    let light = &s.world.lights[0];
    let morgana::light::Light::Directional(sun) = light else { panic!("a sun") };
    let (a, f) = neckel_labs_row(541.76);
    let mut rng = morgana::rng::Rng::for_task(5, morgana::rng::Stream::Test, 0);
    let p = morgana::testing::chi2::chi2_1d(
        (0.0, 1.0),
        40,
        100_000,
        || Some(light.emit(&mut rng).dir.cross(sun.dir).length() / sun.sin_max),
        |r| {
            let mu = (1.0 - r * r).max(0.0).sqrt();
            2.0 * r * a.iter().rev().fold(0.0, |acc, c| acc * mu + c) / f
        },
    );
    assert!(p > 1e-3, "p = {p}");
}

#[test]
fn limb_darkening_needs_a_disc_and_a_tabulated_range() {
    let point = limb_darkened_sun("path", 541.76, 1.2, 8)
        .replace("spectrum = 1.0\n", "spectrum = 1.0\nangular_diameter_deg = 0.0\n");
    let e = common::scene_error(&point);
    assert!(e.contains("limb_darkening needs a disc") && e.contains("test.toml:"), "{e}");
    let uv = limb_darkened_sun("path", 541.76, 1.2, 8).replace("min_nm = 541.26", "min_nm = 290.0");
    let e = common::scene_error(&uv);
    assert!(e.contains("303.327–1098.95 nm") && e.contains("min_nm"), "{e}");
    let unknown = limb_darkened_sun("path", 541.76, 1.2, 8).replace("neckel_labs_1994", "pierce");
    assert!(common::scene_error(&unknown).contains("allowed: none, neckel_labs_1994"));
}
