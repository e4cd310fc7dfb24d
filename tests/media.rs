//! Participating media against closed forms, conservation and each other.

mod common;

use common::{render_with, scene};
use glam::DVec3;
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::quadrature::gauss_legendre;
use std::f64::consts::PI;

const LE: f64 = 2.0;
const RHO: f64 = 0.5;

/// A sphere of radius 1 whose wall emits L_e inward and reflects with albedo ρ, filled with a
/// non-absorbing medium of σ_t = 1 m⁻¹: radiance is L_e/(1 − ρ) everywhere and in every
/// direction, since scattering without absorption preserves a uniform isotropic field.
fn volumetric_furnace(integrator: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.2, 0.1, -1.0]
fov_deg = 80.0
width = 16
height = 16

[output]
bands = 2
min_nm = 450.0
max_nm = 650.0

[integrator]
{integrator}

[world]
medium = "fog"

[[medium]]
name = "fog"
sigma_t = 1.0
albedo = 1.0

[[material]]
name = "wall"
type = "lambertian"
reflectance = {RHO}

[[light]]
type = "area"
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
side = "back"
material = "wall"
spectrum = 1.0
scale = {LE}
"#
    )
}

fn image_mean(values: &[f32]) -> f64 {
    values.iter().map(|v| *v as f64).sum::<f64>() / values.len() as f64
}

#[test]
fn volumetric_furnace_from_the_photon_maps_alone() {
    let s = scene(&volumetric_furnace(
        "photons = 400000\nk = 100\nvolume_k = 60\nmax_radius = 0.5\nvolume_max_radius = 0.5\nmarch_step = 0.05\ndirect = \"photon_map\"\nspp = 1\nseed = 3",
    ));
    assert!(s.plan.volume_map.on && s.camera_medium.is_some());
    let r = render_with(&s, 2);
    let expected = LE / (1.0 - RHO);
    let mean = image_mean(&r.image.data);
    // Photons bounce many times, so the photon pass's noise dominates the image mean: over
    // seeds 1–6 at 400k photons it scatters with a standard deviation of 0.9% (both direct
    // modes), around +0.7% from density-estimation bias. 3% is about 3σ beyond that bias.
    assert!((mean / expected - 1.0).abs() < 0.03, "mean {mean}, expected {expected}");
}

#[test]
fn volumetric_furnace_with_shadow_rays_and_final_gathering() {
    let s = scene(&volumetric_furnace(
        "photons = 400000\nk = 100\nvolume_k = 60\nmax_radius = 0.5\nvolume_max_radius = 0.5\nmarch_step = 0.05\ngather_rays = 8\nspp = 1\nseed = 4",
    ));
    assert!(s.plan.shadow_rays.on && s.plan.final_gather.on);
    let r = render_with(&s, 2);
    let expected = LE / (1.0 - RHO);
    let mean = image_mean(&r.image.data);
    assert!((mean / expected - 1.0).abs() < 0.03, "mean {mean}, expected {expected}");
}

#[test]
fn absorbing_sphere_takes_the_closed_form_share_of_the_power() {
    // A point light at the centre of a black sphere of radius 1 filled with a purely absorbing
    // medium σ_a = 0.7 m⁻¹: the medium absorbs Φ(1 − e^{−0.7}), the wall the rest.
    let toml = &format!(
        r#"
[camera]
position = [0.0, 0.0, 0.5]
look_at = [0.0, 0.0, 0.0]
fov_deg = 40.0
width = 4
height = 4

[world]
medium = "ink"

[[medium]]
name = "ink"
sigma_a = 0.7
sigma_s = 0.0
{black}
[[light]]
type = "point"
position = [0.0, 0.0, 0.0]
spectrum = 1.0
power_w = 10.0
"#,
        black = common::black_sphere(1.0)
    );
    let s = scene(toml);
    let n = 200_000u64;
    let (_, st) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, n, 7, &|_| {});
    let total = st.absorbed_medium_w + st.absorbed_surface_w + st.escaped_w + st.truncated_w;
    assert!((total - 10.0).abs() < 1e-9, "power not conserved: {total}");
    let p = 1.0 - (-0.7f64).exp();
    let se = 10.0 * (p * (1.0 - p) / n as f64).sqrt();
    assert!(
        (st.absorbed_medium_w - 10.0 * p).abs() < 4.0 * se,
        "medium absorbed {} W, expected {}",
        st.absorbed_medium_w,
        10.0 * p
    );
}

/// Single scattering of a point light (intensity I) in a box of homogeneous medium seen by a
/// camera outside it, by quadrature of the closed-form integrand
/// L = ∫ e^{−σ_t (t − t_a)} σ_s f(cos θ) I e^{−σ_t s(t)} / |q − x(t)|² dt, with s(t) the length of
/// the segment from x(t) toward the light that lies inside the box and θ the angle between the
/// light's travel direction and the direction toward the camera.
fn single_scattering_in_a_slab(phase_toml: &str, phase: &dyn Fn(f64) -> f64) {
    single_scattering_in_a_slab_with(phase_toml, "", &|_| 1.0, phase, 400);
}

/// As above, with the medium's density `density_toml` (d(x) given by `density`, which must be
/// linear along any segment, so a segment's optical depth is its length times d at its middle).
fn single_scattering_in_a_slab_with(
    phase_toml: &str,
    density_toml: &str,
    density: &dyn Fn(DVec3) -> f64,
    phase: &dyn Fn(f64) -> f64,
    spp: usize,
) {
    let (sigma_s, sigma_t, intensity) = (0.3, 0.5, 2.0);
    let toml = format!(
        r#"
[camera]
position = [0.0, 0.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 0.01
width = 1
height = 1

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0

[integrator]
photons = 0
march_step = 0.01
spp = {spp}

[[medium]]
name = "slab"
sigma_a = {sa}
sigma_s = {sigma_s}
phase = {phase_toml}
{density_toml}

[[shape]]
type = "box"
min = [-1.0, -1.0, -0.5]
max = [1.0, 1.0, 0.5]
interior = "slab"
exterior = "vacuum"

[[light]]
type = "point"
position = [1.5, 0.5, 0.2]
spectrum = 1.0
scale = {scale}
"#,
        sa = sigma_t - sigma_s,
        scale = intensity / 100.0,
        spp = spp,
    );
    let s = scene(&toml);
    assert!(s.plan.participating_media.on && !s.plan.volume_map.on);
    let r = render_with(&s, 1);
    let rendered = r.image.data[0] as f64 * 100.0;
    let q = DVec3::new(1.5, 0.5, 0.2);
    // Distance inside the box from x toward the light (which lies beyond the face x = 1).
    let inside = |x: DVec3| {
        let d = (q - x).normalize();
        [
            (1.0 - x.x) / d.x,
            if d.y > 0.0 { (1.0 - x.y) / d.y } else { f64::INFINITY },
            if d.z > 0.0 { (0.5 - x.z) / d.z } else { (-0.5 - x.z) / d.z },
        ]
        .into_iter()
        .fold(f64::INFINITY, f64::min)
    };
    let integrand = |z: f64| {
        let x = DVec3::new(0.0, 0.0, z);
        let to_light = q - x;
        let cos = (-to_light.normalize()).dot(DVec3::Z);
        let s_in = inside(x);
        let depth_light = s_in * density(x + 0.5 * s_in * to_light.normalize());
        let depth_eye = (0.5 - z) * density(DVec3::new(0.0, 0.0, 0.5 * (0.5 + z)));
        (-sigma_t * depth_eye).exp() * sigma_s * density(x) * phase(cos) * intensity * (-sigma_t * depth_light).exp()
            / to_light.length_squared()
    };
    let expected = gauss_legendre(&integrand, -0.5, 0.5, 16);
    assert!((rendered / expected - 1.0).abs() < 0.01, "{phase_toml}: rendered {rendered}, quadrature {expected}");
}

#[test]
fn single_scattering_in_a_slab_matches_quadrature() {
    single_scattering_in_a_slab("\"isotropic\"", &|_| 1.0 / (4.0 * PI));
    let g: f64 = 0.6;
    let hg = move |c: f64| (1.0 - g * g) / (4.0 * PI * (1.0 + g * g - 2.0 * g * c).powf(1.5));
    single_scattering_in_a_slab("{ type = \"hg\", g = 0.6 }", &hg);
    single_scattering_in_a_slab("\"rayleigh\"", &|c| 3.0 / (16.0 * PI) * (1.0 + c * c));
}

/// A heterogeneous slab from a density grid file (written with the library's grid writer):
/// d = 0.5 + 0.25 x, which trilinear interpolation reproduces exactly; transmittance by ratio
/// tracking over macro-cell majorants.
#[test]
fn single_scattering_in_a_grid_density_matches_quadrature() {
    let dir = std::env::temp_dir().join(format!("morgana-grid-slab-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let file = dir.join("ramp.mgrid");
    let d = |p: DVec3| 0.5 + 0.25 * p.x;
    morgana::media::density::write_grid_atomically(
        &file,
        [33, 9, 9],
        DVec3::new(-1.0, -1.0, -0.5),
        DVec3::new(1.0, 1.0, 0.5),
        d,
    )
    .unwrap();
    let toml = format!("density = {{ type = \"grid\", file = \"{}\" }}", file.display());
    // Ratio tracking makes each shadow ray's transmittance a random estimate, hence more samples.
    single_scattering_in_a_slab_with("\"isotropic\"", &toml, &d, &|_| 1.0 / (4.0 * PI), 4000);
    let _ = std::fs::remove_dir_all(&dir);
}

/// The same fog box rendered with direct light from the photon map (Lucifer) and from shadow
/// rays (JC98) agrees within the statistical error of the comparison.
#[test]
fn direct_light_from_the_map_and_from_shadow_rays_agree() {
    let base = std::fs::read_to_string("examples/fog_box.toml").expect("examples/fog_box.toml");
    let small = |direct: &str| {
        base.replace("width = 128", "width = 24")
            .replace("height = 128", "height = 24")
            .replace("photons = 400000", &format!("photons = 300000\ndirect = \"{direct}\""))
            .replace("spp = 8", "spp = 2")
            .replace("gather_rays = 16\n", "")
    };
    let pm = scene(&small("photon_map"));
    let sr = scene(
        &small("shadow_rays").replace("direct = \"shadow_rays\"", "direct = \"shadow_rays\"\nfinal_gather = false"),
    );
    let (a, b) = (render_with(&pm, 2), render_with(&sr, 2));
    let (ma, mb) = (image_mean(&a.image.data), image_mean(&b.image.data));
    assert!((ma / mb - 1.0).abs() < 0.03, "photon map {ma}, shadow rays {mb}");
}

#[test]
fn media_renders_are_identical_for_any_thread_count() {
    let base = std::fs::read_to_string("examples/fog_box.toml").expect("examples/fog_box.toml");
    let toml = base
        .replace("width = 128", "width = 12")
        .replace("height = 128", "height = 10")
        .replace("photons = 400000", "photons = 20000")
        .replace("spp = 8", "spp = 1");
    let s = scene(&toml);
    let (a, b) = (render_with(&s, 1), render_with(&s, 2));
    assert!(a.image.data.iter().zip(&b.image.data).all(|(x, y)| x.to_bits() == y.to_bits()));
}

/// A volume caustic comes out of the volume photon map: below a glass sphere (n = 1.5,
/// R = 0.3 m) lit by a spotlight in fog, the in-scattered light at the paraxial focus
/// f = nR/(2(n − 1)) = 0.45 m below the centre far exceeds the unfocused beam there (the same
/// scene without the sphere) and the sphere's shadow beside the focus.
#[test]
fn a_glass_sphere_focuses_a_volume_caustic_into_fog() {
    use morgana::photon_map::{Estimator, Neighbours, Paths, PhotonMap};
    let base = std::fs::read_to_string("examples/volume_caustic.toml").expect("examples/volume_caustic.toml");
    let with = scene(&base.replace("photons = 1000000", "photons = 300000"));
    let without = scene(
        &base
            .replace("photons = 1000000", "photons = 300000")
            .replace("material = \"glass\"\n", "material = \"white\"\n")
            .replace("radius = 0.3", "radius = 0.0001"),
    );
    let inscatter = |s: &morgana::scene::Scene, p: DVec3| {
        let (sink, _) = shoot(&s.world, &PassSettings::of(s), MapKind::Global, s.integrator.photons, 1, &|_| {});
        let map = PhotonMap::build(&sink.volume);
        let est = Estimator {
            map: &map,
            k: 200,
            max_radius: 0.1,
            filter: s.integrator.filter,
            bands: s.bands,
            paths: Paths::All,
            scatter_rows: None,
            disc_share: None,
        };
        let (v, _) = est.volume_scattered(p, DVec3::Z, (0, &s.world.media[0]), &mut Neighbours::default());
        v.iter().take(s.bands.count).sum::<f64>()
    };
    let focus = DVec3::new(0.0, -0.45, 0.0);
    let (at_focus, beside, unfocused) =
        (inscatter(&with, focus), inscatter(&with, DVec3::new(0.2, -0.45, 0.0)), inscatter(&without, focus));
    assert!(at_focus > 4.0 * unfocused, "focus {at_focus} vs the unfocused beam {unfocused}");
    assert!(at_focus > 4.0 * beside, "focus {at_focus} vs beside it {beside}");
}
