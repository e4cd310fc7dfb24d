//! `morgana tonemap IN.exr --out OUT.png [options]`: the command's work, behind a thin `main`.
//!
//! Reads the EXR ([`crate::tonemap::exr_read`]), tone-maps it ([`crate::tonemap::tonemap`]) and writes the PNG
//! and, with `--region x0,y0,x1,y1 --csv FILE`, the region's luminance CSV. Outputs are staged
//! and renamed into place only when all were written. Bad options and unreadable input are
//! input errors (exit code 2) naming the option or file and what is allowed.

use crate::atomic::Staged;
use crate::error::{Error, Location, Result};
use crate::raster::png::write_rgb8;
use crate::tonemap::exposure::Exposure;
use crate::tonemap::exr_read::read_exr;
use crate::tonemap::region::Region;
use crate::tonemap::settings::{OptionError, ToneOptions};
use crate::tonemap::tonemap;
use std::path::{Path, PathBuf};

/// The command line of `morgana tonemap`.
#[derive(clap::Args, Clone, Debug)]
pub struct TonemapArgs {
    /// The EXR to read: a spectral EXR written by morgana render, or an RGB EXR.
    pub input: PathBuf,
    /// The PNG to write.
    #[arg(long)]
    pub out: PathBuf,
    /// exposure | reinhard | ward-histogram | pattanaik (default: exposure).
    #[arg(long)]
    pub operator: Option<String>,
    /// Exposure operator only: "auto" (99th percentile to white) or stops (EV).
    #[arg(long, allow_hyphen_values = true)]
    pub exposure: Option<String>,
    /// Chromatic adaptation from this scene white to D65: none, d65, a, e, white (brightest 1 %),
    /// scene-average (grey world) or x,y.
    #[arg(long)]
    pub adapt_to: Option<String>,
    /// Adaptation space: von-kries | bradford | cat16 (default: cat16).
    #[arg(long)]
    pub cat: Option<String>,
    /// Degree of chromatic adaptation, 0 (none) to 1 (complete, default).
    #[arg(long)]
    pub adaptation_degree: Option<f64>,
    /// Pattanaik only: seconds the eye has looked at the image (default: fully adapted).
    #[arg(long)]
    pub adaptation_time_s: Option<f64>,
    /// Pattanaik only, with --adaptation-time-s: luminance the eye was adapted to before, cd/m².
    #[arg(long)]
    pub adapt_from_cd_m2: Option<f64>,
    /// Rod vision: auto (mesopic by luminance) | on (rods only) | off. Default: auto for
    /// ward-histogram and pattanaik, off for exposure and reinhard.
    #[arg(long)]
    pub scotopic: Option<String>,
    /// Show luminance (cd/m²) in false colour on a log scale with a legend.
    #[arg(long)]
    pub false_colour: bool,
    /// Vertical field of view of the image in degrees (EXRs do not record it; default 40).
    #[arg(long)]
    pub fov_deg: Option<f64>,
    /// Pixel rectangle x0,y0,x1,y1 (x1, y1 exclusive) whose luminance goes to --csv.
    #[arg(long)]
    pub region: Option<String>,
    /// CSV file for --region: x, y, luminance, scotopic luminance, illuminance per pixel.
    #[arg(long)]
    pub csv: Option<PathBuf>,
    /// Show the relative standard error of each pixel (from a render of several passes) in
    /// false colour instead of the image.
    #[arg(long)]
    pub stderr: bool,
}

impl TonemapArgs {
    /// The command, with `--exposure` checked.
    pub fn command(&self) -> Result<TonemapCommand> {
        let exposure = match &self.exposure {
            None => None,
            Some(e) => Some(parse_exposure(e).ok_or_else(|| {
                Error::input(None, format!("--exposure: \"{e}\" is neither \"auto\" nor a number of stops (EV)"))
            })?),
        };
        let options = ToneOptions {
            operator: self.operator.clone(),
            exposure,
            adapt_to: self.adapt_to.clone(),
            cat: self.cat.clone(),
            adaptation_degree: self.adaptation_degree,
            adaptation_time_s: self.adaptation_time_s,
            adapt_from_cd_m2: self.adapt_from_cd_m2,
            scotopic: self.scotopic.clone(),
            false_colour: self.false_colour,
            fov_deg: self.fov_deg,
        };
        Ok(TonemapCommand {
            input: self.input.clone(),
            out: self.out.clone(),
            options,
            region: self.region.clone(),
            csv: self.csv.clone(),
            stderr: self.stderr,
        })
    }
}

/// "auto" or a finite number of stops.
pub fn parse_exposure(s: &str) -> Option<Exposure> {
    if s.eq_ignore_ascii_case("auto") {
        return Some(Exposure::Auto);
    }
    s.parse::<f64>().ok().filter(|x| x.is_finite()).map(Exposure::Ev)
}

/// The command's arguments, as given.
#[derive(Clone, Debug, Default)]
pub struct TonemapCommand {
    /// The EXR to read (spectral or RGB).
    pub input: PathBuf,
    /// The PNG to write.
    pub out: PathBuf,
    /// Tone-reproduction options as given.
    pub options: ToneOptions,
    /// `--region x0,y0,x1,y1`, unparsed.
    pub region: Option<String>,
    /// `--csv FILE`: where the region's luminance goes.
    pub csv: Option<PathBuf>,
    /// `--stderr`: draw the relative standard error instead of the image.
    pub stderr: bool,
}

/// The command-line spelling of an `[output]` option name.
fn flag(field: &str) -> String {
    match field {
        "tonemap" => "--operator".into(),
        f => format!("--{}", f.replace('_', "-")),
    }
}

fn option_error(e: OptionError) -> Error {
    Error::input(None, format!("{}: {}", flag(e.field), e.message))
}

/// What `morgana tonemap` prints: the lines of [`run`].
pub fn run_args(args: &TonemapArgs) -> Result<String> {
    Ok(run(&args.command()?)?.iter().map(|l| format!("{l}\n")).collect())
}

/// Runs the command; returns the lines to print (what was written and how).
pub fn run(cmd: &TonemapCommand) -> Result<Vec<String>> {
    let settings = cmd.options.validate().map_err(option_error)?;
    if cmd.stderr {
        return run_stderr(cmd);
    }
    let region = match (&cmd.region, &cmd.csv) {
        (Some(r), Some(_)) => Some(Region::parse(r).map_err(|m| Error::input(None, format!("--region: {m}")))?),
        (None, None) => None,
        (Some(_), None) => return Err(Error::input(None, "--region needs --csv FILE to write the region's values to")),
        (None, Some(_)) => return Err(Error::input(None, "--csv needs --region x0,y0,x1,y1 to say which pixels")),
    };
    // The arguments agree; now the destinations, before any work.
    super::check_output_file("--out", &cmd.out)?;
    if let Some(csv) = &cmd.csv {
        super::check_output_file("--csv", csv)?;
    }
    let image = read_exr(&cmd.input).map_err(|m| Error::input(Some(Location::file(&cmd.input)), m))?;
    if let Some(r) = &region {
        r.check_inside(image.width, image.height).map_err(|m| Error::input(None, format!("--region: {m}")))?;
    }
    let out = tonemap(&image, &settings);
    let mut lines: Vec<String> = out.notes.iter().map(|n| format!("  {n}")).collect();
    let mut staged = vec![stage(&cmd.out, |p| write_rgb8(p, out.width, out.height, &out.rgb))?];
    if let (Some(r), Some(csv)) = (&region, &cmd.csv) {
        staged.push(stage(csv, |p| r.write_csv(&image, p))?);
        let s = r.summary(&image, settings.fov_deg);
        lines.push(format!(
            "  region {},{},{},{}: {} pixels, luminance mean {:.4e}, min {:.4e}, max {:.4e} cd/m2; illuminance at the camera {:.4e} lx (field of view {}°)",
            r.x0, r.y0, r.x1, r.y1, s.pixels, s.mean_cd_m2, s.min_cd_m2, s.max_cd_m2, s.camera_illuminance_lx, settings.fov_deg
        ));
    }
    for s in staged {
        let target = s.target.clone();
        s.commit().map_err(|e| Error::internal(format!("cannot write {}: {e}", target.display())))?;
        lines.insert(0, format!("wrote {}", target.display()));
    }
    Ok(lines)
}

/// `--stderr`: the relative-error map of the input's standard-error layer.
fn run_stderr(cmd: &TonemapCommand) -> Result<Vec<String>> {
    if cmd.region.is_some() || cmd.csv.is_some() || cmd.options.false_colour || cmd.options.operator.is_some() {
        return Err(Error::input(
            None,
            "--stderr draws the relative standard error by itself: leave out --region, --csv, --false-colour and --operator",
        ));
    }
    super::check_output_file("--out", &cmd.out)?;
    let e = crate::tonemap::stderr_map::read_relative_error(&cmd.input)
        .map_err(|m| Error::input(Some(Location::file(&cmd.input)), m))?;
    let out = crate::tonemap::relative_error_false_colour(&e);
    let s = stage(&cmd.out, |p| write_rgb8(p, out.width, out.height, &out.rgb))?;
    let target = s.target.clone();
    s.commit().map_err(|e| Error::internal(format!("cannot write {}: {e}", target.display())))?;
    let mut lines = vec![format!("wrote {}", target.display())];
    lines.extend(out.notes.iter().map(|n| format!("  {n}")));
    Ok(lines)
}

/// Writes `target` through a staged temporary file (its directory is created if missing).
fn stage(target: &Path, write: impl FnOnce(&Path) -> std::io::Result<()>) -> Result<Staged> {
    if let Some(dir) = target.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|e| {
            Error::input(None, format!("cannot create the directory {} for {}: {e}", dir.display(), target.display()))
        })?;
    }
    let s = Staged::new(target).map_err(|e| Error::input(None, format!("cannot write {}: {e}", target.display())))?;
    write(&s.temp).map_err(|e| Error::internal(format!("cannot write {}: {e}", target.display())))?;
    Ok(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn option_errors_use_command_line_spelling() {
        let e = option_error(OptionError { field: "tonemap", message: "x".into() });
        assert_eq!(e.to_string(), "--operator: x");
        assert_eq!(flag("adaptation_time_s"), "--adaptation-time-s");
        let cmd = TonemapCommand { region: Some("0,0,1,1".into()), ..Default::default() };
        assert!(run(&cmd).unwrap_err().to_string().contains("--csv"));
        let cmd = TonemapCommand { input: "/nonexistent/x.exr".into(), out: "o.png".into(), ..Default::default() };
        let e = run(&cmd).unwrap_err();
        assert_eq!(e.exit_code(), 2);
        assert!(e.to_string().starts_with("/nonexistent/x.exr: cannot read it"), "{e}");
    }
}
