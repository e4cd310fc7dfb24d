//! `morgana check [SCENE]`: validates a scene and prints what will be simulated and why (the
//! effect plan).

use crate::error::Result;
use std::path::PathBuf;

/// The command line of `morgana check`.
#[derive(clap::Args, Clone, Debug)]
pub struct CheckArgs {
    /// Scene file (TOML); the embedded default scene when omitted.
    pub scene: Option<PathBuf>,
    /// The output directory a render would write to: checked too (created by `render`, not by
    /// `check`).
    #[arg(long, default_value = "out")]
    pub out: PathBuf,
}

/// The text `morgana check` prints.
pub fn run(args: &CheckArgs) -> Result<String> {
    let scene = super::load(args.scene.as_deref())?;
    crate::output::check_destination(&scene, &args.out, false)?;
    let mut out = format!("{}: valid\n", scene.label());
    out.push_str(&format!(
        "  {}x{} pixels, {} bands over {}–{} nm ({:?} sampling), {} lights, {} shapes\n",
        scene.camera.width,
        scene.camera.height,
        scene.bands.count,
        scene.bands.min_nm,
        scene.bands.max_nm,
        scene.sampling,
        scene.world.lights.len(),
        scene.world.shapes.len()
    ));
    out.push_str(&format!("  outputs: {} in {}\n", scene.output_file_names().join(", "), args.out.display()));
    out.push_str("effect plan:\n");
    out.push_str(&scene.plan.to_string());
    Ok(out)
}
