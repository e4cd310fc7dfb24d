//! `[integrator]` progressive passes and stopping rules: how many passes a render runs, or
//! for how long, or to what relative standard error (`passes`, `time`, `target_rel_error`,
//! `target`, `alpha`; on the command line `--passes`, `--time`, `--target-rel-error`,
//! `--target`), and whether later passes steer their eye samples (`adaptive`, `--adaptive`). What a pass does is in [`crate::photon_map::progressive`].

use super::raw::RawIntegrator;
use crate::photon_map::progressive::DEFAULT_ALPHA;
use crate::validate::{Ctx, R};
use serde::Serialize;
use toml::{Spanned, Value};

/// The most passes a run may ask for.
pub const MAX_PASSES: u32 = 1_000_000;

/// Under adaptive sampling a pixel gets at most this many times `spp` eye samples in one pass.
pub const ADAPTIVE_MAX_FACTOR: usize = 32;

/// The longest `time` budget, s (a year).
pub const MAX_TIME_S: f64 = 3.2e7;

/// What the relative standard error of `target_rel_error` is measured on.
#[derive(Clone, Debug, PartialEq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Target {
    /// The mean of every pixel and band of the image.
    Image,
    /// The mean of a named sensor's first column over its points.
    Sensor(String),
    /// The mean of every band over the pixels x0 ≤ x < x1, y0 ≤ y < y1.
    Region([usize; 4]),
    /// Every pixel on its own: the error of a picture, not of its mean (see
    /// `render::progressive::pixel_rel_error`).
    Pixels,
}

/// The target's name in words ("image", "sensor desk", "region 0,0,8,8").
pub fn label(target: &Target) -> String {
    match target {
        Target::Image => "image".into(),
        Target::Pixels => "pixels".into(),
        Target::Sensor(n) => format!("sensor {n}"),
        Target::Region([x0, y0, x1, y1]) => format!("region {x0},{y0},{x1},{y1}"),
    }
}

/// How many progressive passes a render runs: every rule given stops the run when it is met.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Progressive {
    /// Stop after this many passes.
    pub passes: Option<u32>,
    /// Stop when the next pass would end past this wall-clock budget for the whole run, s.
    pub time_s: Option<f64>,
    /// Stop when the relative standard error of [`Progressive::target`] falls below this.
    pub target_rel_error: Option<f64>,
    /// What `target_rel_error` is measured on.
    pub target: Target,
    /// Knaus & Zwicker's α: how fast the gather radii shrink (0 < α < 1).
    pub alpha: f64,
    /// Adaptive sampling: from the second pass on, each pass spends its eye samples where the
    /// pixels' samples spread most (see `render::adaptive`).
    pub adaptive: bool,
}

impl Default for Progressive {
    fn default() -> Progressive {
        Progressive {
            passes: None,
            time_s: None,
            target_rel_error: None,
            target: Target::Image,
            alpha: DEFAULT_ALPHA,
            adaptive: false,
        }
    }
}

impl Progressive {
    /// The pass limit in force: `passes`, or one pass when no rule is given.
    pub fn pass_limit(&self) -> u32 {
        match (self.passes, self.time_s, self.target_rel_error) {
            (Some(n), _, _) => n,
            (None, None, None) => 1,
            _ => MAX_PASSES,
        }
    }

    /// Whether any stopping rule is given (a progressive run, which keeps checkpoints), rather
    /// than the one pass of a run without rules.
    pub fn has_rules(&self) -> bool {
        self.passes.is_some() || self.time_s.is_some() || self.target_rel_error.is_some()
    }

    /// Applies a front end's rules over the scene's (each one given replaces its key); errors
    /// name the flag or keyword as `flags.style` spells it.
    pub fn apply(&mut self, flags: &Flags) -> crate::error::Result<()> {
        let said = |key: &str, value: &dyn std::fmt::Display| flags.style.said(key, value);
        if let Some(n) = flags.passes {
            self.passes = Some(check_passes(n).map_err(|e| input_error(format!("{}: {e}", said("passes", &n))))?);
        }
        if let Some(t) = &flags.time {
            self.time_s = Some(parse_duration(t).map_err(|e| input_error(format!("{}: {e}", said("time", t))))?);
        }
        if let Some(e) = flags.target_rel_error {
            self.target_rel_error =
                Some(check_rel_error(e).map_err(|m| input_error(format!("{}: {m}", said("target_rel_error", &e))))?);
        }
        if let Some(t) = &flags.target {
            self.target = parse_target(t).map_err(|e| input_error(format!("{}: {e}", said("target", t))))?;
            if self.target_rel_error.is_none() {
                return Err(input_error(format!(
                    "{} needs {} (or target_rel_error in [integrator]): it names what that error is measured on",
                    said("target", t),
                    flags.style.name("target_rel_error")
                )));
            }
        }
        self.adaptive |= flags.adaptive;
        if self.adaptive && self.pass_limit() == 1 {
            let named = if flags.adaptive { flags.style.name("adaptive") } else { "[integrator] adaptive".into() };
            return Err(input_error(format!(
                "{named} steers the eye samples of later passes, but the run makes one pass: give {}, {} or {} (or passes, time or target_rel_error in [integrator])",
                flags.style.said("passes", &"N"),
                flags.style.said("time", &"90s"),
                flags.style.said("target_rel_error", &"0.01")
            )));
        }
        Ok(())
    }

    /// Checks that the target names a sensor of the scene, or a region inside the image:
    /// `Err` says what is wrong and what would do.
    pub fn check_target(&self, sensors: &[String], width: usize, height: usize) -> Result<(), String> {
        match &self.target {
            Target::Image | Target::Pixels => Ok(()),
            Target::Sensor(name) if sensors.contains(name) => Ok(()),
            Target::Sensor(name) if sensors.is_empty() => Err(format!(
                "names the sensor \"{name}\", but the scene has no sensors; use \"image\", \"pixels\" or a pixel region x0,y0,x1,y1"
            )),
            Target::Sensor(name) => Err(format!(
                "names the sensor \"{name}\", which the scene does not have; its sensors are: {}",
                sensors.join(", ")
            )),
            Target::Region([x0, y0, x1, y1]) if x0 < x1 && y0 < y1 && *x1 <= width && *y1 <= height => Ok(()),
            Target::Region(r) => Err(format!(
                "the region {r:?} is not a non-empty rectangle x0,y0,x1,y1 (x1, y1 exclusive) inside the {width} × {height} image"
            )),
        }
    }
}

/// A front end's stopping rules (`None`: not given): `morgana render`'s flags or the Python
/// package's keyword arguments.
#[derive(Clone, Debug, Default)]
pub struct Flags {
    /// `--passes N`.
    pub passes: Option<i64>,
    /// `--time 90s`.
    pub time: Option<String>,
    /// `--target-rel-error 0.01`.
    pub target_rel_error: Option<f64>,
    /// `--target image|pixels|SENSOR|x0,y0,x1,y1`.
    pub target: Option<String>,
    /// `--adaptive` (given: on; not given: the scene's `adaptive`).
    pub adaptive: bool,
    /// How messages spell the rules.
    pub style: FlagStyle,
}

/// How a front end spells a stopping rule in its messages.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum FlagStyle {
    /// Command-line flags: `--target-rel-error 0.5`.
    #[default]
    Cli,
    /// Keyword arguments: `target_rel_error=0.5`.
    Keyword,
}

impl FlagStyle {
    /// The rule `key` (as `[integrator]` spells it) as this front end names it.
    pub fn name(self, key: &str) -> String {
        match self {
            FlagStyle::Cli => format!("--{}", key.replace('_', "-")),
            FlagStyle::Keyword => key.to_string(),
        }
    }

    /// The rule `key` given `value`, as the user wrote it.
    pub fn said(self, key: &str, value: &dyn std::fmt::Display) -> String {
        match self {
            FlagStyle::Cli => format!("{} {value}", self.name(key)),
            FlagStyle::Keyword => format!("{key}={value}"),
        }
    }
}

fn input_error(message: String) -> crate::error::Error {
    crate::error::Error::input(None, message)
}

fn check_passes(n: i64) -> Result<u32, String> {
    if (1..=i64::from(MAX_PASSES)).contains(&n) {
        Ok(n as u32)
    } else {
        Err(format!("expected between 1 and {MAX_PASSES} passes"))
    }
}

fn check_rel_error(e: f64) -> Result<f64, String> {
    if e.is_finite() && e > 0.0 && e < 1.0 {
        Ok(e)
    } else {
        Err("expected a relative standard error between 0 and 1 (exclusive), e.g. 0.01 for 1 %".into())
    }
}

/// A duration: seconds as a plain number or with a unit `s`, `min` (or `m`) or `h`, e.g. `90s`,
/// `1.5min`, `2h`; positive and at most [`MAX_TIME_S`].
pub fn parse_duration(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let (number, scale) = [("min", 60.0), ("h", 3600.0), ("s", 1.0), ("m", 60.0)]
        .iter()
        .find_map(|(unit, scale)| t.strip_suffix(unit).map(|n| (n.trim(), *scale)))
        .unwrap_or((t, 1.0));
    let seconds = number
        .parse::<f64>()
        .map(|x| x * scale)
        .map_err(|_| "expected a duration such as 90s, 1.5min or 2h (a plain number is seconds)".to_string())?;
    if seconds.is_finite() && seconds > 0.0 && seconds <= MAX_TIME_S {
        Ok(seconds)
    } else {
        Err(format!("expected a positive duration of at most {MAX_TIME_S} s (a year)"))
    }
}

/// A target: `image`, `pixels`, a pixel region `x0,y0,x1,y1`, or a sensor's name (a sensor
/// named `image` or `pixels` cannot be a target).
pub fn parse_target(text: &str) -> Result<Target, String> {
    let t = text.trim();
    match t {
        "image" => return Ok(Target::Image),
        "pixels" => return Ok(Target::Pixels),
        _ => {}
    }
    let parts: Vec<&str> = t.split(',').map(str::trim).collect();
    if parts.len() == 4 {
        let nums: Vec<usize> = parts.iter().filter_map(|p| p.parse().ok()).collect();
        return match nums[..] {
            [x0, y0, x1, y1] => Ok(Target::Region([x0, y0, x1, y1])),
            _ => Err("a region is four pixel indices x0,y0,x1,y1 (x1, y1 exclusive)".into()),
        };
    }
    if t.is_empty() {
        return Err("expected \"image\", \"pixels\", a sensor's name or a pixel region x0,y0,x1,y1".into());
    }
    Ok(Target::Sensor(t.to_string()))
}

/// The `[integrator]` keys `passes`, `time`, `target_rel_error`, `target`, `alpha` and
/// `adaptive`.
pub fn progressive(ctx: &Ctx, r: &RawIntegrator) -> R<Progressive> {
    let mut p = Progressive::default();
    if let Some(v) = &r.passes {
        let n = ctx.integer(v, "passes", 1, i64::from(MAX_PASSES))?;
        p.passes = Some(n as u32);
    }
    if let Some(v) = &r.time {
        p.time_s = Some(time(ctx, v)?);
    }
    if let Some(v) = &r.target_rel_error {
        p.target_rel_error = Some(ctx.number(v, "target_rel_error", 0.0, 1.0, true)?);
    }
    if let Some(v) = &r.target {
        p.target = parse_target(v.get_ref()).map_err(|e| ctx.err(&v.span(), format!("[integrator] target: {e}")))?;
        if p.target_rel_error.is_none() {
            return Err(ctx.err(
                &v.span(),
                "[integrator] target names what target_rel_error is measured on: add target_rel_error (e.g. 0.01)",
            ));
        }
    }
    if let Some(v) = &r.alpha {
        p.alpha = ctx.number(v, "alpha", 0.0, 1.0, true)?;
    }
    if let Some(v) = &r.adaptive {
        p.adaptive = *v.get_ref();
    }
    Ok(p)
}

/// `time`: a number of seconds or a string with a unit.
fn time(ctx: &Ctx, v: &Spanned<Value>) -> R<f64> {
    let parsed = match v.get_ref() {
        Value::String(s) => parse_duration(s),
        Value::Float(x) => parse_duration(&x.to_string()),
        Value::Integer(i) => parse_duration(&i.to_string()),
        _ => Err("expected a duration such as \"90s\", \"1.5min\" or \"2h\", or a number of seconds".into()),
    };
    parsed.map_err(|e| ctx.err(&v.span(), format!("[integrator] time: {e}")))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn durations_take_units() {
        assert_eq!(parse_duration("90s"), Ok(90.0));
        assert_eq!(parse_duration("1.5min"), Ok(90.0));
        assert_eq!(parse_duration("2m"), Ok(120.0));
        assert_eq!(parse_duration("2h"), Ok(7200.0));
        assert_eq!(parse_duration("12"), Ok(12.0));
        for bad in ["-1", "0", "abc", "", "1e99s", "nans"] {
            assert!(parse_duration(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn targets_are_image_regions_or_sensor_names() {
        assert_eq!(parse_target("image"), Ok(Target::Image));
        assert_eq!(parse_target(" pixels "), Ok(Target::Pixels));
        assert_eq!(parse_target("1, 2,30,40"), Ok(Target::Region([1, 2, 30, 40])));
        assert_eq!(parse_target("desk"), Ok(Target::Sensor("desk".into())));
        assert!(parse_target("1,2,x,4").is_err());
        let p = Progressive { target: Target::Region([0, 0, 10, 10]), ..Progressive::default() };
        assert!(p.check_target(&[], 10, 10).is_ok());
        assert!(p.check_target(&[], 9, 10).is_err());
        let p = Progressive { target: Target::Sensor("desk".into()), ..Progressive::default() };
        assert!(p.check_target(&["desk".into()], 1, 1).is_ok());
        assert!(p.check_target(&["floor".into()], 1, 1).unwrap_err().contains("floor"));
    }

    #[test]
    fn one_pass_without_rules() {
        assert_eq!(Progressive::default().pass_limit(), 1);
        let timed = Progressive { time_s: Some(1.0), ..Progressive::default() };
        assert_eq!(timed.pass_limit(), MAX_PASSES);
    }
}
