//! Helpers shared by the integration tests.
#![allow(dead_code)]

pub mod shared;

use morgana::render::{RenderOptions, Rendered, render};
use morgana::scene::{Scene, load_scene_str};
use std::path::Path;

/// A scene from TOML text (errors name "test.toml").
pub fn scene(toml: &str) -> Scene {
    match load_scene_str(toml, Path::new("test.toml"), Path::new("."), "test") {
        Ok(s) => s,
        Err(e) => panic!("test scene does not load: {e}"),
    }
}

/// The error message a scene produces.
pub fn scene_error(toml: &str) -> String {
    match load_scene_str(toml, Path::new("test.toml"), Path::new("."), "test") {
        Ok(_) => panic!("scene was accepted but should have been rejected:\n{toml}"),
        Err(e) => e.to_string(),
    }
}

/// Renders on a pool of `threads` threads without progress bars.
pub fn render_with(scene: &Scene, threads: usize) -> Rendered {
    let pool = rayon::ThreadPoolBuilder::new().num_threads(threads).build().expect("thread pool");
    pool.install(|| render(scene, &RenderOptions { quiet: true, ..RenderOptions::default() }))
}

/// Mean and standard error of the mean of `xs`.
pub fn mean_and_sem(xs: &[f64]) -> (f64, f64) {
    let n = xs.len() as f64;
    let mean = xs.iter().sum::<f64>() / n;
    let var = xs.iter().map(|x| (x - mean).powi(2)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}
