//! The volume caustic of a ball lens, against deterministic light tracing.
//!
//! A point spotlight above a glass sphere in thin, nearly black fog: the light the sphere
//! focuses into the fog below it reaches the camera only through the volume photon map
//! (shadow rays cannot see through glass; Jensen & Christensen 1998, §3), and its radiance
//! field is singular on the caustic (the axis, where every zone of the aberrated lens crosses,
//! and the envelope of the rays). So the per-pixel answer is not a closed form; it is computed
//! here by an independent estimator that has no photon map, no radius and no randomness:
//!
//! the single-scattered radiance of a pixel is a sum over light rays. A ray leaving the light
//! in the solid angle dω carries the flux I dω; it is split at every face of the sphere by the
//! unpolarised Fresnel equations (reflected R, refracted 1 − R; Snell's law for the direction;
//! Hecht, *Optics*, 5th ed., §4.6), and each straight piece of it in the fog, attenuated by
//! e^(−σ_t s) along its way, scatters σ_s p dt of its flux per length into the intensity
//! J = σ_s p I dω e^(−σ_t s) dt toward the camera (isotropic p = 1/4π). Seen from the pinhole
//! at the distance d, attenuated by e^(−σ_t d), a point of intensity J adds to the mean radiance
//! of the pixel its image falls in
//!
//! ```text
//!     ΔL = J e^(−σ_t d) / (d² cos³θ A_pix)
//! ```
//!
//! (∫ L dω = J/d² over the point's image, and the image plane at unit distance has
//! dω = cos³θ dA; A_pix is a pixel's area on that plane: a pixel's value is its radiance
//! averaged over its area). The light rays cover the cone on a midpoint grid in (cos θ, φ) and
//! each piece in the camera's view is summed in steps of a quarter of a pixel, so the
//! integrand's singularities never appear: the caustic is where many rays' pieces project, not
//! a division by a vanishing Jacobian.
//!
//! The fog's albedo is 0.003, so the light scattered twice or more, which this sum leaves out
//! and morgana keeps, is at most about 0.3 % of the single scattering (the chance that light
//! scatters once more on its way across the box, σ_s · 3 m = 0.0027). Every wall is black, and
//! no pixel sees the sphere (checked), so every point the sum projects is seen directly.

use glam::DVec3;
use std::f64::consts::PI;

mod common;

use common::{render_with, scene};
use morgana::scene::VolumeEstimate;

const SPHERE_R: f64 = 0.3;
const IOR: f64 = 1.5;
/// A spotlight of uniform intensity within its cone.
struct Spot {
    position: DVec3,
    axis: DVec3,
    cone_deg: f64,
}

/// The spot focused by the ball: 0.95 m above it, every point of the ball in its cone.
const ABOVE_THE_BALL: Spot = Spot { position: DVec3::new(0.0, 0.95, 0.0), axis: DVec3::NEG_Y, cone_deg: 25.0 };

/// A narrow beam (3°) across the camera's view below the ball, which it misses: a searchlight's
/// sharp-edged beam, with no glass in its way.
const ACROSS_THE_VIEW: Spot = Spot { position: DVec3::new(-1.4, -0.7, 0.0), axis: DVec3::X, cone_deg: 3.0 };
/// The spot's intensity, W sr⁻¹ nm⁻¹.
const INTENSITY: f64 = 1.0;
const SIGMA_T: f64 = 0.3;
const ALBEDO: f64 = 0.003;
/// Half the side of the black box around the scene, m.
const BOX: f64 = 1.5;
const CAMERA: DVec3 = DVec3::new(0.0, -0.7, 1.4);
const LOOK_AT: DVec3 = DVec3::new(0.0, -0.7, 0.0);
const FOV_DEG: f64 = 24.0;
const PIXELS: usize = 24;

fn scene_toml(spot: &Spot, integrator: &str) -> String {
    let b = BOX;
    let quad = |o: [f64; 3], u: [f64; 3], v: [f64; 3]| {
        format!("[[shape]]\ntype = \"quad\"\norigin = {o:?}\nu = {u:?}\nv = {v:?}\nmaterial = \"black\"\n\n")
    };
    let walls = [
        quad([-b, -b, -b], [2.0 * b, 0.0, 0.0], [0.0, 2.0 * b, 0.0]),
        quad([-b, -b, b], [2.0 * b, 0.0, 0.0], [0.0, 2.0 * b, 0.0]),
        quad([-b, -b, -b], [0.0, 2.0 * b, 0.0], [0.0, 0.0, 2.0 * b]),
        quad([b, -b, -b], [0.0, 2.0 * b, 0.0], [0.0, 0.0, 2.0 * b]),
        quad([-b, -b, -b], [2.0 * b, 0.0, 0.0], [0.0, 0.0, 2.0 * b]),
        quad([-b, b, -b], [2.0 * b, 0.0, 0.0], [0.0, 0.0, 2.0 * b]),
    ]
    .concat();
    format!(
        r#"
[camera]
position = {camera:?}
look_at = {look_at:?}
fov_deg = {FOV_DEG}
width = {PIXELS}
height = {PIXELS}

[output]
bands = 1
min_nm = 500.0
max_nm = 600.0

[integrator]
{integrator}

[world]
medium = "fog"

[[medium]]
name = "fog"
sigma_t = {SIGMA_T}
albedo = {ALBEDO}
phase = "isotropic"

[[material]]
name = "black"
type = "lambertian"
reflectance = 0.0

[[material]]
name = "glass"
type = "dielectric"
ior = {IOR}

[[shape]]
type = "sphere"
center = [0.0, 0.0, 0.0]
radius = {SPHERE_R}
material = "glass"

{walls}
[[light]]
type = "spot"
position = {light:?}
direction = {axis:?}
cone_deg = {cone}
spectrum = 1.0
scale = {INTENSITY}
"#,
        camera = CAMERA.to_array(),
        look_at = LOOK_AT.to_array(),
        light = spot.position.to_array(),
        axis = spot.axis.to_array(),
        cone = spot.cone_deg,
    )
}

/// Unpolarised Fresnel reflectance for light going from index `n1` to `n2` at the cosine of
/// incidence `cos_i` (Hecht §4.6.2); 1 beyond the critical angle.
fn fresnel(cos_i: f64, n1: f64, n2: f64) -> f64 {
    let sin_t2 = (n1 / n2).powi(2) * (1.0 - cos_i * cos_i);
    if sin_t2 >= 1.0 {
        return 1.0;
    }
    let cos_t = (1.0 - sin_t2).sqrt();
    let rs = (n1 * cos_i - n2 * cos_t) / (n1 * cos_i + n2 * cos_t);
    let rp = (n2 * cos_i - n1 * cos_t) / (n2 * cos_i + n1 * cos_t);
    0.5 * (rs * rs + rp * rp)
}

/// The refracted direction of `d` at a face with unit normal `n` facing against `d`, from index
/// `n1` to `n2` (Snell), or `None` past the critical angle.
fn refract(d: DVec3, n: DVec3, n1: f64, n2: f64) -> Option<DVec3> {
    let eta = n1 / n2;
    let cos_i = -n.dot(d);
    let sin_t2 = eta * eta * (1.0 - cos_i * cos_i);
    (sin_t2 < 1.0).then(|| (eta * d + (eta * cos_i - (1.0 - sin_t2).sqrt()) * n).normalize())
}

/// Distances along the ray `o + t d` (unit d) to the sphere about the origin: (near, far).
fn sphere_hits(o: DVec3, d: DVec3) -> Option<(f64, f64)> {
    let b = o.dot(d);
    let c = o.length_squared() - SPHERE_R * SPHERE_R;
    let disc = b * b - c;
    (disc > 0.0).then(|| {
        let s = disc.sqrt();
        (-b - s, -b + s)
    })
}

/// Distance from `o` (inside the box) along `d` to the box's walls.
fn to_wall(o: DVec3, d: DVec3) -> f64 {
    let mut t = f64::INFINITY;
    for (p, v) in o.to_array().into_iter().zip(d.to_array()) {
        if v != 0.0 {
            t = t.min(((BOX * v.signum()) - p) / v);
        }
    }
    t
}

/// The pinhole camera of the scene: its basis and the image-plane geometry.
struct View {
    right: DVec3,
    up: DVec3,
    forward: DVec3,
    tan_half: f64,
    pixel_area: f64,
}

impl View {
    fn new() -> View {
        let forward = (LOOK_AT - CAMERA).normalize();
        let right = forward.cross(DVec3::Y).normalize();
        let up = right.cross(forward);
        let tan_half = (0.5 * FOV_DEG.to_radians()).tan();
        let side = 2.0 * tan_half / PIXELS as f64;
        let view = View { right, up, forward, tan_half, pixel_area: side * side };
        // The sum assumes that every point it projects is seen directly, not through the sphere.
        let n = 4 * PIXELS;
        for (i, j) in (0..=n).flat_map(|i| (0..=n).map(move |j| (i, j))) {
            let (sx, sy) = ((2.0 * i as f64 / n as f64 - 1.0) * tan_half, (2.0 * j as f64 / n as f64 - 1.0) * tan_half);
            let d = (forward + sx * right + sy * up).normalize();
            assert!(sphere_hits(CAMERA, d).is_none_or(|(_, far)| far < 0.0), "the camera sees the sphere");
        }
        view
    }

    /// Camera coordinates (right, up, forward) of `x`.
    fn local(&self, x: DVec3) -> DVec3 {
        let v = x - CAMERA;
        DVec3::new(v.dot(self.right), v.dot(self.up), v.dot(self.forward))
    }

    /// The part [t0, t1] of the segment o + t d, t in [0, len], inside the view frustum.
    fn clip(&self, o: DVec3, d: DVec3, len: f64) -> Option<(f64, f64)> {
        let (lo, ld) = (self.local(o), self.local(o + d) - self.local(o));
        let (mut t0, mut t1) = (0.0f64, len);
        // Each side is a·p + c·k ≤ 0 for a plane through the pinhole: ±x − k z ≤ 0, ±y − k z ≤ 0.
        let k = self.tan_half;
        for (px, py) in [(1.0, 0.0), (-1.0, 0.0), (0.0, 1.0), (0.0, -1.0)] {
            let f0 = px * lo.x + py * lo.y - k * lo.z;
            let fd = px * ld.x + py * ld.y - k * ld.z;
            if fd.abs() < 1e-300 {
                if f0 > 0.0 {
                    return None;
                }
            } else if fd > 0.0 {
                t1 = t1.min(-f0 / fd);
            } else {
                t0 = t0.max(-f0 / fd);
            }
        }
        (t1 > t0).then_some((t0, t1))
    }

    /// The pixel (column, row) the point with camera coordinates `l` falls in, if any.
    fn pixel(&self, l: DVec3) -> Option<(usize, usize)> {
        let sx = l.x / (l.z * self.tan_half);
        let sy = l.y / (l.z * self.tan_half);
        let (x, y) = (0.5 * (sx + 1.0) * PIXELS as f64, 0.5 * (1.0 - sy) * PIXELS as f64);
        (x >= 0.0 && y >= 0.0 && x < PIXELS as f64 && y < PIXELS as f64).then_some((x as usize, y as usize))
    }
}

/// Adds what the fog along o + t d, t in [0, len], scatters into the pixels, for a light-ray
/// piece of flux `flux` at t = 0 (W nm⁻¹).
fn scatter_piece(view: &View, image: &mut [f64], o: DVec3, d: DVec3, len: f64, flux: f64) {
    let Some((t0, t1)) = view.clip(o, d, len) else { return };
    let (a, b) = (view.local(o + t0 * d), view.local(o + t1 * d));
    let span_px = (a.x / a.z - b.x / b.z).hypot(a.y / a.z - b.y / b.z) / (2.0 * view.tan_half) * PIXELS as f64;
    let steps = (4.0 * span_px).ceil().max(4.0) as usize;
    let dt = (t1 - t0) / steps as f64;
    let sigma_s = ALBEDO * SIGMA_T;
    for i in 0..steps {
        let t = t0 + (i as f64 + 0.5) * dt;
        let x = o + t * d;
        let l = view.local(x);
        let Some((col, row)) = view.pixel(l) else { continue };
        let dist = l.length();
        let intensity = sigma_s / (4.0 * PI) * flux * (-SIGMA_T * t).exp() * dt;
        image[row * PIXELS + col] += intensity * (-SIGMA_T * dist).exp() * dist / (l.z.powi(3) * view.pixel_area);
    }
}

/// The light-traced image in two parts, summed in one pass over the rays.
struct Traced {
    /// The rays' pieces from the light to the sphere or a wall: what shadow rays see.
    direct: Vec<f64>,
    /// The pieces after the sphere (reflected or refracted): what only photons carry.
    through: Vec<f64>,
}

/// Faces of the sphere a light ray is followed through: the reflection at the first, and up
/// to three reflections inside (each R ≤ 0.04 near normal incidence ... 1 at grazing, so the
/// rays left out carry R⁴ of what entered).
const FACES: u32 = 4;

/// Follows a light ray of flux `flux` from `ray.0` along `ray.1` in the fog, through every
/// Fresnel branch of the sphere (`depth` more faces), adding the single scattering of its
/// pieces to `out` (a piece straight from the light to `direct`, the others to `through`).
fn follow(view: &View, out: &mut Traced, ray: (DVec3, DVec3), flux: f64, depth: u32) {
    let (o, d) = ray;
    let image = if depth == FACES { &mut out.direct } else { &mut out.through };
    let wall = to_wall(o, d);
    let hit = sphere_hits(o, d).filter(|&(near, _)| near > 1e-9 && near < wall);
    let Some((near, _)) = hit else {
        scatter_piece(view, image, o, d, wall, flux);
        return;
    };
    scatter_piece(view, image, o, d, near, flux);
    let flux = flux * (-SIGMA_T * near).exp();
    let p = o + near * d;
    let n = p / SPHERE_R;
    let r = fresnel(-n.dot(d), 1.0, IOR);
    if depth > 0 {
        follow(view, out, (p, d - 2.0 * d.dot(n) * n), flux * r, depth - 1);
    }
    let Some(mut inside) = refract(d, n, 1.0, IOR) else { return };
    let (mut at, mut carried) = (p, flux * (1.0 - r));
    // Inside the glass (no fog): exit where the chord ends, reflecting back in with R.
    for _ in 0..depth {
        let far = sphere_hits(at, inside).map_or(0.0, |(_, far)| far);
        let q = at + far * inside;
        let n_in = -q / SPHERE_R;
        let r_in = fresnel(-n_in.dot(inside), IOR, 1.0);
        if let Some(exit) = refract(inside, n_in, IOR, 1.0) {
            follow(view, out, (q, exit), carried * (1.0 - r_in), 0);
        }
        carried *= r_in;
        if carried < 1e-9 * flux {
            return;
        }
        inside = inside - 2.0 * inside.dot(n_in) * n_in;
        at = q;
    }
}

/// The single-scattered radiance of every pixel (row-major, W m⁻² sr⁻¹ nm⁻¹) from `spot`'s
/// light rays on an `n_mu` × `n_phi` midpoint grid over its cone in (cos θ, φ).
fn light_traced(spot: &Spot, n_mu: usize, n_phi: usize) -> Traced {
    let view = View::new();
    let mut out = Traced { direct: vec![0.0; PIXELS * PIXELS], through: vec![0.0; PIXELS * PIXELS] };
    let cos_cone = spot.cone_deg.to_radians().cos();
    let (d_mu, d_phi) = ((1.0 - cos_cone) / n_mu as f64, 2.0 * PI / n_phi as f64);
    let flux = INTENSITY * d_mu * d_phi;
    let (e1, e2) = spot.axis.any_orthonormal_pair();
    for i in 0..n_mu {
        let mu = cos_cone + (i as f64 + 0.5) * d_mu;
        let s = (1.0 - mu * mu).sqrt();
        for j in 0..n_phi {
            let phi = (j as f64 + 0.5) * d_phi;
            let d = mu * spot.axis + s * (phi.cos() * e1 + phi.sin() * e2);
            follow(&view, &mut out, (spot.position, d), flux, FACES);
        }
    }
    out
}

/// The light-traced single scattering on the grid the tests use.
fn oracle(spot: &Spot) -> Traced {
    light_traced(spot, 2000, 720)
}

/// Sums of `values` over groups of pixels: `group(pixel index)` names each pixel's group.
fn sums(values: &[f64], groups: usize, group: impl Fn(usize) -> usize) -> Vec<f64> {
    let mut out = vec![0.0; groups];
    values.iter().enumerate().for_each(|(i, v)| out[group(i)] += v);
    out
}

/// The 4 × 4-pixel block of pixel `i` (36 blocks).
fn block(i: usize) -> usize {
    (i / PIXELS / 4) * (PIXELS / 4) + (i % PIXELS) / 4
}

/// A render's values with `subtract` taken off, and their variances from the passes' spread.
fn values_and_variances(rendered: &morgana::render::Rendered, subtract: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let se = rendered.std_error.as_ref().expect("a standard error needs two passes or more");
    let values = rendered.image.data.iter().zip(subtract).map(|(&v, s)| f64::from(v) - s).collect();
    (values, se.iter().map(|&e| f64::from(e).powi(2)).collect())
}

/// Compares group sums of a render with the light-traced sums: each ratio within `bias` plus
/// `z` of its standard errors of 1.
fn check(what: &str, got: &[f64], var: &[f64], want: &[f64], bias: f64, z: f64) {
    for (i, ((g, v), w)) in got.iter().zip(var).zip(want).enumerate() {
        let (ratio, se) = (g / w, v.sqrt() / w);
        assert!(
            (ratio - 1.0).abs() < bias + z * se,
            "{what} {i}: morgana/light tracing = {ratio:.4} ± {se:.4}, beyond {bias} + {z} standard errors"
        );
    }
}

/// Shadow rays and the light tracing agree on the light that reaches the fog straight from the
/// spot: this checks the sum's camera, pixel normalisation, intensity and attenuation against
/// the path that needs no photon map (each 4 × 4 block within 0.5 % + 4 standard errors).
#[test]
fn shadow_rays_see_the_direct_light_as_light_tracing_does() {
    let direct = light_traced(&ABOVE_THE_BALL, 1000, 360).direct;
    let integrator = "photons = 0\nspp = 4\npasses = 4\nseed = 3\nmarch_step = 0.01";
    let r = render_with(&scene(&scene_toml(&ABOVE_THE_BALL, integrator)), 2);
    let (got, var) = values_and_variances(&r, &vec![0.0; PIXELS * PIXELS]);
    let blocks = PIXELS * PIXELS / 16;
    check("block", &sums(&got, blocks, block), &sums(&var, blocks, block), &sums(&direct, blocks, block), 0.005, 4.0);
}

/// The light through the sphere, which only the volume photon map carries, converges to the
/// light tracing's: 32 progressive passes of 200 000 photons with the beam estimate, the
/// default beside a glass ball (discs of at most 5 cm, shrinking with α = 0.5). The caustic is sharp, so single pixels keep the blur
/// of the discs for many passes; a row of pixels spans the caustic from side to side, so its
/// sum keeps only the vertical part of the blur. The bound on each row and on the whole image
/// is 1 % (the twice-scattered light morgana keeps and the sum leaves out, ≤ 0.3 %; the light
/// tracing's own grid error, checked here against a grid half as fine) plus 4 (rows) or 3
/// (image) standard errors.
#[test]
fn the_volume_caustic_of_a_ball_lens_matches_light_tracing() {
    let Traced { direct, through } = oracle(&ABOVE_THE_BALL);
    let coarse = light_traced(&ABOVE_THE_BALL, 1000, 360).through;
    let row = |i: usize| i / PIXELS;
    for (fine, coarse) in sums(&through, PIXELS, row).iter().zip(sums(&coarse, PIXELS, row)) {
        assert!((coarse / fine - 1.0).abs() < 0.003, "the light tracing is not converged: {coarse} vs {fine}");
    }
    let integrator = "photons = 200000\nspp = 4\npasses = 32\nseed = 3\nmarch_step = 0.01\n\
                      volume_max_radius = 0.05\nalpha = 0.5";
    let s = scene(&scene_toml(&ABOVE_THE_BALL, integrator));
    assert_eq!(s.integrator.volume_estimate, VolumeEstimate::Beam, "the default beside a glass ball");
    let r = render_with(&s, 2);
    let (got, var) = values_and_variances(&r, &direct);
    check("row", &sums(&got, PIXELS, row), &sums(&var, PIXELS, row), &sums(&through, PIXELS, row), 0.01, 4.0);
    let all = |_: usize| 0;
    check("image", &sums(&got, 1, all), &sums(&var, 1, all), &sums(&through, 1, all), 0.01, 3.0);
}

/// Photon beams (`volume_estimate = "photon_beams"`) blur the caustic across each photon's
/// flight by a tube a few millimetres wide, where the beam estimate's discs were centimetres:
/// after 16 passes of 200 000 photons (default radii) every 4 × 4 block of the light through
/// the sphere is within 3 % + 4 standard errors of the light tracing (the beam estimate's
/// blocks read 0.98–1.20 after 32 passes), each row within 1 % + 4 and the image within
/// 1 % + 3.
#[test]
fn photon_beams_resolve_the_volume_caustic_block_by_block() {
    let Traced { direct, through } = oracle(&ABOVE_THE_BALL);
    let integrator = "photons = 200000\nspp = 4\npasses = 16\nseed = 3\nmarch_step = 0.01\n\
                      volume_estimate = \"photon_beams\"";
    let r = render_with(&scene(&scene_toml(&ABOVE_THE_BALL, integrator)), 2);
    let (got, var) = values_and_variances(&r, &direct);
    let blocks = PIXELS * PIXELS / 16;
    let (g, v, w) = (sums(&got, blocks, block), sums(&var, blocks, block), sums(&through, blocks, block));
    let ratios: Vec<String> = g.iter().zip(&w).map(|(g, w)| format!("{:.3}", g / w)).collect();
    eprintln!("photon beams, 4 × 4 blocks over light tracing: {}", ratios.join(" "));
    check("block", &g, &v, &w, 0.03, 4.0);
    let row = |i: usize| i / PIXELS;
    check("row", &sums(&got, PIXELS, row), &sums(&var, PIXELS, row), &sums(&through, PIXELS, row), 0.01, 4.0);
    let all = |_: usize| 0;
    check("image", &sums(&got, 1, all), &sums(&var, 1, all), &sums(&through, 1, all), 0.01, 3.0);
}

/// A narrow beam read from the photon map. With `direct = "photon_map"` (what curved paths
/// need) the volume map carries the single scattering of a 3° spot's beam itself, whose edges
/// are sharp; its light-traced image is the whole answer (the beam misses the ball). The beam
/// estimate reads the image within 1 % + 3 standard errors, and each row holding at least a
/// quarter of the brightest row's light within 4 % + 4 (the rows at the beam's edges keep the
/// discs' blur: light moved outward by a disc's radius).
#[test]
fn a_narrow_beam_read_from_the_photon_map_matches_light_tracing() {
    let want = oracle(&ACROSS_THE_VIEW).direct;
    let integrator = "photons = 200000\nspp = 4\npasses = 16\nseed = 3\nmarch_step = 0.01\n\
                      direct = \"photon_map\"\nvolume_estimate = \"beam\"\nvolume_max_radius = 0.05\nalpha = 0.5";
    let r = render_with(&scene(&scene_toml(&ACROSS_THE_VIEW, integrator)), 2);
    let (got, var) = values_and_variances(&r, &vec![0.0; PIXELS * PIXELS]);
    let all = |_: usize| 0;
    check("image", &sums(&got, 1, all), &sums(&var, 1, all), &sums(&want, 1, all), 0.01, 3.0);
    let row = |i: usize| i / PIXELS;
    let (got, var, want) = (sums(&got, PIXELS, row), sums(&var, PIXELS, row), sums(&want, PIXELS, row));
    let brightest = want.iter().copied().fold(0.0, f64::max);
    let core: Vec<usize> = (0..PIXELS).filter(|&i| want[i] >= 0.25 * brightest).collect();
    assert!(core.len() >= 4, "the beam crosses too few rows: {core:?}");
    let pick = |v: &[f64]| core.iter().map(|&i| v[i]).collect::<Vec<_>>();
    check("row", &pick(&got), &pick(&var), &pick(&want), 0.04, 4.0);
}

/// The measurement of the book's table (docs/book/src/convergence.md, "A volume caustic against
/// light tracing"): the light through the sphere, morgana over light tracing, for the image, its
/// rows and its 4 × 4 blocks, with the point and the beam estimates and photon beams. Prints;
/// asserts nothing.
///
/// `cargo test --release --test volume_caustic -- --ignored --nocapture` (about 10 minutes on
/// two cores).
#[test]
#[ignore]
fn point_and_beam_estimates_against_light_tracing() {
    let Traced { direct, through } = oracle(&ABOVE_THE_BALL);
    let runs = [
        ("point, defaults, 8 passes", "passes = 8\nvolume_estimate = \"point\""),
        ("point, defaults, 32 passes", "passes = 32\nvolume_estimate = \"point\""),
        (
            "point, 5 cm, α = 0.5, 32 passes",
            "passes = 32\nvolume_estimate = \"point\"\nvolume_max_radius = 0.05\nalpha = 0.5",
        ),
        (
            "point, 3 cm fixed, α = 0.5, 32 passes",
            "passes = 32\nvolume_estimate = \"point\"\nvolume_k = 100000\nvolume_max_radius = 0.03\nalpha = 0.5",
        ),
        ("beam (the default), 32 passes", "passes = 32"),
        ("beam, 5 cm, α = 0.5, 32 passes", "passes = 32\nvolume_max_radius = 0.05\nalpha = 0.5"),
        ("photon beams, default radii, 8 passes", "passes = 8\nvolume_estimate = \"photon_beams\""),
        ("photon beams, default radii, 32 passes", "passes = 32\nvolume_estimate = \"photon_beams\""),
    ];
    let blocks = PIXELS * PIXELS / 16;
    let row = |i: usize| i / PIXELS;
    eprintln!("| estimate | image | rows, least – most | blocks, least – most | wall s |");
    for (name, extra) in runs {
        let t = std::time::Instant::now();
        let toml =
            scene_toml(&ABOVE_THE_BALL, &format!("photons = 200000\nspp = 4\nseed = 3\nmarch_step = 0.01\n{extra}"));
        let r = render_with(&scene(&toml), 2);
        let (got, var) = values_and_variances(&r, &direct);
        let ratios = |groups: usize, g: &dyn Fn(usize) -> usize| {
            let (s, v, w) = (sums(&got, groups, g), sums(&var, groups, g), sums(&through, groups, g));
            s.iter().zip(&v).zip(&w).map(|((s, v), w)| (s / w, v.sqrt() / w)).collect::<Vec<_>>()
        };
        let range = |x: &[(f64, f64)]| {
            let lo = x.iter().min_by(|a, b| a.0.total_cmp(&b.0)).copied().unwrap_or_default();
            let hi = x.iter().max_by(|a, b| a.0.total_cmp(&b.0)).copied().unwrap_or_default();
            format!("{:.3} ± {:.3} – {:.3} ± {:.3}", lo.0, lo.1, hi.0, hi.1)
        };
        let image = ratios(1, &|_| 0)[0];
        eprintln!(
            "| {name} | {:.3} ± {:.3} | {} | {} | {:.0} |",
            image.0,
            image.1,
            range(&ratios(PIXELS, &row)),
            range(&ratios(blocks, &block)),
            t.elapsed().as_secs_f64()
        );
    }
    // The narrow beam, all of its light from the photon map (`direct = "photon_map"`).
    let want = oracle(&ACROSS_THE_VIEW).direct;
    for estimate in ["point", "beam", "photon_beams"] {
        for extra in ["", "volume_max_radius = 0.05\nalpha = 0.5"] {
            let toml = scene_toml(
                &ACROSS_THE_VIEW,
                &format!(
                    "photons = 200000\nspp = 4\nseed = 3\nmarch_step = 0.01\npasses = 16\ndirect = \"photon_map\"\n\
                     volume_estimate = \"{estimate}\"\n{extra}"
                ),
            );
            let r = render_with(&scene(&toml), 2);
            let (got, var) = values_and_variances(&r, &vec![0.0; PIXELS * PIXELS]);
            let (g, v, w) = (got.iter().sum::<f64>(), var.iter().sum::<f64>(), want.iter().sum::<f64>());
            eprintln!("| narrow beam, {estimate}, {extra:?}, 16 passes | {:.3} ± {:.3} |", g / w, v.sqrt() / w);
        }
    }
}
