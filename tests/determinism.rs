//! A fixed seed gives the same output bytes for any thread count.

mod common;

use common::render_with;
use morgana::scene::default_scene;

#[test]
fn default_scene_is_identical_on_one_and_two_threads() {
    let mut s = default_scene().expect("default scene");
    s.camera =
        morgana::geometry::Camera::new(s.camera.position, s.camera.look_at, s.camera.up, s.camera.fov_deg, 40, 32);
    s.integrator.spp = 2;
    s.integrator.gather_rays = 4;
    s.apply_overrides(Some(20_000), Some(9));
    let one = render_with(&s, 1);
    let two = render_with(&s, 2);
    assert_eq!(one.image.data.len(), 40 * 32 * s.bands.count);
    assert!(one.image.data.iter().any(|v| *v > 0.0), "image is black");
    let bits = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert!(bits(&one.image.data) == bits(&two.image.data), "spectral data differ between 1 and 2 threads");
    assert!(bits(&one.image.rgb) == bits(&two.image.rgb), "RGB differs between 1 and 2 threads");
    assert_eq!(one.stats.rays, two.stats.rays);
    let dir = std::env::temp_dir().join(format!("morgana-determinism-{}", std::process::id()));
    let written: Vec<Vec<u8>> = [&one, &two]
        .iter()
        .enumerate()
        .map(|(i, r)| {
            let p = dir.join(format!("{i}.exr"));
            std::fs::create_dir_all(&dir).unwrap();
            morgana::spectrum::exr::write_spectral_exr(&p, &r.image).expect("write exr");
            std::fs::read(&p).unwrap()
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    assert!(written[0] == written[1], "EXR bytes differ between 1 and 2 threads");
}

/// The beam estimate (the default beside glass in fog: the volume caustic example, reduced)
/// gives the same bytes on one and two threads, its discs' pilot radii included.
#[test]
fn the_volume_caustic_with_the_beam_estimate_is_identical_on_one_and_two_threads() {
    let s = common::scene(&small_volume_caustic(""));
    assert_eq!(s.integrator.volume_estimate, morgana::scene::VolumeEstimate::Beam);
    identical_on_one_and_two_threads(&s);
}

/// Photon beams likewise: the flights kept in batch order, their tubes' radii and hierarchy.
#[test]
fn the_volume_caustic_with_photon_beams_is_identical_on_one_and_two_threads() {
    let s = common::scene(&small_volume_caustic("volume_estimate = \"photon_beams\"\n"));
    assert_eq!(s.integrator.volume_estimate, morgana::scene::VolumeEstimate::PhotonBeams);
    identical_on_one_and_two_threads(&s);
}

/// The volume caustic example at 24 × 24 with 30 000 photons and two passes, `keys` added to
/// its `[integrator]`.
fn small_volume_caustic(keys: &str) -> String {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/volume_caustic.toml"))
        .expect("the example");
    text.replace("width = 128", "width = 24")
        .replace("height = 128", "height = 24")
        .replace("photons = 1000000", "photons = 30000")
        .replace("gather_rays = 16", "gather_rays = 2")
        .replace("spp = 8", "spp = 1\npasses = 2")
        .replace("[integrator]\n", &format!("[integrator]\n{keys}"))
}

/// Renders `s` on one and on two threads: a lit image, and the same bits in its spectral data
/// and its standard errors.
fn identical_on_one_and_two_threads(s: &morgana::scene::Scene) {
    let (one, two) = (render_with(s, 1), render_with(s, 2));
    let bits = |d: &[f32]| d.iter().map(|v| v.to_bits()).collect::<Vec<_>>();
    assert!(one.image.data.iter().any(|v| *v > 0.0), "image is black");
    assert!(bits(&one.image.data) == bits(&two.image.data), "spectral data differ between 1 and 2 threads");
    let se = |r: &morgana::render::Rendered| bits(r.std_error.as_deref().expect("two passes"));
    assert!(se(&one) == se(&two), "standard errors differ between 1 and 2 threads");
}

/// A sky radiance sensor whose directions take more samples than one chunk
/// (`render::sensors::sky_radiance::CHUNK`) reads them in parallel chunks: the same bits on one
/// and on two threads (the twilight example, path-traced, two directions of 2 chunks + 5
/// samples).
#[test]
fn a_sky_sensor_read_in_chunks_is_identical_on_one_and_two_threads() {
    use morgana::render::sensors::sky_radiance::CHUNK;
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/sky_twilight.toml"))
        .expect("the example");
    let samples = 2 * CHUNK + 5;
    let text = text
        .replace("photons = 0\n", "method = \"path\"\n")
        .replace("directions_deg = [[0.0, 0.0]]", "directions_deg = [[0.0, 0.0], [60.0, 90.0]]")
        .replace("samples = 4\n", &format!("samples = {samples}\n"));
    let s = common::scene(&text);
    let (one, two) = (render_with(&s, 1), render_with(&s, 2));
    let column = |r: &morgana::render::Rendered| {
        let sky = r.sensors.iter().find(|x| x.name == "sky").expect("the sky sensor");
        sky.columns[0].1.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
    };
    let (a, b) = (column(&one), column(&two));
    assert_eq!(a.len(), 2);
    assert!(a.iter().all(|v| f64::from_bits(*v) > 0.0), "a dark sky: {a:?}");
    assert!(a == b, "sky radiance differs between 1 and 2 threads");
}
