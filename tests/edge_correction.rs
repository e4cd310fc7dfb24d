//! The share of a surface photon estimate's disc that lies on surfaces able to hold photons
//! (`World::gather_share`), against the area of a disc cut by a straight line: a disc of radius
//! r whose centre lies d inside the edge keeps the share
//!
//! s(d) = 1 − (acos(d/r) − (d/r) √(1 − (d/r)²)) / π
//!
//! (the circular segment beyond the chord has area r² (acos(d/r) − (d/r) √(1 − d²/r²))).

mod common;

use common::scene;
use glam::DVec3;
use morgana::scene::Scene;
use std::f64::consts::PI;

/// The share of the disc left when a straight edge passes `d` from its centre (d ≥ 0 inside).
fn segment_share(d: f64, r: f64) -> f64 {
    let c = (d / r).clamp(-1.0, 1.0);
    1.0 - (c.acos() - c * (1.0 - c * c).sqrt()) / PI
}

/// One set of 8 × 4 probes measures a straight cut to within this (0.149 is the worst seen
/// over 800 points of an edge).
const ONE: f64 = 0.17;

/// Turned and moved along the radius differently at each point, the probes' mean along an edge
/// (`ALONG` points) is within this of the segment's share (0.003 the worst seen over 21
/// offsets at 200 points).
const MEAN: f64 = 0.012;

/// Points along an edge whose shares are averaged.
const ALONG: usize = 100;

const MATERIALS: &str = "[[material]]\nname = \"white\"\ntype = \"lambertian\"\nreflectance = 0.5\n\n\
     [[material]]\nname = \"glass\"\ntype = \"dielectric\"\nior = 1.5\n";

fn world(shapes: &str) -> Scene {
    scene(&format!(
        "[camera]\nposition = [0.0, 3.0, 0.0]\nlook_at = [0.0, 0.0, 0.0]\nup = [0.0, 0.0, -1.0]\nfov_deg = 60.0\nwidth = 8\nheight = 8\n\n\
         [integrator]\nphotons = 1000\n\n[[light]]\ntype = \"point\"\nposition = [0.0, 2.0, 0.0]\npower_w = 1.0\nspectrum = 1.0\n\n\
         {MATERIALS}\n{shapes}"
    ))
}

fn quad(name: &str, material: &str, origin: [f64; 3], u: [f64; 3], v: [f64; 3]) -> String {
    format!(
        "[[shape]]\nname = \"{name}\"\ntype = \"quad\"\norigin = {origin:?}\nu = {u:?}\nv = {v:?}\nmaterial = \"{material}\"\n\n"
    )
}

/// A floor y = 0 over x, z ∈ [−1, 1], its normal up.
fn floor() -> String {
    quad("floor", "white", [-1.0, 0.0, -1.0], [0.0, 0.0, 2.0], [2.0, 0.0, 0.0])
}

/// The share at `x` on the floor (the first shape) for radius `r`.
fn share(s: &Scene, x: [f64; 3], r: f64) -> f64 {
    s.world.gather_share(DVec3::from(x), DVec3::Y, r)
}

/// Checks the share at `d` inside a straight edge for radius `r`: at each of [`ALONG`] points
/// `at(t)`, t ∈ [0, 1), within [`ONE`], and their mean within [`MEAN`].
fn check_edge(s: &Scene, d: f64, r: f64, at: impl Fn(f64) -> [f64; 3], what: &str) {
    let want = segment_share(d, r);
    let shares: Vec<f64> = (0..ALONG).map(|i| share(s, at(i as f64 / ALONG as f64), r)).collect();
    for (i, got) in shares.iter().enumerate() {
        assert!((got - want).abs() < ONE, "{what}, d = {d}, point {i}: share {got}, segment {want}");
    }
    let mean = shares.iter().sum::<f64>() / ALONG as f64;
    assert!((mean - want).abs() < MEAN, "{what}, d = {d}: mean share {mean}, segment {want}");
}

#[test]
fn a_disc_in_the_middle_of_a_surface_is_whole() {
    let s = world(&floor());
    assert_eq!(share(&s, [0.0, 0.0, 0.0], 0.3), 1.0);
    assert_eq!(share(&s, [0.69, 0.0, -0.69], 0.3), 1.0);
}

#[test]
fn a_disc_over_the_open_edge_of_a_surface_keeps_the_segment_inside() {
    let s = world(&floor());
    let r = 0.2;
    for d in [0.0, 0.03, 0.07, 0.1, 0.15, 0.19] {
        check_edge(&s, d, r, |t| [1.0 - d, 0.0, -0.5 + t], "edge x = 1");
        check_edge(&s, d, r, |t| [-0.5 + t, 0.0, -1.0 + d], "edge z = −1");
    }
    // A corner of the quad: a quarter of the disc when the centre sits on it.
    let corner = share(&s, [1.0, 0.0, 1.0], r);
    assert!((corner - 0.25).abs() < ONE, "corner: {corner}");
}

#[test]
fn a_wall_cuts_a_floor_that_runs_on_under_it() {
    // The floor reaches x = 1; a wall stands at x = 0.5, so the floor beyond it (dark, behind
    // the wall) is not where photons from this side land.
    let wall = quad("wall", "white", [0.5, 0.0, -1.0], [0.0, 1.0, 0.0], [0.0, 0.0, 2.0]);
    let s = world(&format!("{}{wall}", floor()));
    let r = 0.2;
    for d in [0.01, 0.05, 0.1, 0.15] {
        check_edge(&s, d, r, |t| [0.5 - d, 0.0, -0.5 + t], "wall");
    }
    // Two walls meeting: a quarter.
    let side = quad("side", "white", [-1.0, 0.0, 0.5], [2.0, 0.0, 0.0], [0.0, 1.0, 0.0]);
    let s = world(&format!("{}{wall}{side}", floor()));
    let corner = share(&s, [0.5 - 1e-6, 0.0, 0.5 - 1e-6], r);
    assert!((corner - 0.25).abs() < ONE, "corner: {corner}");
}

#[test]
fn glass_lets_the_disc_through_and_an_opaque_block_does_not() {
    let r = 0.2;
    // A glass ball resting on the floor: photons reach the floor under and beside it.
    let ball =
        "[[shape]]\nname = \"ball\"\ntype = \"sphere\"\ncenter = [0.0, 0.3, 0.0]\nradius = 0.3\nmaterial = \"glass\"\n";
    let s = world(&format!("{}{ball}", floor()));
    for z in [-0.1, 0.0, 0.1] {
        let got = share(&s, [0.05, 0.0, z], r);
        assert!(got > 1.0 - ONE, "beside a glass ball: {got}");
    }
    // An opaque box's side face standing on the floor at x = 0.3 (its top out of reach):
    // the floor beyond it is covered.
    let block = quad("block", "white", [0.3, 0.0, -0.5], [0.0, 0.5, 0.0], [0.0, 0.0, 1.0]);
    let top = quad("top", "white", [0.3, 0.5, -0.5], [0.5, 0.0, 0.0], [0.0, 0.0, 1.0]);
    let s = world(&format!("{}{block}{top}", floor()));
    check_edge(&s, 0.08, r, |t| [0.22, 0.0, -0.3 + 0.6 * t], "beside a block");
}

#[test]
fn a_surface_tilted_away_beyond_a_fold_does_not_count() {
    // The floor meets a ramp rising at 70° along x = 0.5: the ramp's normal is 70° from the
    // floor's, beyond the estimate's 60°, so its photons are not counted and nor is its area.
    let t = 70f64.to_radians();
    let ramp = quad("ramp", "white", [0.5, 0.0, -1.0], [t.cos(), t.sin(), 0.0], [0.0, 0.0, 2.0]);
    let floor_to_fold = quad("floor", "white", [-1.0, 0.0, -1.0], [0.0, 0.0, 2.0], [1.5, 0.0, 0.0]);
    let s = world(&format!("{floor_to_fold}{ramp}"));
    check_edge(&s, 0.1, 0.2, |t| [0.4, 0.0, -0.5 + t], "before a steep fold");
    // A gentle fold (20°) carries on: the disc is (nearly) whole.
    let t = 20f64.to_radians();
    let gentle = quad("ramp", "white", [0.5, 0.0, -1.0], [t.cos(), t.sin(), 0.0], [0.0, 0.0, 2.0]);
    let s = world(&format!("{floor_to_fold}{gentle}"));
    let got = share(&s, [0.4, 0.0, 0.0], 0.2);
    assert!(got > 1.0 - ONE, "before a gentle fold: {got}");
}
