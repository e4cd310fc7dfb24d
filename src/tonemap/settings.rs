//! Tone-reproduction settings: raw option values (command line or `[output]`) and their
//! validation into [`ToneSettings`].
//!
//! A value that the chosen settings do not use is an error, naming the option it needs, e.g.
//! `adaptation_time_s` without `tonemap = "pattanaik"`.

use super::chromatic::Cat;
use super::exposure::Exposure;
use super::mesopic::ScotopicMode;
use super::white::AdaptTo;

/// The tone-reproduction operator.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Operator {
    /// Global exposure (a camera, not an eye).
    Exposure(Exposure),
    /// Reinhard et al. (2002), photographic tone reproduction.
    Reinhard,
    /// Ward Larson et al. (1997), histogram adjustment.
    WardHistogram,
    /// Pattanaik et al. (2000), time-dependent visual adaptation.
    Pattanaik,
}

impl Operator {
    /// Canonical names (dashes and underscores are interchangeable).
    pub const NAMES: [&'static str; 4] = ["exposure", "reinhard", "ward_histogram", "pattanaik"];

    /// The canonical name (one of [`Operator::NAMES`]).
    pub fn name(&self) -> &'static str {
        match self {
            Operator::Exposure(_) => "exposure",
            Operator::Reinhard => "reinhard",
            Operator::WardHistogram => "ward_histogram",
            Operator::Pattanaik => "pattanaik",
        }
    }

    /// Operators that model the eye simulate rod vision by default.
    fn default_scotopic(&self) -> ScotopicMode {
        match self {
            Operator::WardHistogram | Operator::Pattanaik => ScotopicMode::Auto,
            Operator::Exposure(_) | Operator::Reinhard => ScotopicMode::Off,
        }
    }
}

/// Where a Pattanaik eye comes from: steady at `from_cd_m2`, then `time_s` seconds on the image.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptationTime {
    /// Luminance the eye was adapted to at steady state before, cd m⁻².
    pub from_cd_m2: f64,
    /// Time since the eye began looking at the image, s.
    pub time_s: f64,
}

/// Validated settings.
#[derive(Clone, Debug, PartialEq)]
pub struct ToneSettings {
    /// The tone-reproduction operator.
    pub operator: Operator,
    /// The scene white chromatic adaptation starts from.
    pub adapt_to: AdaptTo,
    /// The chromatic adaptation transform.
    pub cat: Cat,
    /// Degree of chromatic adaptation D ∈ [0, 1].
    pub adaptation_degree: f64,
    /// `None`: fully adapted to the image.
    pub time: Option<AdaptationTime>,
    /// How rod vision is simulated.
    pub scotopic: ScotopicMode,
    /// Show luminance in false colour instead of tone mapping.
    pub false_colour: bool,
    /// Vertical field of view of the image, degrees.
    pub fov_deg: f64,
}

/// The default vertical field of view when an image does not say, degrees.
pub const DEFAULT_FOV_DEG: f64 = 40.0;

impl Default for ToneSettings {
    fn default() -> Self {
        ToneSettings {
            operator: Operator::Exposure(Exposure::Auto),
            adapt_to: AdaptTo::None,
            cat: Cat::Cat16,
            adaptation_degree: 1.0,
            time: None,
            scotopic: ScotopicMode::Off,
            false_colour: false,
            fov_deg: DEFAULT_FOV_DEG,
        }
    }
}

/// Option values as given; names are those of `[output]` (the command line uses dashes and
/// `--operator` for `tonemap`).
#[derive(Clone, Debug, Default)]
pub struct ToneOptions {
    /// `tonemap` / `--operator`: operator name.
    pub operator: Option<String>,
    /// `exposure`: `auto` or stops (EV); only with the exposure operator.
    pub exposure: Option<Exposure>,
    /// `adapt_to`: scene white, a name or `x,y`.
    pub adapt_to: Option<String>,
    /// `cat`: chromatic adaptation transform name.
    pub cat: Option<String>,
    /// `adaptation_degree`: degree of adaptation D, 0 to 1.
    pub adaptation_degree: Option<f64>,
    /// `adaptation_time_s`: seconds since the adaptation luminance changed (Pattanaik).
    pub adaptation_time_s: Option<f64>,
    /// `adapt_from_cd_m2`: the luminance adapted to before, cd m⁻² (Pattanaik).
    pub adapt_from_cd_m2: Option<f64>,
    /// `scotopic`: `auto`, `on` or `off`.
    pub scotopic: Option<String>,
    /// `false_colour`: luminance in false colour.
    pub false_colour: bool,
    /// Vertical field of view of the image, degrees (from the camera, or given).
    pub fov_deg: Option<f64>,
}

/// A rejected option: which one and why.
#[derive(Clone, Debug, PartialEq)]
pub struct OptionError {
    /// The `[output]` name of the option (`tonemap` for the operator).
    pub field: &'static str,
    /// What is wrong, and what is allowed.
    pub message: String,
}

fn err(field: &'static str, message: impl Into<String>) -> OptionError {
    OptionError { field, message: message.into() }
}

impl ToneOptions {
    /// Validates the options (see the module documentation).
    pub fn validate(&self) -> Result<ToneSettings, OptionError> {
        let mut s = ToneSettings { operator: self.operator()?, ..ToneSettings::default() };
        if let Some(a) = &self.adapt_to {
            s.adapt_to = AdaptTo::parse(a).map_err(|m| err("adapt_to", m))?;
        }
        let adapting = s.adapt_to != AdaptTo::None;
        if let Some(c) = &self.cat {
            need(adapting, "cat", "adapt_to")?;
            s.cat = Cat::parse(c)
                .ok_or_else(|| err("cat", format!("\"{c}\" is not known; allowed: von_kries, bradford, cat16")))?;
        }
        if let Some(d) = self.adaptation_degree {
            need(adapting, "adaptation_degree", "adapt_to")?;
            if !(0.0..=1.0).contains(&d) {
                return Err(err("adaptation_degree", format!("{d} is out of range: it must be between 0 and 1")));
            }
            s.adaptation_degree = d;
        }
        s.time = self.time(&s.operator)?;
        s.scotopic = match &self.scotopic {
            None => s.operator.default_scotopic(),
            Some(m) => ScotopicMode::parse(m)
                .ok_or_else(|| err("scotopic", format!("\"{m}\" is not known; allowed: auto, on, off")))?,
        };
        if let Some(f) = self.fov_deg {
            if !(f.is_finite() && f > 0.0 && f < 180.0) {
                return Err(err("fov_deg", format!("{f} is out of range: it must be strictly between 0 and 180")));
            }
            s.fov_deg = f;
        }
        s.false_colour = self.false_colour;
        if s.false_colour {
            self.check_false_colour()?;
        }
        Ok(s)
    }

    fn operator(&self) -> Result<Operator, OptionError> {
        let name = self.operator.as_deref().unwrap_or("exposure").to_ascii_lowercase().replace('-', "_");
        let op = match name.as_str() {
            "exposure" => Operator::Exposure(self.exposure.unwrap_or(Exposure::Auto)),
            "reinhard" => Operator::Reinhard,
            "ward_histogram" => Operator::WardHistogram,
            "pattanaik" => Operator::Pattanaik,
            _ => {
                return Err(err(
                    "tonemap",
                    format!("\"{name}\" is not an operator; allowed: {}", Operator::NAMES.join(", ")),
                ));
            }
        };
        if self.exposure.is_some() && !matches!(op, Operator::Exposure(_)) {
            return Err(err(
                "exposure",
                format!("exposure is only used by the exposure operator, not \"{}\"", op.name()),
            ));
        }
        Ok(op)
    }

    fn time(&self, op: &Operator) -> Result<Option<AdaptationTime>, OptionError> {
        match (self.adaptation_time_s, self.adapt_from_cd_m2) {
            (None, None) => Ok(None),
            (Some(_), _) if *op != Operator::Pattanaik => {
                Err(err("adaptation_time_s", "adaptation_time_s is only used by the pattanaik operator"))
            }
            (None, Some(_)) => {
                Err(err("adapt_from_cd_m2", "adapt_from_cd_m2 is only used together with adaptation_time_s"))
            }
            (Some(_), None) => Err(err(
                "adaptation_time_s",
                "adaptation_time_s needs adapt_from_cd_m2, the luminance the eye was adapted to before \
                 (e.g. 5000 for daylight, 0.01 for a night scene)",
            )),
            (Some(t), Some(from)) => {
                if !(t.is_finite() && t >= 0.0) {
                    return Err(err(
                        "adaptation_time_s",
                        format!("{t} is out of range: it must be at least 0 seconds"),
                    ));
                }
                if !(from.is_finite() && from > 0.0) {
                    return Err(err("adapt_from_cd_m2", format!("{from} is out of range: it must be greater than 0")));
                }
                Ok(Some(AdaptationTime { from_cd_m2: from, time_s: t }))
            }
        }
    }

    /// False colour shows luminance itself: operator, exposure, adaptation and rod options have
    /// no effect and are rejected.
    fn check_false_colour(&self) -> Result<(), OptionError> {
        let unused = [
            ("tonemap", self.operator.is_some()),
            ("exposure", self.exposure.is_some()),
            ("adapt_to", self.adapt_to.is_some()),
            ("adaptation_time_s", self.adaptation_time_s.is_some()),
            ("scotopic", self.scotopic.is_some()),
        ];
        match unused.iter().find(|(_, given)| *given) {
            Some((field, _)) => Err(err(
                field,
                format!(
                    "{field} has no effect with false colour, which shows the image's own luminance; remove one of them"
                ),
            )),
            None => Ok(()),
        }
    }
}

fn need(ok: bool, field: &'static str, needs: &str) -> Result<(), OptionError> {
    if ok {
        Ok(())
    } else {
        Err(err(field, format!("{field} is only used together with {needs} (other than \"none\")")))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> ToneOptions {
        ToneOptions::default()
    }

    #[test]
    fn defaults_and_operator_dependent_scotopic_mode() {
        let s = opts().validate().unwrap();
        assert_eq!(s, ToneSettings::default());
        let w = ToneOptions { operator: Some("ward-histogram".into()), ..opts() }.validate().unwrap();
        assert_eq!((w.operator, w.scotopic), (Operator::WardHistogram, ScotopicMode::Auto));
        let r = ToneOptions { operator: Some("reinhard".into()), scotopic: Some("on".into()), ..opts() };
        assert_eq!(r.validate().unwrap().scotopic, ScotopicMode::On);
    }

    #[test]
    fn unused_or_bad_values_name_their_option() {
        let field = |o: ToneOptions| o.validate().unwrap_err().field;
        assert_eq!(field(ToneOptions { operator: Some("drago".into()), ..opts() }), "tonemap");
        assert_eq!(
            field(ToneOptions { operator: Some("reinhard".into()), exposure: Some(Exposure::Ev(1.0)), ..opts() }),
            "exposure"
        );
        assert_eq!(field(ToneOptions { cat: Some("bradford".into()), ..opts() }), "cat");
        assert_eq!(field(ToneOptions { adapt_to: Some("x".into()), ..opts() }), "adapt_to");
        assert_eq!(
            field(ToneOptions { adapt_to: Some("white".into()), adaptation_degree: Some(1.5), ..opts() }),
            "adaptation_degree"
        );
        assert_eq!(field(ToneOptions { adaptation_time_s: Some(2.0), ..opts() }), "adaptation_time_s");
        let p = || ToneOptions { operator: Some("pattanaik".into()), ..opts() };
        assert_eq!(field(ToneOptions { adaptation_time_s: Some(2.0), ..p() }), "adaptation_time_s");
        assert_eq!(field(ToneOptions { adapt_from_cd_m2: Some(2.0), ..p() }), "adapt_from_cd_m2");
        let ok = ToneOptions { adaptation_time_s: Some(2.0), adapt_from_cd_m2: Some(5000.0), ..p() };
        assert_eq!(ok.validate().unwrap().time, Some(AdaptationTime { from_cd_m2: 5000.0, time_s: 2.0 }));
        assert_eq!(field(ToneOptions { scotopic: Some("maybe".into()), ..opts() }), "scotopic");
        assert_eq!(field(ToneOptions { fov_deg: Some(180.0), ..opts() }), "fov_deg");
        assert_eq!(field(ToneOptions { false_colour: true, operator: Some("reinhard".into()), ..opts() }), "tonemap");
        assert!(ToneOptions { false_colour: true, ..opts() }.validate().unwrap().false_colour);
    }
}
