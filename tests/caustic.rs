//! Caustics: a glass sphere focuses a narrow collimated beam where paraxial optics puts it, and
//! dispersion orders the foci of blue and red.
//!
//! A ball lens of radius R and index n has its paraxial back focus at f = nR/(2(n − 1)) from its
//! centre (Hecht, *Optics*, 5th ed., §6.2, thick-lens formulas with R₁ = −R₂ = R, d = 2R). A
//! beam of radius 0.05 R keeps spherical aberration negligible. From the caustic photons stored on
//! a screen (positions and arrival directions) the distance of least RMS spot radius follows in
//! closed form; it is compared with f at each colour's index.

mod common;

use common::scene;
use morgana::material::named_glass;
use morgana::photon::PassSettings;
use morgana::photon::{MapKind, shoot};
use morgana::photon_map::PhotonRecord;

fn scene_toml() -> String {
    let cone_deg = (0.05f64 / 1.0e4).atan().to_degrees();
    format!(
        r#"
[camera]
position = [0.0, 0.0, 6.0]
look_at = [0.0, 0.0, 0.0]
fov_deg = 40.0
width = 8
height = 8

[output]
bands = 11
min_nm = 440.0
max_nm = 660.0

[[material]]
name = "glass"
type = "dielectric"
ior = "N-BK7"

[[material]]
name = "screen"
type = "lambertian"
reflectance = 0.5

[[shape]]
type = "sphere"
center = [0.0, 0.0, 0.0]
radius = 1.0
material = "glass"

[[shape]]
type = "quad"
origin = [-5.0, -3.0, -5.0]
u = [0.0, 0.0, 10.0]
v = [10.0, 0.0, 0.0]
material = "screen"

[[light]]
type = "spot"
position = [0.0, 1.0e4, 0.0]
direction = [0.0, -1.0, 0.0]
cone_deg = {cone_deg}
spectrum = {{ nm = [440.0, 445.0, 450.0, 455.0, 645.0, 650.0, 655.0, 660.0], values = [0.0, 0.0, 1.0, 0.0, 0.0, 1.0, 0.0, 0.0] }}
power_w = 1.0
"#
    )
}

/// Distance below the sphere's centre where the RMS distance of the rays from the axis is least.
/// Each stored photon (at height y_p with direction d) is at lateral offset a + b t after a
/// further drop t, with a = (x, z) and b = (d_x, d_z)/d_y; Σ|a + b t|² is least at
/// t = −Σ a·b / Σ b·b.
fn least_confusion_depth(photons: &[&PhotonRecord]) -> f64 {
    let (mut ab, mut bb) = (0.0, 0.0);
    for p in photons {
        let (ax, az) = (p.position.x, p.position.z);
        let (bx, bz) = (p.dir.x / p.dir.y, p.dir.z / p.dir.y);
        ab += ax * bx + az * bz;
        bb += bx * bx + bz * bz;
    }
    let y = photons[0].position.y + (-ab / bb);
    -y
}

#[test]
fn glass_sphere_focuses_at_the_paraxial_focus_blue_before_red() {
    let s = scene(&scene_toml());
    assert!(s.plan.caustic_map.on);
    let photons = shoot(&s.world, &PassSettings::of(&s), MapKind::Caustic, 3_000_000, 2, &|_| {}).0.surface;
    let on_axis: Vec<&PhotonRecord> =
        photons.iter().filter(|p| p.dir.y < 0.0 && (p.position.x.hypot(p.position.z)) < 0.08).collect();
    let blue: Vec<&PhotonRecord> = on_axis.iter().copied().filter(|p| p.wavelength_nm < 550.0).collect();
    let red: Vec<&PhotonRecord> = on_axis.iter().copied().filter(|p| p.wavelength_nm >= 550.0).collect();
    assert!(blue.len() > 2000 && red.len() > 2000, "too few caustic photons: {} blue, {} red", blue.len(), red.len());
    let glass = named_glass("N-BK7").unwrap();
    let paraxial = |l: f64| {
        let n = glass.eval(l);
        n / (2.0 * (n - 1.0))
    };
    let (f_blue, f_red) = (least_confusion_depth(&blue), least_confusion_depth(&red));
    let (p_blue, p_red) = (paraxial(450.0), paraxial(650.0));
    assert!((f_blue / p_blue - 1.0).abs() < 0.003, "blue focus {f_blue}, paraxial {p_blue}");
    assert!((f_red / p_red - 1.0).abs() < 0.003, "red focus {f_red}, paraxial {p_red}");
    assert!(f_blue < f_red, "blue must focus closer than red: {f_blue} vs {f_red}");
    let (d, dp) = (f_red - f_blue, p_red - p_blue);
    assert!((d / dp - 1.0).abs() < 0.2, "focal separation {d}, paraxial {dp}");
}
