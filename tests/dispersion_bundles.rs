//! Dispersion bundles (`render::eye` bundles, issue 18): a camera path through air that bends
//! each wavelength differently traces four guide wavelengths and interpolates the other twelve.
//! The oracle is the same render with `dispersion_bundles = false`, every wavelength traced on
//! its own: the two must agree pixel by pixel to the tolerances the bundle's check holds its
//! fourth guide to, in smooth air (the setting sun over the sea) and through the duct of an
//! inversion (the green flash, where paths fold and the check must refuse what it cannot fit).

mod common;

use morgana::render::Rendered;
use morgana::scene::{Scene, load_scene_str};
use std::path::Path;

/// An example scene, shrunk to `width` × `height` pixels, without photons (its sea is black),
/// with `[integrator]` lines added.
fn example(name: &str, width: u32, height: u32, integrator: &str) -> Scene {
    let file = format!("examples/{name}.toml");
    let text = std::fs::read_to_string(&file).expect("the example");
    let text = regex_line(&text, "width", &width.to_string());
    let text = regex_line(&text, "height", &height.to_string());
    let text = regex_line(&text, "photons", "0");
    let text = text.replacen("[integrator]\n", &format!("[integrator]\n{integrator}\n"), 1);
    load_scene_str(&text, Path::new(&file), Path::new("examples"), name).expect("the shrunk example loads")
}

/// `text` with the first line `key = ...` set to `key = value`.
fn regex_line(text: &str, key: &str, value: &str) -> String {
    let start = text.find(&format!("\n{key} = ")).expect("the key") + 1;
    let end = start + text[start..].find('\n').expect("end of line");
    format!("{}{key} = {value}{}", &text[..start], &text[end..])
}

/// Counts of the rays report: (lanes interpolated, eye paths traced: guides, single lanes and
/// their continuations past the top of the air).
fn rays(r: &Rendered) -> (u64, u64) {
    (r.stats.rays.bundled, r.stats.rays.eye)
}

/// Compares two renders value by value: the largest relative difference among values above
/// `floor` times the image's largest, the share of such values that differ by more than `tol`,
/// and the relative difference of the image sums.
fn compare(a: &Rendered, b: &Rendered, tol: f64, floor: f64) -> (f64, f64, f64) {
    let (x, y) = (&a.image.data, &b.image.data);
    let top = x.iter().fold(0.0f32, |m, v| m.max(*v)) as f64;
    let (mut worst, mut over, mut count) = (0.0f64, 0usize, 0usize);
    for (u, v) in x.iter().zip(y) {
        let (u, v) = (*u as f64, *v as f64);
        let s = u.abs().max(v.abs());
        if s <= floor * top {
            continue;
        }
        let rel = (u - v).abs() / s;
        worst = worst.max(rel);
        over += usize::from(rel > tol);
        count += 1;
    }
    let (sa, sb): (f64, f64) = (x.iter().map(|v| *v as f64).sum(), y.iter().map(|v| *v as f64).sum());
    (worst, over as f64 / count as f64, (sa - sb).abs() / sa)
}

/// Renders `on` and `off` (the oracle) on two threads and checks that they agree as the
/// bundle's check promises: fewer than 0.2 % of the values (above 1e-6 of the largest) differ by
/// more than 1e-4 of themselves — a lane whose direction crosses the sun's limb between the two
/// renders may — and the image sums by less than 1e-5.
fn agree(on: &Scene, off: &Scene) -> (Rendered, Rendered) {
    let (a, b) = (common::render_with(on, 2), common::render_with(off, 2));
    let (worst, share, total) = compare(&a, &b, 1e-4, 1e-6);
    eprintln!(
        "worst {worst:.2e}, {:.3} % over 1e-4, sums {total:.2e}, rays {:?} vs {:?}",
        100.0 * share,
        rays(&a),
        rays(&b)
    );
    assert!(share < 2e-3, "{:.3} % of values differ by more than 1e-4 (worst {worst:.2e})", 100.0 * share);
    assert!(total < 1e-5, "image sums differ by {total:.2e}");
    (a, b)
}

#[test]
fn bundled_wavelengths_match_traced_ones_on_the_setting_sun() {
    // The shipped sunset over the sea at 64 × 48 pixels, one sample each, without photons (the
    // sea is black, so every value is the sun's disc or the sky seen through the air: a
    // deterministic function of each path's end and transmittance, which the bundle
    // interpolates). The check holds the fourth guide's transmittance to 1e-4 and its
    // direction to 0.5 m / 1000 km = 5e-7 rad, 0.3 % of a pixel; the cubic used is tighter
    // still, so values agree to 1e-4 except where a lane's direction crosses the sun's limb
    // between the two renders (a 0.3 % chance for a lane whose pixel the limb crosses).
    let on = example("sunset_sea", 64, 48, "");
    let off = example("sunset_sea", 64, 48, "dispersion_bundles = false");
    assert!(
        on.plan.dispersion_splitting.why.contains("interpolate the other 12"),
        "{}",
        on.plan.dispersion_splitting.why
    );
    assert!(off.plan.dispersion_splitting.why.contains("dispersion_bundles = false"));
    let (a, b) = agree(&on, &off);
    // Most lanes are interpolated (4 of 16 traced per pixel), none with bundles off.
    let (pixels, lanes) = (64 * 48, 12 * 64 * 48);
    let ((bundled, _), (none, traced)) = (rays(&a), rays(&b));
    assert!(bundled as f64 > 0.9 * lanes as f64, "{bundled} of {lanes} lanes interpolated");
    assert_eq!(none, 0);
    assert!(traced >= 16 * pixels, "{traced} eye paths without bundles");
    // The guides' paths alone ran the integrator: a quarter of the events of the oracle's.
    let (ea, eb) = (a.stats.eye_curved.curved_events, b.stats.eye_curved.curved_events);
    assert!(ea * 3 < eb, "{ea} vs {eb} curved events");
}

#[test]
fn bundles_through_a_duct_agree_with_traced_wavelengths_where_they_are_used() {
    // The green flash: the sun's upper limb seen through a mock-mirage inversion, whose duct
    // folds the paths of neighbouring heights and parts the wavelengths most. The check must
    // refuse every bundle it cannot fit, so the image still agrees with the traced one as in
    // smooth air.
    let on = example("green_flash", 48, 48, "");
    let off = example("green_flash", 48, 48, "dispersion_bundles = false");
    let (a, _) = agree(&on, &off);
    let (bundled, _) = rays(&a);
    assert!(bundled > 0, "some bundles are used");
}

#[test]
fn bundles_in_a_hot_road_mirage_agree_with_traced_wavelengths() {
    // The hot road: the air fills the world, so escaping paths run on straight for 21 000 km and
    // their direction is held to the floor of ten Dormand–Prince steps, not to the arc tolerance
    // over that length. The image must still agree with every wavelength traced.
    let on = example("mirage_hot_road", 60, 40, "");
    let off = example("mirage_hot_road", 60, 40, "dispersion_bundles = false");
    let (a, _) = agree(&on, &off);
    // 8 bands: each split path has 4 lanes to interpolate; most are.
    let (bundled, splits) = (a.stats.rays.bundled, a.stats.rays.splits);
    assert!(bundled as f64 > 0.5 * (4 * splits) as f64, "{bundled} of {} lanes interpolated", 4 * splits);
}

#[test]
fn a_render_with_bundles_is_the_same_for_any_thread_count() {
    let s = example("sunset_sea", 24, 18, "");
    let (a, b) = (common::render_with(&s, 1), common::render_with(&s, 2));
    assert_eq!(a.image.data, b.image.data);
}
