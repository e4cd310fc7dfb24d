//! The beam radiance estimate of the volume map (issue 17 item 6; Jarosz, Zwicker & Jensen 2008)
//! and photon beams (Jarosz et al. 2011) against closed forms, the point estimate, and
//! degenerate chords; the estimates where a chord ends on a wall.

mod common;

use common::{emitting_box_walls, mean_and_sem, render_with, scene, scene_error};
use glam::DVec3;
use morgana::photon::{MapKind, PassSettings, shoot};
use morgana::photon_map::progressive::{DEFAULT_ALPHA, measure_ratio};
use morgana::photon_map::{
    BeamEstimator, BeamMap, ChordEstimate, Paths, PhotonBeamMap, PhotonMap, PhotonPath, SegmentEnds, TubeEstimator,
    tube_radii,
};
use morgana::scene::VolumeEstimate;
use std::f64::consts::PI;

const SIGMA_S: f64 = 0.3;
const SIGMA_T: f64 = 0.5;
/// Spectral irradiance of the collimated beam, W m⁻² nm⁻¹.
const E: f64 = 2.0;

/// A 4 m × 4 m × 1 m slab (z from −0.5 to 0.5) of isotropic medium (σ_s = 0.3, σ_t = 0.5 m⁻¹)
/// under a collimated beam travelling straight down with E = 2 W m⁻² nm⁻¹, limited to the slab,
/// read by the beam estimate.
fn collimated_slab() -> String {
    collimated_slab_read_by("beam")
}

/// [`collimated_slab`] with the volume map read by `estimate`.
fn collimated_slab_read_by(estimate: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 3.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 10.0
width = 1
height = 1

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0

[integrator]
direct = "photon_map"
volume_estimate = "{estimate}"

[[medium]]
name = "slab"
sigma_a = {sa}
sigma_s = {SIGMA_S}
phase = "isotropic"

[[shape]]
type = "box"
min = [-2.0, -2.0, -0.5]
max = [2.0, 2.0, 0.5]
interior = "slab"
exterior = "vacuum"

[[light]]
type = "directional"
direction = [0.0, 0.0, -1.0]
target_min = [-2.0, -2.0, -0.5]
target_max = [2.0, 2.0, 0.5]
spectrum = 1.0
scale = {E}
"#,
        sa = SIGMA_T - SIGMA_S,
    )
}

/// Single scattering of the collimated beam seen along the chord from (−1, 0, 0) to (1, 0, 0)
/// (light travelling back along it, −x): at depth 0.5 m the beam's irradiance is E e^{−σ_t/2},
/// isotropic scattering sends σ_s/(4π) of it per unit length toward the eye, and the chord
/// attenuates it by e^{−σ_t t}:
/// L = σ_s E e^{−σ_t/2} (1 − e^{−2σ_t}) / (4π σ_t).
fn single_scattering_closed_form() -> f64 {
    SIGMA_S * E * (-SIGMA_T * 0.5).exp() * (1.0 - (-2.0 * SIGMA_T).exp()) / (4.0 * PI * SIGMA_T)
}

/// The beam estimate of pass `pass` (fresh photons from seed `pass + 1`; discs of the 50 nearest,
/// at most 0.2 m, shrunk by √sᵢ), from the photons at their first interaction only: those
/// are the single-scattering sources (later ones carry multiple scattering, which has no
/// closed form here).
fn beam_pass(s: &morgana::scene::Scene, pass: u32) -> f64 {
    let (sink, _) = shoot(&s.world, &PassSettings::of(s), MapKind::Global, 200_000, u64::from(pass) + 1, &|_| {});
    let first: Vec<_> = sink.volume.into_iter().filter(|p| p.path == PhotonPath::Direct).collect();
    let map = PhotonMap::build(&first);
    let discs = BeamMap::build(&map, 50, 0.2, measure_ratio(pass, DEFAULT_ALPHA).sqrt());
    let est = BeamEstimator { map: &map, discs: &discs, bands: s.bands, paths: Paths::All, scatter_rows: None };
    let medium = &s.world.media[0];
    let (mut hits, mut tmp) = (Vec::new(), [0.0; morgana::spectrum::MAX_BANDS]);
    est.gather(DVec3::new(-1.0, 0.0, 0.0), DVec3::X, 2.0, SegmentEnds::default(), &mut hits);
    let mut l = 0.0;
    for h in &hits {
        est.photon(h, DVec3::NEG_X, (0, medium), &mut tmp, &mut |_, v| l += (-SIGMA_T * h.t).exp() * v);
    }
    l
}

/// Progressive passes of the beam estimate converge to the closed form of single scattering in
/// a collimated beam: the mean of 16 passes lies within 3 standard errors (from the passes'
/// spread) of it, and that error is small enough to mean something (< 3 %).
#[test]
fn beam_estimate_of_a_collimated_beam_converges_to_the_closed_form() {
    let s = scene(&collimated_slab());
    let passes: Vec<f64> = (0..16).map(|i| beam_pass(&s, i)).collect();
    let (mean, se) = mean_and_sem(&passes);
    let want = single_scattering_closed_form();
    eprintln!("beam: {mean} ± {se}, closed form {want}");
    assert!(se < 0.03 * want, "standard error {se} of {want}");
    assert!((mean - want).abs() < 3.0 * se, "beam {mean} ± {se}, closed form {want}");
}

/// The photon-beam estimate of pass `pass` (fresh photons from seed `pass + 1`): the flights of
/// the photons straight from the light (the single-scattering sources), their tubes from the 50
/// nearest of the photons at first interactions ([`tube_radii`], at most 0.2 m) shrunk by sᵢ.
fn photon_beam_pass(s: &morgana::scene::Scene, pass: u32) -> f64 {
    let (sink, _) = shoot(&s.world, &PassSettings::of(s), MapKind::Global, 200_000, u64::from(pass) + 1, &|_| {});
    let first: Vec<_> = sink.volume.into_iter().filter(|p| p.path == PhotonPath::Direct).collect();
    let beams: Vec<_> = sink.beams.into_iter().filter(|b| b.path == PhotonPath::Direct).collect();
    let total: f64 = beams.iter().map(|b| b.length).sum();
    let radii = tube_radii(&PhotonMap::build(&first), &beams, total, 50, 0.2, measure_ratio(pass, DEFAULT_ALPHA));
    let map = PhotonBeamMap::new(beams, radii);
    let est = TubeEstimator { beams: &map, bands: s.bands, paths: Paths::All };
    let medium = &s.world.media[0];
    let (mut hits, mut tmp) = (Vec::new(), [0.0; morgana::spectrum::MAX_BANDS]);
    let (o, d) = (DVec3::new(-1.0, 0.0, 0.0), DVec3::X);
    est.gather(o, d, 2.0, SegmentEnds::default(), &mut hits);
    let mut l = 0.0;
    for h in &hits {
        est.radiance(h, o + h.t * d, -d, (0, medium), &mut tmp, &mut |_, v| l += (-SIGMA_T * h.t).exp() * v);
    }
    l
}

/// Progressive passes of photon beams converge to the closed form of single scattering in a
/// collimated beam: the mean of 16 passes lies within 3 standard errors of it, and that error
/// is below 3 %.
#[test]
fn photon_beams_of_a_collimated_beam_converge_to_the_closed_form() {
    let s = scene(&collimated_slab_read_by("photon_beams"));
    let passes: Vec<f64> = (0..16).map(|i| photon_beam_pass(&s, i)).collect();
    let (mean, se) = mean_and_sem(&passes);
    let want = single_scattering_closed_form();
    eprintln!("photon beams: {mean} ± {se}, closed form {want}");
    assert!(se < 0.03 * want, "standard error {se} of {want}");
    assert!((mean - want).abs() < 3.0 * se, "photon beams {mean} ± {se}, closed form {want}");
}

/// A sphere of radius 1 whose wall emits L_e = 2 inward and reflects with ρ = 0.5, filled with
/// a non-absorbing medium (σ_t = 1 m⁻¹): radiance is L_e/(1 − ρ) = 4 everywhere (as in
/// tests/media.rs), here with every order of scattering from `estimate` ("beam" or
/// "photon_beams").
fn beam_furnace(seed: u64, estimate: &str) -> String {
    format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.2, 0.1, -1.0]
fov_deg = 80.0
width = 8
height = 8

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0

[integrator]
photons = 20000
volume_k = 50
direct = "photon_map"
volume_estimate = "{estimate}"
spp = 1
seed = {seed}

{fog}

[[light]]
type = "area"
shape = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
side = "back"
material = "wall"
spectrum = 1.0
scale = 2.0
"#,
        fog = fog_and_walls(1.0)
    )
}

/// The furnaces' world: a non-absorbing fog of extinction `sigma_t` (m⁻¹) filling it, and the
/// walls' material (Lambertian, ρ = 0.5).
fn fog_and_walls(sigma_t: f64) -> String {
    format!(
        "[world]\nmedium = \"fog\"\n\n[[medium]]\nname = \"fog\"\nsigma_t = {sigma_t:?}\nalbedo = 1.0\n\n\
         [[material]]\nname = \"wall\"\ntype = \"lambertian\"\nreflectance = 0.5\n"
    )
}

fn image_mean(values: &[f32]) -> f64 {
    values.iter().map(|v| f64::from(*v)).sum::<f64>() / values.len() as f64
}

/// The volumetric furnace read by the beam estimate (direct light from the maps, shadow rays
/// off): the image means of 12 independent renders lie within 3 standard errors of 4.
#[test]
fn volumetric_furnace_from_the_beam_estimate() {
    volumetric_furnace("beam");
}

/// The same furnace read by photon beams.
#[test]
fn volumetric_furnace_from_photon_beams() {
    volumetric_furnace("photon_beams");
}

/// The sphere furnace read by `estimate`: the image means of 12 independent renders lie within
/// 3 standard errors of 4, which are below 1 %.
fn volumetric_furnace(estimate: &str) {
    let means: Vec<f64> =
        (1..=12).map(|seed| image_mean(&render_with(&scene(&beam_furnace(seed, estimate)), 2).image.data)).collect();
    let (mean, se) = mean_and_sem(&means);
    eprintln!("{estimate} furnace: {mean} ± {se}");
    assert!(se < 0.01 * 4.0, "standard error {se}");
    assert!((mean - 4.0).abs() < 3.0 * se, "{estimate} furnace {mean} ± {se}, exact 4");
}

/// The box [−1, 1]³ of tests/furnace.rs (walls emitting L_e = 2, reflecting ρ = 0.5 on both
/// sides) filled with a non-absorbing fog (σ_t = 0.5 m⁻¹): radiance is L_e/(1 − ρ) = 4
/// everywhere. The camera at the centre looks into a corner, so its rays meet the walls at
/// 0–70°; the fog's light comes from `estimate` ("beam" or "point") over the 400 nearest
/// photons (large discs or balls), the walls' from the global map. Returns the image mean over
/// 4 (one band, 32 × 32).
fn fog_box_furnace(estimate: &str, seed: u64, edge_correction: bool) -> f64 {
    let toml = format!(
        r#"
[camera]
position = [0.0, 0.0, 0.0]
look_at = [0.577, 0.577, -0.577]
fov_deg = 100.0
width = 32
height = 32

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0

[integrator]
photons = 20000
volume_k = 400
volume_max_radius = 0.6
direct = "photon_map"
final_gather = false
volume_estimate = "{estimate}"
edge_correction = {edge_correction}
spp = 1
seed = {seed}

{fog}
{walls}"#,
        fog = fog_and_walls(0.5),
        walls = emitting_box_walls(2.0)
    );
    image_mean(&render_with(&scene(&toml), 2).image.data) / 4.0
}

/// Where a chord meets a wall obliquely, the tube of discs cut across the chord misses the fog
/// in front of the wall beyond the chord's end (see `BeamMap::query`): the fog box furnace
/// reads dark without the wall's plane as the tube's end. With it, the image means of 24 seeds
/// lie within 3 standard errors of L_e/(1 − ρ); without it, the same seeds read darker by more
/// than 5 standard errors of the difference.
#[test]
fn chords_ending_on_walls_read_the_fog_in_front_of_them() {
    walls_lighten_the_fog_box_furnace("beam", 24);
}

/// The check of the tests above and below: over `seeds` seeds, the fog box furnace read by
/// `estimate` with `edge_correction` has its image mean within 3 standard errors of
/// L_e/(1 − ρ), and without it the same seeds read darker by more than 5 standard errors of
/// the paired difference.
fn walls_lighten_the_fog_box_furnace(estimate: &str, seeds: u64) {
    let (with, without): (Vec<f64>, Vec<f64>) =
        (1..=seeds).map(|seed| (fog_box_furnace(estimate, seed, true), fog_box_furnace(estimate, seed, false))).unzip();
    let diff: Vec<f64> = with.iter().zip(&without).map(|(a, b)| a - b).collect();
    let ((with, se), (without, _), (gain, se_gain)) =
        (mean_and_sem(&with), mean_and_sem(&without), mean_and_sem(&diff));
    eprintln!(
        "{estimate} estimate, fog box furnace over L_e/(1 − ρ): with the walls {with:.4} ± {se:.4}, without {without:.4}, difference {gain:.4} ± {se_gain:.4}"
    );
    assert!((with - 1.0).abs() < 3.0 * se, "{estimate}: with the walls {with} ± {se}");
    assert!(gain > 5.0 * se_gain, "{estimate}: without them darker by {gain} ± {se_gain}");
}

/// Photon beams end where their photons' flights end, on the walls, so the fog box furnace read
/// by them needs no planes at the chords' ends: the image means of 12 seeds lie within 3
/// standard errors of L_e/(1 − ρ).
#[test]
fn photon_beams_read_the_fog_box_furnace() {
    let means: Vec<f64> = (1..=12).map(|seed| fog_box_furnace("photon_beams", seed, true)).collect();
    let (mean, se) = mean_and_sem(&means);
    eprintln!("photon beams, fog box furnace over L_e/(1 − ρ): {mean:.4} ± {se:.4}");
    assert!(se < 0.01, "standard error {se}");
    assert!((mean - 1.0).abs() < 3.0 * se, "photon beams {mean} ± {se}");
}

/// The point estimate's ball about a march step within its radius of the wall the chord ends
/// on reaches behind it, where no photon is: the same furnace read by the point estimate
/// (`volume_estimate = "point"`, the 400 nearest photons) reads dark without the walls, and
/// within 3 standard errors of L_e/(1 − ρ) with them (photons behind a wall left out, the ball's
/// volume scaled by the share in front of it).
#[test]
fn a_point_estimate_beside_a_wall_reads_the_ball_in_front_of_it() {
    walls_lighten_the_fog_box_furnace("point", 12);
}

/// The point estimate against the density of a uniform field of photons filling z < 1 (10⁶ in a
/// unit cube; the slab's isotropic medium): at 400 points within the ball's radius of the face
/// z = 1, with that face as a [`Wall`] the estimate is the field's within 1 %; without it,
/// 1 − h²(3r − h)/(4r³) of it on average (h = r − d, the cap behind the face), within 1.5 %.
#[test]
fn a_ball_cut_by_a_wall_is_measured_in_front_of_it() {
    use morgana::photon_map::{Estimator, Neighbours, PhotonRecord, Wall, Walls};
    use morgana::rng::{Rng, Stream};
    let s = scene(&collimated_slab());
    let mut rng = Rng::for_task(21, Stream::Test, 0);
    let n = 1_000_000;
    let records: Vec<PhotonRecord> = (0..n)
        .map(|_| PhotonRecord {
            position: DVec3::new(rng.uniform(), rng.uniform(), rng.uniform()),
            dir: DVec3::Z,
            normal: DVec3::ZERO,
            wavelength_nm: 550.0,
            power_w: 1.0,
            path: PhotonPath::Diffuse,
        })
        .collect();
    let map = PhotonMap::build(&records);
    let est = Estimator {
        map: &map,
        k: 400,
        max_radius: 0.3,
        filter: s.integrator.filter,
        bands: s.bands,
        paths: Paths::All,
        scatter_rows: None,
        disc_share: None,
    };
    // Σ α f ΔΦ / (V Δλ) for density n m⁻³ of 1 W photons, α = σ_s/σ_t (the slab's medium),
    // f = 1/(4π).
    let exact = n as f64 * (SIGMA_S / SIGMA_T) / (4.0 * PI * s.bands.width_nm());
    let wall = Walls { ends: [None, Some(Wall { point: DVec3::new(0.0, 0.0, 1.0), normal: DVec3::NEG_Z })] };
    let medium = (0u32, &s.world.media[0]);
    let (mut with, mut without, mut cut) = (0.0, 0.0, 0.0);
    let mut nb = Neighbours::default();
    let points = 400;
    for i in 0..points {
        let d = 0.04 * (i as f64 + 0.5) / points as f64;
        let x = DVec3::new(0.3 + 0.4 * rng.uniform(), 0.3 + 0.4 * rng.uniform(), 1.0 - d);
        let (v, r) = est.volume_scattered_within(x, DVec3::X, medium, &wall, &mut nb);
        with += v[0] / exact;
        without += est.volume_scattered(x, DVec3::X, medium, &mut nb).0[0] / exact;
        cut += 1.0 - wall.iter().map(|w| w.cap_fraction(x, r)).sum::<f64>();
    }
    let (with, without, cut) = (with / points as f64, without / points as f64, cut / points as f64);
    eprintln!("ball at a wall: with it {with:.4}, without {without:.4} (1 − cap: {cut:.4})");
    assert!((with - 1.0).abs() < 0.01, "with the wall: {with}");
    assert!((without / cut - 1.0).abs() < 0.015, "without it: {without}, expected {cut}");
    assert!(cut < 0.8, "the points must lie where the wall cuts the ball: 1 − cap {cut}");
}

/// The fog box (examples/fog_box.toml, small) with `volume_estimate`: the point and beam
/// estimates read the same maps in the same scene, so their images agree within noise: the
/// image means of 6 seeds each differ by less than 3 standard errors of the difference.
#[test]
fn beam_and_point_estimates_agree_on_the_fog_box() {
    let base = std::fs::read_to_string("examples/fog_box.toml").expect("examples/fog_box.toml");
    let small = |estimate: &str, seed: u64| {
        base.replace("width = 128", "width = 16")
            .replace("height = 128", "height = 16")
            .replace("photons = 400000", &format!("photons = 100000\nvolume_estimate = \"{estimate}\"\nseed = {seed}"))
            .replace("spp = 8", "spp = 2")
    };
    let means = |estimate: &str| -> Vec<f64> {
        (1..=6).map(|seed| image_mean(&render_with(&scene(&small(estimate, seed)), 2).image.data)).collect()
    };
    let (point, beam) = (mean_and_sem(&means("point")), mean_and_sem(&means("beam")));
    let se = (point.1 * point.1 + beam.1 * beam.1).sqrt();
    eprintln!("fog box: point {point:?}, beam {beam:?}");
    assert!(se < 0.02 * point.0, "standard error {se} of {}", point.0);
    assert!((point.0 - beam.0).abs() < 3.0 * se, "point {point:?}, beam {beam:?}");
}

/// Chords the estimate must survive: one grazing the slab's top face (inside it, 1 µm below),
/// one of zero length, one of NaN length: finite, non-negative radiance, nothing for the
/// degenerate ones; the face seen edge-on, read by the beam estimate and by photon beams.
#[test]
fn grazing_and_empty_chords_give_finite_non_negative_light() {
    let s = scene(&collimated_slab());
    let (sink, _) = shoot(&s.world, &PassSettings::of(&s), MapKind::Global, 50_000, 9, &|_| {});
    let map = PhotonMap::build(&sink.volume);
    let discs = BeamMap::build(&map, 50, 0.2, 1.0);
    let est = BeamEstimator { map: &map, discs: &discs, bands: s.bands, paths: Paths::All, scatter_rows: None };
    let medium = &s.world.media[0];
    let (mut hits, mut tmp) = (Vec::new(), [0.0; morgana::spectrum::MAX_BANDS]);
    let mut total = |o: DVec3, d: DVec3, len: f64| {
        est.gather(o, d, len, SegmentEnds::default(), &mut hits);
        let mut l = 0.0;
        for h in &hits {
            est.photon(h, -d, (0, medium), &mut tmp, &mut |_, v| l += v);
        }
        l
    };
    let grazing = total(DVec3::new(-2.0, 0.0, 0.5 - 1e-6), DVec3::X, 4.0);
    assert!(grazing.is_finite() && grazing > 0.0, "grazing chord: {grazing}");
    assert_eq!(total(DVec3::ZERO, DVec3::X, 0.0), 0.0);
    assert_eq!(total(DVec3::ZERO, DVec3::X, f64::NAN), 0.0);
    // The same chord grazing from a camera: a render of the face seen edge-on is finite.
    let edge = collimated_slab()
        .replace("position = [0.0, 0.0, 3.0]", "position = [-3.0, 0.0, 0.5]")
        .replace("look_at = [0.0, 0.0, 0.0]", "look_at = [0.0, 0.0, 0.5]")
        .replace("width = 1\nheight = 1", "width = 8\nheight = 8");
    let r = render_with(&scene(&edge), 2);
    assert!(r.image.data.iter().all(|v| v.is_finite() && *v >= 0.0));
    // And read by photon beams: chords along the face run along the beams' tubes' ends.
    let tubes = edge.replace("volume_estimate = \"beam\"", "volume_estimate = \"photon_beams\"");
    let r = render_with(&scene(&tubes), 2);
    assert!(r.image.data.iter().all(|v| v.is_finite() && *v >= 0.0));
    assert!(r.image.data.iter().any(|v| *v > 0.0), "the slab seen edge-on is lit");
}

/// The effect plan says which estimate reads the volume map; an unknown one is refused naming
/// the key and the choices.
#[test]
fn the_plan_names_the_volume_estimate_and_bad_names_are_refused() {
    let beam = scene(&collimated_slab());
    assert!(beam.plan.volume_map.why.contains("beam estimate"), "{}", beam.plan.volume_map.why);
    let point = scene(&collimated_slab().replace("volume_estimate = \"beam\"", "volume_estimate = \"point\""));
    assert!(point.plan.volume_map.why.contains("point estimate"), "{}", point.plan.volume_map.why);
    let tubes = scene(&collimated_slab_read_by("photon_beams"));
    assert!(tubes.plan.volume_map.why.contains("photon beams"), "{}", tubes.plan.volume_map.why);
    let e = scene_error(&collimated_slab().replace("volume_estimate = \"beam\"", "volume_estimate = \"beams\""));
    assert!(e.contains("volume_estimate") && e.contains("photon_beams") && e.contains("test.toml"), "{e}");
}

/// Unset, `volume_estimate` is the beam estimate where the volume map holds sharp-edged light —
/// a specular surface can focus light into the medium (a volume caustic:
/// `tests/volume_caustic.rs`), the map carries the direct light, or a spot light shines into
/// the medium — and the eye paths' march steps across the scattering media outnumber the
/// photons; the point estimate otherwise. A given estimate is kept.
#[test]
fn the_default_is_the_beam_estimate_where_the_map_holds_sharp_edged_light() {
    let unset = collimated_slab().replace("volume_estimate = \"beam\"\n", "");
    let shadow = unset.replace("direct = \"photon_map\"", "direct = \"shadow_rays\"");
    let wide = |t: &str| t.replace("width = 1\nheight = 1", "width = 64\nheight = 64");
    let glass = "\n[[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n\n\
                 [[shape]]\ntype = \"sphere\"\ncenter = [0.0, 0.0, 0.0]\nradius = 0.3\nmaterial = \"glass\"\n";
    let estimate = |t: &str| {
        let s = scene(t);
        let words =
            if s.integrator.volume_estimate == VolumeEstimate::Beam { "beam estimate" } else { "point estimate" };
        assert!(s.plan.volume_map.why.contains(words), "{}", s.plan.volume_map.why);
        s.integrator.volume_estimate
    };
    assert_eq!(estimate(&wide(&shadow)), VolumeEstimate::Point, "fog lit by shadow rays, nothing specular");
    assert_eq!(estimate(&(wide(&shadow) + glass)), VolumeEstimate::Beam, "a glass ball in fog");
    assert_eq!(estimate(&wide(&unset)), VolumeEstimate::Beam, "the direct light read from the map");
    let spot = "\n[[light]]\ntype = \"spot\"\nposition = [0.0, 0.0, 0.0]\ndirection = [1.0, 0.0, 0.0]\n\
                cone_deg = 3.0\nspectrum = 1.0\npower_w = 1.0\n";
    assert_eq!(estimate(&(wide(&shadow) + spot)), VolumeEstimate::Beam, "a spot light in fog lit by shadow rays");
    assert_eq!(estimate(&(unset.clone() + glass)), VolumeEstimate::Point, "one pixel: fewer steps than photons");
    let given = wide(&unset).replace("[integrator]\n", "[integrator]\nvolume_estimate = \"point\"\n") + glass;
    assert_eq!(estimate(&given), VolumeEstimate::Point, "a given estimate is kept");
    // The march steps are counted across the scattering media, not the scene: 64² pixels × 16
    // samples over the slab's 5.74 m diagonal in 1 m steps are 376 000 < 10⁶ photons, however
    // far a wall away (a wall 10 km off makes the scene's diagonal 6.6 × 10⁸ steps).
    let steps = |t: &str| t.replace("[integrator]\n", "[integrator]\nphotons = 1000000\nmarch_step = 1.0\n");
    let far_wall = "\n[[material]]\nname = \"wall\"\ntype = \"lambertian\"\nreflectance = 0.5\n\n\
                    [[shape]]\ntype = \"sphere\"\ncenter = [10000.0, 0.0, 0.0]\nradius = 1.0\nmaterial = \"wall\"\n";
    assert_eq!(estimate(&(steps(&wide(&unset)) + far_wall)), VolumeEstimate::Point, "a thin medium in a large scene");
    let finer = steps(&wide(&unset)).replace("march_step = 1.0", "march_step = 0.2") + far_wall;
    assert_eq!(estimate(&finer), VolumeEstimate::Beam, "1.9 × 10⁶ steps across the medium");
}
