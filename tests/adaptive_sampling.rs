//! Adaptive sampling across progressive passes (issue 17, item 7): the image stays an unbiased
//! average with calibrated standard errors when the passes' eye samples go where the spread
//! is; it spends no more samples than a uniform run and takes the squared error out of the
//! edges that cause it; it does not depend on the thread count; a resumed run writes the bytes
//! of an uninterrupted one; `--adaptive` without passes is refused.

mod common;

use common::{lit_plate, pinhole_90, render_with, scene, scene_error};

/// Width and height of the emitter scene, pixels.
const SIDE: usize = 32;

/// Radiance of the emitter, W m⁻² sr⁻¹ nm⁻¹.
const L: f64 = 7.0;

/// The emitting rectangle's x and y extent in the plane z = −1, m.
const X: [f64; 2] = [-0.53, 0.31];
const Y: [f64; 2] = [-0.2, 0.44];

/// A rectangle of constant radiance L, facing a pinhole camera at the origin 1 m away in the
/// plane z = −1, and nothing else, seen by a 90° camera of SIDE × SIDE pixels. With tan 45° = 1
/// the camera's ray through pixel coordinates (px, py) meets that plane at
/// X = 2 px/SIDE − 1, Y = 1 − 2 py/SIDE, so the rectangle covers the pixel-coordinate box
/// SIDE/2 (1 + X) × SIDE/2 (1 − Y), and pixel (i, j) — the mean over its area of L or 0 under
/// the box filter — is exactly L × (the fraction of the pixel inside that box). The edge pixels
/// are partly covered (their samples are L or 0), the others have no variance at all.
fn emitter(integrator: &str) -> String {
    format!(
        r#"{view}
[integrator]
photons = 1000
spp = 4
{integrator}

[[light]]
type = "area"
shape = "quad"
origin = [{x0}, {y0}, -1.0]
u = [{dx}, 0.0, 0.0]
v = [0.0, {dy}, 0.0]
spectrum = 1.0
scale = {L}
"#,
        x0 = X[0],
        y0 = Y[0],
        dx = X[1] - X[0],
        dy = Y[1] - Y[0],
        view = pinhole_90(SIDE),
    )
}

/// The exact value of pixel (i, j) of [`emitter`].
fn exact(i: usize, j: usize) -> f64 {
    let h = SIDE as f64 / 2.0;
    let overlap = |a: f64, b: f64, lo: f64| (b.min(lo + 1.0) - a.max(lo)).max(0.0);
    let ox = overlap(h * (1.0 + X[0]), h * (1.0 + X[1]), i as f64);
    let oy = overlap(h * (1.0 - Y[1]), h * (1.0 - Y[0]), j as f64);
    L * ox * oy
}

/// Sum over pixels of (value − exact)².
fn squared_error(data: &[f32]) -> f64 {
    (0..SIDE * SIDE).map(|p| (f64::from(data[p]) - exact(p % SIDE, p / SIDE)).powi(2)).sum()
}

#[test]
fn adaptive_passes_average_to_the_exact_coverage_within_their_standard_errors() {
    let r = render_with(&scene(&emitter("passes = 16\nadaptive = true\nseed = 11")), 2);
    let se = r.std_error.as_ref().expect("16 passes have standard errors");
    let (mut inside, mut partial) = (0usize, 0usize);
    let (mut diff, mut var) = (0.0f64, 0.0f64);
    for (p, (v, s)) in r.image.data.iter().zip(se).enumerate() {
        let (v, s, e) = (f64::from(*v), f64::from(*s), exact(p % SIDE, p / SIDE));
        diff += v - e;
        var += s * s;
        if e == 0.0 || e == L {
            // Every sample of the pixel is 0 or L: so is every pass, and the spread is zero.
            assert!((v - e).abs() <= 1e-6 * L && s == 0.0, "pixel {p}: {v} ± {s}, exact {e}");
            continue;
        }
        partial += 1;
        // Student's t with 15 degrees of freedom: P(|t| > 5) = 1.6e-4 per pixel.
        assert!((v - e).abs() <= 5.0 * s, "pixel {p}: {v} ± {s}, exact {e}");
        // The two-sided 95 % point of t with 15 degrees of freedom is 2.131.
        if (v - e).abs() <= 2.131 * s {
            inside += 1;
        }
    }
    // The whole image's sum: its passes are independent, so its variance is the sum of the
    // pixels' (their errors are uncorrelated within a pass too: separate sample streams).
    assert!(diff.abs() <= 4.0 * var.sqrt(), "image sum off by {diff} ± {}", var.sqrt());
    // ~45 edge pixels, each within its 95 % interval with probability 0.95: at least 80 % is
    // 3.3 binomial standard deviations below the expected 95 %.
    let covered = inside as f64 / partial as f64;
    assert!(partial > 40 && covered >= 0.8, "{inside} of {partial} edge pixels within their 95 % interval");
    let a = r.stats.progressive.adaptive.as_ref().expect("report.json says adaptive sampling was on");
    assert_eq!(a.samples_per_pass, (4 * SIDE * SIDE) as u64);
    assert!(a.last_pass_samples.abs_diff(a.samples_per_pass) <= 1, "{a:?}");
    assert!(a.last_pass_most_pixel_samples >= 16 && a.last_pass_pixels_at_one as usize > SIDE * SIDE / 2, "{a:?}");
}

#[test]
fn adaptive_passes_take_the_squared_error_out_of_the_edges_at_equal_samples() {
    // The same 16 passes of 4 samples per pixel, uniform and adaptive, over 6 seeds: against
    // the exact image, the adaptive images' squared error is a fraction of the uniform ones'.
    // Expected: a pixel covered to a fraction f has a sample variance L² f(1 − f), so with
    // independent sample positions the uniform error would be Σ_p L² f(1 − f)/64 = 4.26 a seed
    // (Σ_p f(1 − f) = 5.56 here). The scrambled Sobol' positions stratify a pass's 4 samples
    // along each axis, which this rectangle's edges follow: measured 1.06 a seed uniform.
    // Adaptive passes 2–16 give the ~144 pixels on and beside the edges ~22 samples each (the
    // other 880 one): measured 0.27 of the uniform error.
    let (mut u, mut a) = (0.0, 0.0);
    let (mut u_rays, mut a_rays) = (0, 0);
    for seed in 1..=6 {
        let uniform = render_with(&scene(&emitter(&format!("passes = 16\nseed = {seed}"))), 2);
        let adaptive = render_with(&scene(&emitter(&format!("passes = 16\nadaptive = true\nseed = {seed}"))), 2);
        assert!(uniform.stats.progressive.adaptive.is_none());
        u += squared_error(&uniform.image.data);
        a += squared_error(&adaptive.image.data);
        u_rays += uniform.stats.rays.eye;
        a_rays += adaptive.stats.rays.eye;
    }
    assert!(a < 0.4 * u, "squared error over 6 seeds: adaptive {a}, uniform {u}");
    assert!(a_rays.abs_diff(u_rays) * 1000 <= u_rays, "eye rays: adaptive {a_rays}, uniform {u_rays}");
}

#[test]
fn adaptive_output_does_not_depend_on_the_thread_count() {
    let text = lit_plate(16, 12, "").replace("spp = 1", "spp = 2\npasses = 3\nadaptive = true");
    let s = scene(&text);
    let (a, b) = (render_with(&s, 1), render_with(&s, 2));
    assert_eq!(a.image.data, b.image.data);
    assert_eq!(a.std_error, b.std_error);
    let plain = render_with(&scene(&text.replace("adaptive = true", "")), 2);
    assert_ne!(a.image.data, plain.image.data, "the adaptive passes were uniform");
}

#[test]
fn a_bad_adaptive_value_is_refused_naming_the_key() {
    let e = scene_error(&emitter("adaptive = \"yes\""));
    assert!(e.contains("adaptive"), "{e}");
}

fn morgana() -> std::process::Command {
    std::process::Command::new(env!("CARGO_BIN_EXE_morgana"))
}

/// Renders quietly with `args`; returns the exit code and stderr.
fn run(args: &[&str]) -> (Option<i32>, String) {
    let o = morgana().args(args).arg("--quiet").output().expect("run morgana");
    (o.status.code(), String::from_utf8_lossy(&o.stderr).into_owned())
}

#[test]
fn a_resumed_adaptive_run_writes_the_bytes_of_an_uninterrupted_one() {
    let dir = std::env::temp_dir().join(format!("morgana-adaptive-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let path = dir.join("plate.toml");
    std::fs::write(&path, lit_plate(16, 12, "").replace("spp = 1", "spp = 2")).expect("scene");
    let (scene, whole, part) = (path.display().to_string(), dir.join("whole"), dir.join("part"));
    let (whole_s, part_s) = (whole.display().to_string(), part.display().to_string());
    let (code, err) = run(&["render", &scene, "--adaptive", "--out", &whole_s]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("--adaptive"), "{err}");
    let keyed = dir.join("keyed.toml");
    std::fs::write(&keyed, lit_plate(16, 12, "").replace("spp = 1", "spp = 2\nadaptive = true")).expect("scene");
    let (code, err) = run(&["render", &keyed.display().to_string(), "--out", &whole_s]);
    assert_eq!(code, Some(2), "{err}");
    assert!(err.contains("[integrator] adaptive") && err.contains("one pass"), "{err}");
    let (code, err) = run(&["render", &scene, "--adaptive", "--passes", "4", "--threads", "2", "--out", &whole_s]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = run(&["render", &scene, "--adaptive", "--passes", "2", "--threads", "2", "--out", &part_s]);
    assert_eq!(code, Some(0), "{err}");
    let (code, err) = run(&["render", &scene, "--passes", "4", "--resume", &part_s]);
    assert_eq!(code, Some(2), "a resume without --adaptive from an adaptive checkpoint: {err}");
    assert!(err.contains("adaptive"), "{err}");
    let (code, err) = run(&["render", &scene, "--adaptive", "--passes", "4", "--threads", "1", "--resume", &part_s]);
    assert_eq!(code, Some(0), "{err}");
    let report: serde_json::Value =
        serde_json::from_slice(&std::fs::read(part.join("report.json")).expect("report")).expect("json");
    assert!(report["progressive"]["adaptive"]["samples_per_pass"].as_u64() == Some(2 * 16 * 12), "{report}");
    assert!(report["effects"]["progressive_passes"]["why"].as_str().is_some_and(|w| w.contains("adaptive")));
    for f in ["plate.exr", "plate.png"] {
        let (a, b) = (std::fs::read(whole.join(f)).expect(f), std::fs::read(part.join(f)).expect(f));
        assert!(a == b, "{f} differs between the uninterrupted and the resumed run");
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// The volume-caustic scene of the Mitsuba benchmark (`benches/scenes/volume_caustic.toml`: a
/// small square light in a snoot above a glass sphere in fog, whose glints — the light seen
/// through and in the sphere — hold most of the image's error) at 64 × 64 pixels, with
/// `integrator` as its `[integrator]` table.
fn glint_scene(integrator: &str) -> morgana::scene::Scene {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("benches/scenes/volume_caustic.toml");
    let text = std::fs::read_to_string(&path).expect("the benchmark scene");
    let (start, end) = (text.find("\n[integrator]").expect("[integrator]"), text.find("\n[world]").expect("[world]"));
    let text = format!("{}\n[integrator]\n{integrator}\n{}", &text[..start], &text[end..])
        .replace("width = 128", "width = 64")
        .replace("height = 128", "height = 64");
    scene(&text)
}

/// Renders the glint scene with `passes`, `spp`, `seed` and `extra` keys, on 2 threads.
fn glint(passes: u32, spp: u32, seed: u64, extra: &str) -> morgana::render::Rendered {
    let keys = format!(
        "photons = 100000\ncaustic_photons = 50000\nvolume_k = 50\nmarch_step = 0.1\ngather_rays = 4\nspp = {spp}\npasses = {passes}\nseed = {seed}\n{extra}"
    );
    render_with(&glint_scene(&keys), 2)
}

/// Passes of the glint scene's reference.
const REF_PASSES: u32 = 64;

/// The measurement behind the book's adaptive-sampling paragraph (`scripts/bench_adaptive.sh`
/// runs it and prints what it finds): on the glint scene, 16 passes of 4 samples per pixel,
/// uniform and adaptive (the same seed: the same photon maps), against a reference of 64
/// adaptive passes of 8 samples per pixel (another seed; adaptive passes are unbiased, tested
/// above, and with stratified sample positions 32 uniform passes of 8 were noisier than the
/// adaptive image measured: 0.45 of the mean against its raw 0.40). RMSE over every pixel and
/// band, relative to the reference's image mean, with the reference's own noise removed in
/// quadrature (RMSE² − mean SE²_ref, unbiased in the square, as `scripts/peer_mitsuba.py` does).
/// About 8 CPU minutes. It asserts only that adaptive is below uniform: one run's ratio has the
/// noise of a few dozen glint pixels.
#[test]
#[ignore = "slow (about 8 CPU minutes): ./scripts/bench_adaptive.sh runs it"]
fn adaptive_sampling_lowers_the_glint_scenes_rmse_at_equal_samples() {
    let t = std::time::Instant::now();
    let reference = glint(REF_PASSES, 8, 1000, "adaptive = true");
    let ref_s = t.elapsed().as_secs_f64();
    let ref_se = reference.std_error.as_ref().expect("the reference's passes have standard errors");
    let n = reference.image.data.len() as f64;
    let ref_mean = reference.image.data.iter().map(|v| f64::from(*v)).sum::<f64>() / n;
    let ref_var = ref_se.iter().map(|s| f64::from(*s).powi(2)).sum::<f64>() / n;
    let rmse = |data: &[f32]| -> (f64, f64) {
        let mse = data.iter().zip(&reference.image.data).map(|(a, b)| f64::from(a - b).powi(2)).sum::<f64>() / n;
        ((mse - ref_var).max(0.0).sqrt() / ref_mean, mse.sqrt() / ref_mean)
    };
    let mut rows = Vec::new();
    for (name, extra) in [("uniform", ""), ("adaptive", "adaptive = true")] {
        let t = std::time::Instant::now();
        let r = glint(16, 4, 1, extra);
        let (e, raw) = rmse(&r.image.data);
        // The squared error's share in the 1 % of pixels where it is largest.
        let nb = r.image.bands.count;
        let mut per_pixel: Vec<f64> = r
            .image
            .data
            .chunks(nb)
            .zip(reference.image.data.chunks(nb))
            .map(|(a, b)| a.iter().zip(b).map(|(x, y)| f64::from(x - y).powi(2)).sum())
            .collect();
        per_pixel.sort_by(|a, b| b.total_cmp(a));
        let top = per_pixel[..per_pixel.len().div_ceil(100)].iter().sum::<f64>() / per_pixel.iter().sum::<f64>();
        let wall = t.elapsed().as_secs_f64();
        println!(
            "{name:>8}: relative RMSE {e:.4} (raw {raw:.4}), top 1 % of pixels hold {:.0} % of the squared error, {} eye rays, {wall:.1} s",
            100.0 * top,
            r.stats.rays.eye
        );
        rows.push(e);
    }
    println!(
        "reference: {REF_PASSES} adaptive passes × 8 spp in {ref_s:.1} s, its noise RMSE {:.4} of its mean; adaptive/uniform RMSE ratio {:.3}",
        ref_var.sqrt() / ref_mean,
        rows[1] / rows[0]
    );
    assert!(rows[1] < rows[0], "adaptive {} is not below uniform {}", rows[1], rows[0]);
}
