//! The ocean: the sea-water medium against its published formulas, the profile sensor against a
//! closed form and the path tracer, and the Mobley et al. (1993) canonical problems.

mod common;
mod ocean_reference;

use common::{mean_and_sem, render_with, scene};
use morgana::sensor::ProfileReading;
use std::path::PathBuf;

/// The folder of morgana's built-in ocean tables (embedded in the binary; read here as files).
fn ocean_data() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("src/media/ocean/data")
}

/// A value of a two-column table, linear between rows (the test's own reader).
fn table(name: &str, lambda: f64) -> f64 {
    let text = std::fs::read_to_string(ocean_data().join(name)).unwrap();
    let rows: Vec<(f64, f64)> = text
        .lines()
        .filter(|l| !l.starts_with('#'))
        .filter_map(|l| {
            let mut c = l.split(',');
            Some((c.next()?.trim().parse().ok()?, c.next()?.trim().parse().ok()?))
        })
        .collect();
    let j = rows.windows(2).position(|w| (w[0].0..=w[1].0).contains(&lambda)).unwrap();
    let ((x0, a), (x1, b)) = (rows[j], rows[j + 1]);
    a + (b - a) * (lambda - x0) / (x1 - x0)
}

/// Bricaud's four coefficients at λ (a row of the table: the test uses tabulated wavelengths).
fn bricaud(lambda: f64) -> [f64; 4] {
    let text =
        std::fs::read_to_string(ocean_data().join("bricaud_1998_particle_phytoplankton_absorption.csv")).unwrap();
    for l in text.lines().filter(|l| !l.starts_with('#')) {
        let v: Vec<f64> = l.split(',').filter_map(|c| c.trim().parse().ok()).collect();
        if v.len() == 5 && v[0] == lambda {
            return [v[1], v[2], v[3], v[4]];
        }
    }
    panic!("no Bricaud row at {lambda}");
}

const OCEAN_SCENE: &str = r#"
[camera]
position = [0.0, 5.0, 0.0]
look_at = [0.0, 10.0, 0.0]
up = [1.0, 0.0, 0.0]
width = 1
height = 1
fov_deg = 10.0

[output]
bands = 30
min_nm = 400.0
max_nm = 700.0

[[medium]]
name = "sea"
type = "ocean"
chl_mg_m3 = 2.0
cdom_a440_per_m = 0.1
DATA

[[material]]
name = "surface"
type = "dielectric"
ior = "seawater"

[[shape]]
type = "box"
min = [-10.0, -10.0, -10.0]
max = [10.0, 0.0, 10.0]
material = "surface"
interior = "sea"

[[light]]
type = "directional"
direction = [0.0, -1.0, 0.0]
spectrum = "D65"
irradiance_w_m2 = 100.0
"#;

/// The ocean scene with morgana's built-in tables (no data_dir).
fn ocean_scene(extra: &str) -> String {
    OCEAN_SCENE.replace("DATA", extra)
}

#[test]
fn sea_water_has_the_published_coefficients() {
    let s = scene(&ocean_scene(""));
    assert!(s.plan.inelastic_scattering.on);
    let why = &s.plan.inelastic_scattering.why;
    for c in ["chlorophyll fluorescence", "CDOM fluorescence", "Raman"] {
        assert!(why.contains(c), "plan does not name {c}: {why}");
    }
    let m = &s.world.media[0];
    let chl: f64 = 2.0;
    for l in [440.0, 550.0, 600.0] {
        let [ap, ep, aphi, ephi] = bricaud(l);
        let a_w = table("pope_fry_1997_water_absorption.csv", l);
        let a_p = ap * chl.powf(ep);
        let a_phi = aphi * chl.powf(ephi);
        let a_y = 0.1 * (-0.014 * (l - 440.0)).exp();
        let b_w = 0.0029 * (l / 500.0f64).powf(-4.32);
        let b_p = 0.30 * chl.powf(0.62) * 550.0 / l;
        let b_r = 2.7e-4 * (488.0 / l).powf(5.3);
        let sigma_t = a_w + a_p + a_y + b_w + b_p + b_r;
        assert!((m.sigma_t(l) / sigma_t - 1.0).abs() < 1e-9, "σ_t({l}) = {} vs {sigma_t}", m.sigma_t(l));
        assert!((m.sigma_s(l) / (b_w + b_p) - 1.0).abs() < 1e-9, "σ_s({l})");
        let fl = &m.inelastic.components;
        assert!((fl[0].coefficient(l) / a_phi - 1.0).abs() < 1e-9 && (fl[1].coefficient(l) / a_y - 1.0).abs() < 1e-9);
    }
    // Outside Pope & Fry's range the Smith & Baker table takes over (e.g. 730 nm is past 727.5).
    let s2 = scene(&ocean_scene("").replace("max_nm = 700.0", "max_nm = 750.0"));
    let a730 =
        s2.world.media[0].sigma_t(730.0) - s2.world.media[0].sigma_s(730.0) - s2.world.media[0].inelastic.sigma(730.0);
    let want = table("smith_baker_1981_water_absorption.csv", 730.0) + {
        let [ap, ep, aphi, ephi] = bricaud(700.0);
        ap * chl.powf(ep) - aphi * chl.powf(ephi)
    };
    assert!((a730 / want - 1.0).abs() < 1e-9, "a(730) = {a730} vs {want}");
}

#[test]
fn a_data_dir_of_ones_own_tables_replaces_the_built_in_ones() {
    // The same tables as files give the same medium; one changed value changes it.
    let dir = std::env::temp_dir().join(format!("morgana_ocean_tables_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    for (name, text) in morgana::media::ocean::builtin::TABLES {
        std::fs::write(dir.join(name), text).unwrap();
    }
    let with_dir = |extra: &str| scene(&ocean_scene(&format!("data_dir = \"{}\"\n{extra}", dir.display())));
    let (built_in, own) = (scene(&ocean_scene("")), with_dir(""));
    for l in [412.0, 500.0, 650.0] {
        assert_eq!(built_in.world.media[0].sigma_t(l), own.world.media[0].sigma_t(l), "σ_t({l})");
    }
    let pf = morgana::media::ocean::builtin::POPE_FRY_FILE;
    let text = std::fs::read_to_string(dir.join(pf)).unwrap().replace("500,0.0204", "500,0.0304");
    std::fs::write(dir.join(pf), text).unwrap();
    let changed = with_dir("");
    let d = changed.world.media[0].sigma_t(500.0) - built_in.world.media[0].sigma_t(500.0);
    assert!((d - 0.01).abs() < 1e-12, "a_w(500) raised by {d}");
    // A folder without one of the tables names the file and the way back to the built-in ones.
    std::fs::remove_file(dir.join(morgana::media::ocean::builtin::BRICAUD_FILE)).unwrap();
    let e = common::scene_error(&ocean_scene(&format!("data_dir = \"{}\"", dir.display())));
    assert!(e.contains("test.toml:") && e.contains("bricaud_1998") && e.contains("remove data_dir"), "{e}");
    std::fs::remove_dir_all(&dir).unwrap();
}

#[test]
fn a_missing_ocean_data_folder_is_a_clear_error() {
    let toml = OCEAN_SCENE.replace("DATA", "data_dir = \"no/such/folder\"");
    let e = common::scene_error(&toml);
    assert!(e.contains("test.toml:") && e.contains("no/such/folder") && e.contains("not a folder"), "{e}");
    assert!(e.contains("remove data_dir to use morgana's built-in ocean tables"), "{e}");
    let e = common::scene_error(&OCEAN_SCENE.replace("DATA", "chl_mg_m3 = -1.0"));
    assert!(e.contains("chl_mg_m3") || e.contains("duplicate"), "{e}");
}

/// The profile of a purely absorbing ocean (c = a = 0.5 m⁻¹, n = 1.34) under a sun at 60°: the
/// refracted beam alone, Ed(z) = Ed(0+) T(60°) e^{−c z/μ_w} with T the Fresnel transmittance,
/// μ_w the cosine of the refracted angle, Eod = Ed/μ_w, and nothing upwelling.
#[test]
fn profile_sensor_matches_the_refracted_beam_in_absorbing_water() {
    let base = std::fs::read_to_string("examples/mobley1993_problem1.toml").unwrap();
    let toml = base.replace("albedo = 0.9", "albedo = 0.0").replace("sigma_t = 1.0", "sigma_t = 0.5");
    let mut s = scene(&toml);
    s.apply_overrides(Some(200_000), None);
    let r = render_with(&s, 2);
    let p = &r.profiles[0];
    let (n, cos_i) = (1.34f64, 0.5f64);
    let sin_t = (1.0 - cos_i * cos_i).sqrt() / n;
    let cos_t = (1.0 - sin_t * sin_t).sqrt();
    let rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    let rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    let t = 1.0 - 0.5 * (rs * rs + rp * rp);
    for row in &p.rows {
        let ed = 0.5 * t * (-0.5 * row.depth_m / cos_t).exp();
        // Photons in a slab: binomial counts; at 200k photons over 120²/200² of the beam and a
        // slab holding ~ 0.5·0.2/μ_w of those still travelling, 4σ is about 3% at z = 10 m.
        let tol = 4.0 * (1.0 / (200_000.0 * 0.36 * 0.1 / cos_t * (-0.5 * row.depth_m / cos_t).exp())).sqrt();
        assert!((row.ed / ed - 1.0).abs() < tol, "z = {}: Ed {} vs {ed} (tol {tol})", row.depth_m, row.ed);
        // Stored directions are octahedral-coded to 0.005° (src/photon_map/photon.rs): μ to 1e-4.
        assert!((row.eod * cos_t / row.ed - 1.0).abs() < 1e-4, "Eod = Ed/μ_w: {}", row.eod * cos_t / row.ed);
        assert!(row.eu == 0.0 && row.eou == 0.0 && row.lu == 0.0);
    }
    // The sun direction is written to 7 digits: cos 60° to 1e-8.
    assert!((p.surface[0][1] - 0.5).abs() < 1e-8, "Ed(0+) = {}", p.surface[0][1]);
    let kd = p.kd();
    assert!((kd[0].3 - 0.5 / cos_t).abs() < 0.02, "Kd {} vs {}", kd[0].3, 0.5 / cos_t);
}

/// Issue 15: at depth 0 (or any depth less than half its slab) the profile averaged over the air
/// and the water and read half the irradiance. Clipped to the water, Ed just below the surface
/// continues Ed deeper down: the purely absorbing ocean above (Ed exactly exponential), 4 seeds,
/// Ed at 0.5, 1 and 2 m fitted by an exponential (log-linear least squares) and carried to the
/// clipped slabs at 0 and 0.05 m (their mean of the fit), within 4 standard errors of the
/// readings and of the extrapolation; and against the closed form Ed(0−) = Ed(0+) T(60°).
#[test]
fn profile_at_the_surface_is_continuous_with_the_profile_below() {
    let base = std::fs::read_to_string("examples/mobley1993_problem1.toml").unwrap();
    let toml = base
        .replace("albedo = 0.9", "albedo = 0.0")
        .replace("sigma_t = 1.0", "sigma_t = 0.5")
        .replace("depths_m = [1.0, 5.0, 10.0]", "depths_m = [0.0, 0.05, 0.5, 1.0, 2.0]");
    assert!(toml.contains("depths_m = [0.0, 0.05") && toml.contains("slab_m = 0.2"));
    let slab = 0.2;
    let runs: Vec<ProfileReading> = (1..=4)
        .map(|seed| {
            let mut s = scene(&toml);
            s.apply_overrides(Some(400_000), Some(seed));
            render_with(&s, 2).profiles.remove(0)
        })
        .collect();
    let ed = |z: f64| -> (f64, f64) {
        let v: Vec<f64> = runs.iter().map(|r| r.rows.iter().find(|x| x.depth_m == z).unwrap().ed).collect();
        mean_and_sem(&v)
    };
    // ln Ed = c0 − K z through the three deeper readings (each a slab mean; for an exponential
    // that is e^{−Kz} times the same factor S = sinh(KΔz/2)/(KΔz/2) at every depth).
    let zs = [0.5, 1.0, 2.0];
    let pts: Vec<(f64, f64, f64)> = zs.iter().map(|&z| (z, ed(z).0.ln(), ed(z).1 / ed(z).0)).collect();
    let zbar = zs.iter().sum::<f64>() / 3.0;
    let sxx: f64 = zs.iter().map(|z| (z - zbar).powi(2)).sum();
    let slope = pts.iter().map(|(z, y, _)| (z - zbar) * y).sum::<f64>() / sxx;
    let k = -slope;
    let ybar = pts.iter().map(|p| p.1).sum::<f64>() / 3.0;
    let c0 = ybar - slope * zbar;
    // Variance of c0 (a linear combination of the ln Ed, each with relative error sem/mean).
    let c0_var: f64 = pts.iter().map(|(z, _, rel)| (1.0 / 3.0 - zbar * (z - zbar) / sxx).powi(2) * rel * rel).sum();
    let x = k * slab / 2.0;
    let e0 = c0.exp() * x / x.sinh(); // Ed just below the surface, from the fit
    // Closed form: Ed(0+) = 0.5 and Fresnel's T at 60° into n = 1.34; K = c/μ_w.
    let (n, cos_i) = (1.34f64, 0.5f64);
    let cos_t = (1.0 - (1.0 - cos_i * cos_i) / (n * n)).sqrt();
    let rs = (cos_i - n * cos_t) / (cos_i + n * cos_t);
    let rp = (n * cos_i - cos_t) / (n * cos_i + cos_t);
    let ed0_closed = 0.5 * (1.0 - 0.5 * (rs * rs + rp * rp));
    eprintln!("fit: Ed(0−) = {e0:.5} (closed form {ed0_closed:.5}), K = {k:.4} (closed form {:.4})", 0.5 / cos_t);
    for z in [0.0, 0.05] {
        let (top, bottom) = (0.0f64.max(z - slab / 2.0), z + slab / 2.0);
        let slab_mean = |e0: f64, k: f64| e0 * ((-k * top).exp() - (-k * bottom).exp()) / (k * (bottom - top));
        let (got, sem) = ed(z);
        let want = slab_mean(e0, k);
        let tol = 4.0 * (sem * sem + want * want * c0_var).sqrt();
        eprintln!("Ed({z}) = {got:.5} ± {sem:.5}; the fit's mean over the clipped slab {want:.5} (tol {tol:.5})");
        assert!((got - want).abs() < tol, "Ed({z}) = {got} ± {sem}, continuing the profile below: {want}");
        let closed = slab_mean(ed0_closed, 0.5 / cos_t);
        assert!((got - closed).abs() < 4.0 * sem + 1e-3 * closed, "Ed({z}) = {got} ± {sem}, closed form {closed}");
    }
}

/// Mobley et al. (1993) Table values at τ = 1 for problems 1 and 2 (Lu, Eou; W m⁻² (sr⁻¹) nm⁻¹,
/// Ed(0+) = 0.5), as quoted by a public validation script of another Monte Carlo code
/// (mc_solver_free, "Validation against Mobley et al. (1993)"); the paper's own tables were not
/// reachable from here.
const PUBLISHED: [(&str, u32, f64, f64, f64); 4] = [
    ("mobley1993_problem1.toml", 1, 0.9, 0.0485, 0.372),
    ("mobley1993_problem1.toml", 1, 0.2, 0.00172, 0.0134),
    ("mobley1993_problem2.toml", 2, 0.9, 0.00699, 0.0931),
    ("mobley1993_problem2.toml", 2, 0.2, 0.0000547, 0.000966),
];

/// An example scene with edits, resolving its relative paths against examples/.
fn example(file: &str, edit: &dyn Fn(String) -> String) -> morgana::scene::Scene {
    let base = std::fs::read_to_string(format!("examples/{file}")).unwrap();
    let path = std::path::Path::new("examples").join(file);
    match morgana::scene::load_scene_str(&edit(base), &path, std::path::Path::new("examples"), "test") {
        Ok(s) => s,
        Err(e) => panic!("{file}: {e}"),
    }
}

fn profile(file: &str, albedo: f64, photons: u64, seed: u64) -> ProfileReading {
    profile_with(file, &|t| t.replace("albedo = 0.9", &format!("albedo = {albedo}")), photons, seed)
}

fn profile_with(file: &str, edit: &dyn Fn(String) -> String, photons: u64, seed: u64) -> ProfileReading {
    let mut s = example(file, edit);
    s.apply_overrides(Some(photons), Some(seed));
    render_with(&s, 2).profiles.remove(0)
}

/// Lu and Eou at τ = 1 against the published values: the mean over 6 seeds within 3 standard
/// errors plus 2% of the published value (three significant digits, and the spread among the
/// published models). Slow: `cargo test --release --test ocean -- --ignored mobley`.
#[test]
#[ignore]
fn mobley1993_problems_1_and_2_at_tau_1() {
    for (file, problem, albedo, lu_ref, eou_ref) in PUBLISHED {
        if problem == 2 && albedo == 0.2 {
            continue; // Lu = 5.5e-5 needs ~10⁹ photons for a 3% error; see README.
        }
        let runs: Vec<ProfileReading> = (1..=6).map(|seed| profile(file, albedo, 1_500_000, seed)).collect();
        let at = |f: &dyn Fn(&morgana::sensor::ProfileRow) -> f64| -> Vec<f64> {
            runs.iter().map(|r| f(r.rows.iter().find(|x| x.depth_m == 1.0).unwrap())).collect()
        };
        for (name, v, reference) in [("Lu", at(&|r| r.lu), lu_ref), ("Eou", at(&|r| r.eou), eou_ref)] {
            let (mean, sem) = mean_and_sem(&v);
            eprintln!("problem {problem} ω₀ = {albedo}: {name}(τ=1) = {mean:.5} ± {sem:.5}, published {reference}");
            assert!((mean - reference).abs() < 3.0 * sem + 0.02 * reference, "problem {problem} ω₀ {albedo} {name}");
        }
        // The deeper rows, printed for the record (no published values are reachable from here).
        for z in [1.0, 5.0, 10.0] {
            let row = |f: &dyn Fn(&morgana::sensor::ProfileRow) -> f64| -> (f64, f64) {
                mean_and_sem(
                    &runs.iter().map(|r| f(r.rows.iter().find(|x| x.depth_m == z).unwrap())).collect::<Vec<_>>(),
                )
            };
            let ((ed, ed_s), (eou, eou_s), (lu, lu_s)) = (row(&|r| r.ed), row(&|r| r.eou), row(&|r| r.lu));
            let ratio = mean_and_sem(
                &runs
                    .iter()
                    .map(|r| r.rows.iter().find(|x| x.depth_m == z).map(|x| x.lu / x.eou).unwrap())
                    .collect::<Vec<_>>(),
            );
            eprintln!(
                "problem {problem} ω₀ = {albedo}, τ = {z}: Ed {ed:.5} ± {ed_s:.5}, Eou {eou:.5} ± {eou_s:.5}, \
                 Lu {lu:.6} ± {lu_s:.6}, Lu/Eou {:.4} ± {:.4}",
                ratio.0, ratio.1
            );
        }
    }
}

/// The independent discrete-ordinates reference (tests/ocean_reference) for a problem: Petzold's
/// table read from the built-in CSV by the reference's own reader, or Rayleigh's 1 + cos²θ
/// tabulated every 0.5°.
fn reference(problem: u32, albedo: f64) -> ocean_reference::Solution {
    let phase = if problem == 1 {
        let rows: Vec<(f64, f64)> = (0..=360)
            .map(|i| if i == 0 { 0.05 } else { 0.5 * i as f64 })
            .map(|t: f64| (t, 1.0 + t.to_radians().cos().powi(2)))
            .collect();
        ocean_reference::Phase::from_rows(&rows)
    } else {
        petzold_reference()
    };
    ocean_reference::solve(&ocean_reference::Problem::mobley1993(albedo), &phase)
}

fn petzold_reference() -> ocean_reference::Phase {
    ocean_reference::Phase::from_csv(&ocean_data().join("petzold_average_particle_phase_function.csv"))
}

/// The reference solver against the published values at τ = 1 (each within 2 %: their three
/// digits and the spread among the published models, as for morgana above) and against Gershun's
/// law, d(Ed − Eu)/dτ = −(1 − ω₀) Eo (Mobley 1994, *Light and Water*; Simpson's rule over the nodes from
/// τ = 1 to 10, relative 1e-3), which its bookkeeping of the scattering matrix, the sun's beam and
/// the surface must keep. Excluded from the 2 %: problem 2's Lu at ω₀ = 0.9, which the reference
/// puts 2.8 % below the published 0.00699, as morgana does (−3.0 % over 20 seeds) — issue 15,
/// see docs/book/src/media.md. About 15 s (four solutions on two threads).
#[test]
fn the_discrete_ordinates_reference_reproduces_the_published_values() {
    // The reference's own reading of Petzold's table has the published moments (Mobley 1994:
    // mean cosine 0.924, backscatter fraction 0.0183).
    let (g, bb) = petzold_reference().moments();
    assert!((g - 0.924).abs() < 1e-3 && (bb - 0.0183).abs() < 3e-4, "mean cosine {g}, backscatter {bb}");
    let solutions: Vec<ocean_reference::Solution> = std::thread::scope(|scope| {
        let handles: Vec<_> = PUBLISHED.iter().map(|c| scope.spawn(move || reference(c.1, c.2))).collect();
        handles.into_iter().map(|h| h.join().unwrap()).collect()
    });
    for ((_, problem, albedo, lu_ref, eou_ref), s) in PUBLISHED.into_iter().zip(&solutions) {
        let r = s.at(1.0);
        eprintln!(
            "problem {problem} ω₀ = {albedo}: reference Lu(1) {:.6} ({:+.1} %), Eou(1) {:.6} ({:+.1} %), {} sweeps",
            r.lu,
            100.0 * (r.lu / lu_ref - 1.0),
            r.eou,
            100.0 * (r.eou / eou_ref - 1.0),
            s.sweeps
        );
        assert!((r.eou / eou_ref - 1.0).abs() < 0.02, "problem {problem} ω₀ {albedo}: Eou {} vs {eou_ref}", r.eou);
        if !(problem == 2 && albedo == 0.9) {
            assert!((r.lu / lu_ref - 1.0).abs() < 0.02, "problem {problem} ω₀ {albedo}: Lu {} vs {lu_ref}", r.lu);
        }
        let net = |tau: f64| s.at(tau).ed - s.at(tau).eu;
        let eo = |tau: f64| s.at(tau).eod + s.at(tau).eou;
        let h = 0.1;
        let simpson: f64 = (0..45)
            .map(|k| 1.0 + 2.0 * h * k as f64)
            .map(|t| h / 3.0 * (eo(t) + 4.0 * eo(t + h) + eo(t + 2.0 * h)))
            .sum();
        let (lost, absorbed) = (net(1.0) - net(10.0), (1.0 - albedo) * simpson);
        assert!((lost / absorbed - 1.0).abs() < 1e-3, "Gershun: net flux lost {lost}, absorbed {absorbed}");
    }
}

/// The reference's discretisation, and what moves its Lu/Eou at depth (issue 15). Problem 2,
/// ω₀ = 0.9, at τ = 1, 5, 10: doubling the direction bins, halving Δτ or doubling the points per
/// input bin changes Ed, Eou and Lu by less than 0.5 % (the allowance in the comparison with
/// morgana below). Then two changes of the problem that are choices of a model rather than
/// physics: no internal reflection at the surface, and no scattering below Petzold's first angle
/// (the 5 % of the table's mass that morgana and the reference extrapolate below 0.1°, dropped
/// and the rest renormalised); neither brings Lu/Eou at τ = 5 to the 0.070 that issue 15 quotes
/// for the published models. About 2 minutes:
/// `cargo test --release --test ocean -- --ignored --nocapture reference_convergence`.
#[test]
#[ignore]
fn discrete_ordinates_reference_convergence_and_sensitivity() {
    use ocean_reference::{Phase, Problem, Solution, solve};
    let rows = Phase::csv_rows(&ocean_data().join("petzold_average_particle_phase_function.csv"));
    let petzold = Phase::from_rows(&rows);
    let base = Problem::mobley1993(0.9);
    let show = |what: &str, s: &Solution| {
        let r: Vec<String> = [1.0, 5.0, 10.0, 20.0]
            .iter()
            .map(|&t| {
                let r = s.at(t);
                format!("τ {t}: Ed {:.5} Eou {:.6} Lu {:.7} Lu/Eou {:.4}", r.ed, r.eou, r.lu, r.lu / r.eou)
            })
            .collect();
        eprintln!("{what}:\n  {}", r.join("\n  "));
    };
    let used = solve(&base, &petzold);
    show("as used (90 bins, Δτ 0.05, 8 points per bin)", &used);
    let finer = [
        ("180 bins", Problem { bins: 180, ..base }),
        ("Δτ 0.025", Problem { dtau: 0.025, ..base }),
        ("16 points per bin", Problem { mu_points: 16, ..base }),
    ];
    for (what, pb) in finer {
        let s = solve(&pb, &petzold);
        show(what, &s);
        for t in [1.0, 5.0, 10.0] {
            let (a, b) = (used.at(t), s.at(t));
            for (name, x, y) in [("Ed", a.ed, b.ed), ("Eou", a.eou, b.eou), ("Lu", a.lu, b.lu)] {
                assert!((x / y - 1.0).abs() < 0.005, "{what}: {name}({t}) {y} against {x} as used");
            }
        }
    }
    let variants = [
        ("no surface reflection", solve(&Problem { surface_reflection: false, ..base }, &petzold)),
        ("nothing below 0.1°", solve(&base, &Phase::with_forward(&rows, false))),
    ];
    for (what, s) in &variants {
        show(what, s);
        let r = s.at(5.0);
        assert!(r.lu / r.eou < 0.070, "{what}: Lu/Eou(5) = {}", r.lu / r.eou);
    }
}

/// morgana's profile against the independent discrete-ordinates reference at τ = 1, 5 and 10
/// (issue 15: Lu/Eou at depth under Petzold's phase function): problem 1 (Rayleigh, ω₀ = 0.9) and
/// problem 2 (Petzold, ω₀ = 0.9) with their refracting surfaces and sun, Ed, Eou and Lu each within
/// 3 standard errors of the mean over seeds + 1 % (the reference's discretisation is below 0.3 %,
/// the profile's 0.2 m slab and the 5° and 2° cones about the nadir below 0.3 %); problem 2 at
/// ω₀ = 0.2 at τ = 1 (upwelling light is 10⁻³ of the downwelling there, deeper it is noise).
/// The profile's Lu under Petzold's forward peak is skewed over seeds (media.md), hence 20 seeds
/// for problem 2, and 12 for the others (a standard error from 4 seeds is itself uncertain by
/// 40 %). Slow (about 25 minutes on the loaded 2-core machine):
/// `cargo test --release --test ocean -- --ignored --nocapture profile_matches_the_discrete`.
#[test]
#[ignore]
fn profile_matches_the_discrete_ordinates_reference() {
    // (problem, file, albedo, depths, seeds, photons per seed)
    type Case<'a> = (u32, &'a str, f64, &'a [f64], u64, u64);
    type Quantity = (&'static str, fn(&morgana::sensor::ProfileRow) -> f64, f64);
    let cases: [Case; 3] = [
        (1, "mobley1993_problem1.toml", 0.9, &[1.0, 5.0, 10.0], 12, 1_500_000),
        (2, "mobley1993_problem2.toml", 0.9, &[1.0, 5.0, 10.0], 20, 2_000_000),
        (2, "mobley1993_problem2.toml", 0.2, &[1.0], 12, 2_000_000),
    ];
    let mut failures = Vec::new();
    for (problem, file, albedo, depths, seeds, photons) in cases {
        let reference = reference(problem, albedo);
        let runs: Vec<ProfileReading> = (1..=seeds).map(|seed| profile(file, albedo, photons, seed)).collect();
        for &z in depths {
            let want = reference.at(z);
            let rows: Vec<morgana::sensor::ProfileRow> =
                runs.iter().map(|r| *r.rows.iter().find(|x| x.depth_m == z).unwrap()).collect();
            let quantities: [Quantity; 3] =
                [("Ed", |r| r.ed, want.ed), ("Eou", |r| r.eou, want.eou), ("Lu", |r| r.lu, want.lu)];
            let ratio = mean_and_sem(&rows.iter().map(|r| r.lu / r.eou).collect::<Vec<_>>());
            eprintln!(
                "problem {problem} ω₀ = {albedo}, τ = {z}: Lu/Eou {:.4} ± {:.4}, reference {:.4}",
                ratio.0,
                ratio.1,
                want.lu / want.eou
            );
            for (name, f, reference) in quantities {
                let (mean, sem) = mean_and_sem(&rows.iter().map(f).collect::<Vec<_>>());
                eprintln!(
                    "  {name}: profile {mean:.6} ± {sem:.6}, reference {reference:.6} ({:+.2} %)",
                    100.0 * (mean / reference - 1.0)
                );
                if (mean - reference).abs() >= 3.0 * sem + 0.01 * reference {
                    failures.push(format!("problem {problem} ω₀ {albedo} {name}({z}): {mean} ± {sem} vs {reference}"));
                }
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

/// The profile's Lu (the expected value of upward scattering over the collisions below z)
/// against the path tracer: a camera at depth z looking straight down sees the upwelling
/// radiance Lu(z), averaged over its 2° field of view (the upwelling light field is smooth about
/// the nadir-viewing direction, so the 2° of the camera and the 5° cone of the profile average
/// alike).
///
/// Problem 1 (Rayleigh) at τ = 1 and 5 under its sun with the surface index-matched, because
/// the path tracer reaches a delta light only by shadow rays, which do not refract. Problem 2
/// (Petzold's forward-peaked phase function, ω₀ = 0.9) at τ = 1, 5 and 10, where upwelling
/// light is mostly carried up by small-angle scattering of light already travelling up, under a
/// uniform sky instead of its sun: next-event estimation toward a delta sun meets Petzold's
/// forward peak (p reaches 2·10⁷ sr⁻¹) and its variance has no useful bound, while a sky is
/// reached with multiple importance sampling. Problem 2 is run twice: index-matched, and with
/// its refracting surface (the path tracer then sees the sky only through the refracting
/// surface). Both sides are means over seeds; |profile − path tracer| < 3 combined standard
/// errors + 3 % of the path tracer. Slow (about 15 minutes on 2 cores):
/// `cargo test --release --test ocean -- --ignored --nocapture path_tracer`.
#[test]
#[ignore]
fn profile_lu_agrees_with_the_path_tracer() {
    let matched = |t: String| t.replace("material = \"surface\"\ninterior", "interior");
    let sky = |t: String| {
        let sun = "type = \"directional\"\ndirection = [0.8660254, -0.5, 0.0]\n";
        assert!(t.contains(sun));
        t.replace(sun, "type = \"sky\"\n")
    };
    let matched_sky = |t: String| sky(matched(t));
    // (file, what, edit, depths, profile seeds, photons per seed)
    type Case<'a> = (&'a str, &'a str, &'a dyn Fn(String) -> String, &'a [f64], u64, u64);
    let cases: [Case; 3] = [
        ("mobley1993_problem1.toml", "index-matched, sun", &matched, &[1.0, 5.0], 4, 1_500_000),
        ("mobley1993_problem2.toml", "index-matched, sky", &matched_sky, &[1.0, 5.0, 10.0], 8, 2_000_000),
        ("mobley1993_problem2.toml", "refracting, sky", &sky, &[1.0, 5.0, 10.0], 8, 2_000_000),
    ];
    let mut failures = Vec::new();
    for (file, what, edit, depths, seeds, photons) in cases {
        let runs: Vec<ProfileReading> = (1..=seeds).map(|seed| profile_with(file, edit, photons, seed)).collect();
        for &z in depths {
            let row = |r: &ProfileReading| *r.rows.iter().find(|x| x.depth_m == z).unwrap();
            let (lu, sem) = mean_and_sem(&runs.iter().map(|r| row(r).lu).collect::<Vec<_>>());
            let (eou, _) = mean_and_sem(&runs.iter().map(|r| row(r).eou).collect::<Vec<_>>());
            let pt: Vec<f64> = (1..=4)
                .map(|seed| {
                    let mut s = example(file, &|t| {
                        edit(t)
                            .replace(
                                "position = [0.0, 5.0, 0.0]\nlook_at = [0.0, 10.0, 0.0]",
                                &format!("position = [0.0, {}, 0.0]\nlook_at = [0.0, -100.0, 0.0]", -z),
                            )
                            .replace("fov_deg = 10.0", "fov_deg = 2.0")
                            .replace("photons = 1000000\nspp = 1", "method = \"path\"\nspp = 100000")
                    });
                    s.apply_overrides(None, Some(seed));
                    render_with(&s, 2).image.data[0] as f64
                })
                .collect();
            let (pt, pt_sem) = mean_and_sem(&pt);
            let tol = 3.0 * (sem * sem + pt_sem * pt_sem).sqrt() + 0.03 * pt;
            eprintln!(
                "{file} ({what}) Lu({z}): profile {lu:.6} ± {sem:.6}, path tracer {pt:.6} ± {pt_sem:.6} \
                 ({:+.1} %); Lu/Eou {:.4} and {:.4}",
                100.0 * (lu / pt - 1.0),
                lu / eou,
                pt / eou
            );
            if (lu - pt).abs() >= tol {
                failures.push(format!("{file} ({what}) Lu({z}): profile {lu} ± {sem}, path tracer {pt} ± {pt_sem}"));
            }
        }
    }
    assert!(failures.is_empty(), "{failures:#?}");
}

#[test]
fn the_ocean_and_inelastic_examples_load_and_say_what_they_show() {
    let files = [
        ("mobley1993_problem1.toml", false),
        ("mobley1993_problem2.toml", false),
        ("mobley1993_problem7.toml", true),
        ("lucifer_fig3_ocean_box.toml", true),
        ("chlorophyll_sweep.toml", true),
        ("diver_view.toml", true),
        ("fluorescent_glass_block.toml", true),
    ];
    for (f, inelastic) in files {
        let path = std::path::Path::new("examples").join(f);
        let text = std::fs::read_to_string(&path).unwrap();
        assert!(text.starts_with("# Shows:"), "{f} must start with a line saying what it shows");
        let s = morgana::scene::load_scene_file(&path).unwrap_or_else(|e| panic!("{f}: {e}"));
        assert_eq!(s.plan.inelastic_scattering.on, inelastic, "{f}: {}", s.plan.inelastic_scattering.why);
    }
}

#[test]
fn bad_inelastic_components_are_errors_at_their_line() {
    let base = |c: &str| {
        format!(
            "[camera]\nposition = [0.0, 0.0, 1.0]\nlook_at = [0.0, 0.0, 0.0]\nfov_deg = 30.0\nwidth = 1\nheight = 1\n\n[[medium]]\nname = \"m\"\nsigma_a = 0.1\nsigma_s = 0.0\ninelastic = [{c}]\n\n[[light]]\ntype = \"point\"\nposition = [0.0, 0.0, 0.0]\nspectrum = 1.0\npower_w = 1.0\n"
        )
    };
    for (component, want) in [
        (
            "{ process = \"fluorescence\", sigma_a = 1.0, emission = { type = \"gaussian\", peak_nm = 600, sigma_nm = 10 } }",
            "missing `yield`",
        ),
        (
            "{ process = \"fluorescence\", sigma_a = 1.0, yield = 1.5, emission = { type = \"gaussian\", peak_nm = 600, sigma_nm = 10 } }",
            "yield = 1.5",
        ),
        ("{ process = \"glow\", sigma_a = 1.0 }", "process must be"),
        ("{ process = \"raman\", sigma_s = 1e-4, colour = 2 }", "unknown key `colour`"),
        ("{ process = \"raman\", sigma_a = 1e-4 }", "`sigma_a` is not used"),
        (
            "{ process = \"fluorescence\", sigma_a = 1.0, yield = 0.1, emission = { type = \"gaussian\", peak_nm = 600, sigma_nm = -1 } }",
            "sigma_nm",
        ),
        ("{ process = \"raman\", sigma_s = 1e-4, accounting = \"joules\" }", "accounting must be"),
    ] {
        let e = common::scene_error(&base(component));
        assert!(e.contains("test.toml:12:") && e.contains(want), "{component}: {e}");
    }
    let e = common::scene_error(&base("").replace("inelastic = []\n", "chl_mg_m3 = 1.0\n"));
    assert!(e.contains("chl_mg_m3") && e.contains("type = \"ocean\""), "{e}");
}

/// The built-in tables are usable by name in any medium: `sigma_a = "pope_fry_1997"` is Pope &
/// Fry's table (read here from the CSV by the test's own reader) and `phase = "petzold"` is the
/// built-in average-particle phase function; a wrong name lists the right ones.
#[test]
fn builtin_tables_are_named_spectra_and_phase_functions() {
    let medium = |sigma_a: &str, phase: &str| {
        OCEAN_SCENE.replace(
            "type = \"ocean\"\nchl_mg_m3 = 2.0\ncdom_a440_per_m = 0.1\nDATA\n",
            &format!("sigma_a = {sigma_a}\nsigma_s = 0.1\nphase = {phase}\n"),
        )
    };
    let s = scene(&medium("\"pope_fry_1997\"", "\"petzold\""));
    let m = &s.world.media[0];
    for l in [400.0, 412.5, 551.0, 700.0] {
        let want = table("pope_fry_1997_water_absorption.csv", l) + 0.1;
        assert!((m.sigma_t(l) / want - 1.0).abs() < 1e-12, "σ_t({l}) = {} vs {want}", m.sigma_t(l));
    }
    let petzold = morgana::media::ocean::builtin::petzold();
    for mu in [1.0, 0.999, 0.9, 0.0, -1.0] {
        assert_eq!(m.phase.eval(500.0, mu), petzold.eval(500.0, mu), "p(μ = {mu})");
    }
    let e = common::scene_error(&medium("\"pope_fry\"", "\"petzold\""));
    assert!(e.contains("no spectrum named \"pope_fry\"") && e.contains("pope_fry_1997"), "{e}");
    let e = common::scene_error(&medium("0.01", "\"petzoldd\""));
    assert!(e.contains("petzoldd") && e.contains("petzold"), "{e}");
}

/// The fuzzer found a sea over 400–70,000 nm accepted (its absorption tables silently held at
/// their 800 nm value) and its inelastic table taking hours to build; the scene's range must now
/// lie within the water tables' 200–800 nm, and the refusal names the medium and the limits.
#[test]
fn a_sea_beyond_its_tables_wavelengths_is_refused() {
    common::scene(&ocean_scene("").replace("max_nm = 700.0", "max_nm = 800.0"));
    for (from, to) in [("max_nm = 700.0", "max_nm = 70000.0"), ("min_nm = 400.0", "min_nm = 150.0")] {
        let e = common::scene_error(&ocean_scene("").replace(from, to));
        assert!(e.contains("200–800 nm") && e.contains("min_nm and max_nm") && e.contains("test.toml:"), "{e}");
    }
}
