//! A phase function tabulated at scattering angles, e.g. Petzold's average ocean particle phase
//! function (Petzold 1972, as tabulated by Mobley et al. 1993).
//!
//! # Interpolation: power laws in x = 1 − cos θ
//! Between nodes θⱼ < θⱼ₊₁ the value is the power law through both samples in the variable
//! x = 1 − cos θ (log β linear in log x):
//!
//! β(x) = βⱼ (x/xⱼ)^{aⱼ},  aⱼ = ln(βⱼ₊₁/βⱼ) / ln(xⱼ₊₁/xⱼ).
//!
//! Why: (1) the forward peak of ocean particle phase functions is close to a power law in θ
//! (Petzold's first decade falls as θ^−1.35), and since x = θ²/2 (1 − θ²/12 + …), a power law in
//! θ is a power law in x with half the exponent — so this is log–log interpolation in angle up
//! to O(θ²) (it differs from log–log in θ by < 0.5 % anywhere in Petzold's table, largest between
//! 175° and 180°), whereas linear interpolation would overshoot between log-spaced nodes;
//! (2) dω = 2π dx, so the mass of each piece, its first moment and the inverse of its CDF are
//! closed forms: the normalisation, the mean cosine and the sampler are exact for the
//! interpolated function, with no discretisation of their own.
//!
//! # The forward peak below the first angle
//! Tables stop at a smallest angle θ₀ (0.1° for Petzold), yet a large share of scattering lies
//! below it. The power law of the first segment is extended from θ₀ down to θ_c = θ₀/1000, and
//! the value is held constant below θ_c (so the density stays finite at θ = 0, which a
//! camera looking straight into a sunbeam will evaluate). For Petzold (β ∝ θ^−1.347 below
//! 0.1°) this puts 5.19 % of the scattering below 0.1° and 0.019 % below θ_c = 10⁻⁴°, where
//! p = 1.95·10⁷ sr⁻¹. The table's normalisation supports the extension: the built-in copy
//! (`src/media/ocean/data/`, renormalised by its transcriber) integrates to 0.9995 with it and to
//! 0.948 without it. [`TabulatedPhase::fraction_below_first_angle`] reports the share.
//!
//! # Normalisation and sampling
//! The interpolated table is divided by its integral over the sphere (the raw integral is kept
//! in [`TabulatedPhase::raw_integral`]), so values may be given in any unit (a phase function in
//! sr⁻¹ or a volume scattering function in m⁻¹ sr⁻¹). Sampling inverts the piecewise closed-form
//! CDF: find the piece by binary search, then x = xⱼ (1 + (a+1) y)^{1/(a+1)} with
//! y = (mass into the piece) / (2π pⱼ xⱼ).
//!
//! # References
//! - Petzold, "Volume scattering functions for selected ocean waters", SIO Ref. 72-78 (1972).
//! - Mobley, Gentili, Gordon et al., "Comparison of numerical models for computing underwater light
//!   fields", Applied Optics 32(36) (1993), 7484–7504 (Table 2: the average particle phase function).
//! - Mobley, *Light and Water* (1994): mean cosine 0.924 of the average particle phase function.

use std::f64::consts::PI;
use std::path::Path;

/// Ratio θ_c/θ₀ of the angle below which the extrapolated forward peak is held constant.
const FLOOR_ANGLE_RATIO: f64 = 1e-3;

/// A tabulated, normalised phase function with power-law interpolation in 1 − cos θ.
#[derive(Clone, Debug)]
pub struct TabulatedPhase {
    /// Nodes xᵢ = 1 − cos θᵢ, increasing; `x[0]` is the floor x_c, `x[1]` the first table angle.
    x: Vec<f64>,
    /// Normalised density at the nodes (sr⁻¹).
    p: Vec<f64>,
    /// Power-law exponent of each piece [xⱼ, xⱼ₊₁].
    slope: Vec<f64>,
    /// `cdf[i]` = probability that 1 − cos θ < xᵢ.
    cdf: Vec<f64>,
    mean_cosine: f64,
    raw_integral: f64,
    first_angle_deg: f64,
}

/// A validation failure, optionally at a row of the table (0-based).
struct RowError {
    row: Option<usize>,
    message: String,
}

impl TabulatedPhase {
    /// From angles in degrees (strictly increasing, first > 0, last = 180) and positive finite
    /// values (any unit; normalised here).
    pub fn from_samples(angles_deg: &[f64], values: &[f64]) -> Result<TabulatedPhase, String> {
        Self::build(angles_deg, values).map_err(|e| match e.row {
            Some(i) => format!("tabulated phase function, sample #{i}: {}", e.message),
            None => format!("tabulated phase function: {}", e.message),
        })
    }

    /// From a CSV file of `angle_deg,value` rows; `#` starts a comment line, and the first
    /// non-comment line may be a header. Errors name the file and line.
    pub fn from_csv(path: &Path) -> Result<TabulatedPhase, String> {
        let text = std::fs::read_to_string(path).map_err(|e| read_error_message(path, &e))?;
        Self::from_csv_text(path, &text)
    }

    /// [`TabulatedPhase::from_csv`] of the file's text; `path` names it in errors.
    pub fn from_csv_text(path: &Path, text: &str) -> Result<TabulatedPhase, String> {
        let (lines, angles, values) = parse_csv(path, text)?;
        Self::build(&angles, &values).map_err(|e| match e.row {
            Some(i) => format!("{}:{}: {}", path.display(), lines[i], e.message),
            None => format!("{}: {}", path.display(), e.message),
        })
    }

    fn build(angles_deg: &[f64], values: &[f64]) -> Result<TabulatedPhase, RowError> {
        validate(angles_deg, values)?;
        let (x, beta) = extend_forward(angles_deg, values)?;
        let slope: Vec<f64> = (0..x.len() - 1).map(|j| (beta[j + 1] / beta[j]).ln() / (x[j + 1] / x[j]).ln()).collect();
        let (mass, moment) = piece_masses(&x, &beta, &slope);
        let total: f64 = mass.iter().sum();
        let cdf = mass
            .iter()
            .scan(0.0, |acc, m| {
                *acc += m / total;
                Some(*acc)
            })
            .collect();
        Ok(TabulatedPhase {
            p: beta.iter().map(|b| b / total).collect(),
            x,
            slope,
            cdf,
            mean_cosine: 1.0 - moment / total,
            raw_integral: total,
            first_angle_deg: angles_deg[0],
        })
    }

    /// The normalised density at cos θ.
    pub fn eval(&self, cos_theta: f64) -> f64 {
        let x = (1.0 - cos_theta).clamp(0.0, 2.0);
        if x <= self.x[0] {
            return self.p[0];
        }
        let j = self.piece(x);
        self.p[j] * (self.slope[j] * (x / self.x[j]).ln()).exp()
    }

    /// Inverse of the piecewise closed-form CDF (module documentation).
    pub fn sample_cos_theta(&self, u0: f64) -> f64 {
        let target = u0.clamp(0.0, 1.0);
        if target < self.cdf[0] {
            return 1.0 - target / (2.0 * PI * self.p[0]);
        }
        let j = self.cdf.partition_point(|c| *c <= target).saturating_sub(1).min(self.x.len() - 2);
        let y = (target - self.cdf[j]) / (2.0 * PI * self.p[j] * self.x[j]);
        // Solve ∫₁ᵗ s^{q−1} ds = y for t = x/xⱼ: ln t = ln(1 + q y)/q (→ y as q → 0).
        let q = self.slope[j] + 1.0;
        let x = if q.abs() < 1e-12 {
            self.x[j] * y.exp()
        } else if q * y > -1.0 {
            self.x[j] * ((q * y).ln_1p() / q).exp()
        } else {
            self.x[j + 1]
        };
        1.0 - x.clamp(self.x[j], self.x[j + 1])
    }

    /// Fraction of the scattering at angles below `theta_deg` (a CDF in angle).
    pub fn scattered_within(&self, theta_deg: f64) -> f64 {
        let t = theta_deg.clamp(0.0, 180.0).to_radians();
        let x = 2.0 * (t / 2.0).sin().powi(2);
        if x <= self.x[0] {
            return 2.0 * PI * self.p[0] * x;
        }
        let j = self.piece(x);
        let partial = 2.0 * PI * self.p[j] * self.x[j] * power_integral(self.slope[j] + 1.0, x / self.x[j]);
        (self.cdf[j] + partial).min(1.0)
    }

    /// The mean cosine, exact for the interpolated table.
    pub fn mean_cosine(&self) -> f64 {
        self.mean_cosine
    }

    /// ∫ β dω of the values as given, including the extrapolated forward peak (1 for a table
    /// that was already a normalised phase function).
    pub fn raw_integral(&self) -> f64 {
        self.raw_integral
    }

    /// Fraction of the scattering below the first tabulated angle: the extrapolated part.
    pub fn fraction_below_first_angle(&self) -> f64 {
        self.cdf[1]
    }

    /// The first tabulated angle θ₀ and the angle θ_c below which the density is constant (°).
    pub fn forward_angles_deg(&self) -> (f64, f64) {
        (self.first_angle_deg, self.first_angle_deg * FLOOR_ANGLE_RATIO)
    }

    /// Index j of the piece [xⱼ, xⱼ₊₁] holding x > x₀.
    fn piece(&self, x: f64) -> usize {
        self.x.partition_point(|xi| *xi <= x).saturating_sub(1).min(self.x.len() - 2)
    }
}

/// The message for a table file that cannot be read.
fn read_error_message(path: &Path, e: &std::io::Error) -> String {
    if e.kind() == std::io::ErrorKind::NotFound {
        format!(
            "phase function table {} not found: give the path of a CSV file of 'angle_deg,value_per_sr' rows",
            path.display()
        )
    } else {
        format!("phase function table {} cannot be read: {e}", path.display())
    }
}

/// The masses ∫ β dω of the constant cap [0, x₀] and of each power-law piece [xⱼ, xⱼ₊₁]
/// (2π βⱼ xⱼ ∫₁ʳ t^{a} dt, r = xⱼ₊₁/xⱼ), and the first moment ∫ (1 − cos θ) β dω of the whole.
fn piece_masses(x: &[f64], beta: &[f64], slope: &[f64]) -> (Vec<f64>, f64) {
    let mut mass = vec![2.0 * PI * beta[0] * x[0]];
    let mut moment = PI * beta[0] * x[0] * x[0];
    for j in 0..x.len() - 1 {
        let r = x[j + 1] / x[j];
        mass.push(2.0 * PI * beta[j] * x[j] * power_integral(slope[j] + 1.0, r));
        moment += 2.0 * PI * beta[j] * x[j] * x[j] * power_integral(slope[j] + 2.0, r);
    }
    (mass, moment)
}

/// ∫₁ʳ t^{q−1} dt = (r^q − 1)/q, stable as q → 0 (where it is ln r).
fn power_integral(q: f64, r: f64) -> f64 {
    let l = r.ln();
    let z = q * l;
    if z.abs() < 1e-8 { l * (1.0 + z / 2.0) } else { z.exp_m1() / q }
}

/// Nodes x = 1 − cos θ and values, with the forward floor node x_c prepended: the first
/// segment's power law continued down to θ_c = θ₀ · `FLOOR_ANGLE_RATIO`.
fn extend_forward(angles_deg: &[f64], values: &[f64]) -> Result<(Vec<f64>, Vec<f64>), RowError> {
    let one_minus_cos = |deg: f64| 2.0 * (deg.to_radians() / 2.0).sin().powi(2);
    let mut x: Vec<f64> = angles_deg.iter().map(|a| one_minus_cos(*a)).collect();
    let mut beta = values.to_vec();
    let a0 = (beta[1] / beta[0]).ln() / (x[1] / x[0]).ln();
    let x_c = one_minus_cos(angles_deg[0] * FLOOR_ANGLE_RATIO);
    let beta_c = beta[0] * (x_c / x[0]).powf(a0);
    if !(beta_c.is_finite() && beta_c > 0.0) {
        return Err(RowError {
            row: Some(0),
            message: format!(
                "the forward peak extrapolated from the first two rows (slope {:.3} in log θ) overflows \
                 at {}°: the first rows must not fall or rise that steeply",
                2.0 * a0,
                angles_deg[0] * FLOOR_ANGLE_RATIO
            ),
        });
    }
    x.insert(0, x_c);
    beta.insert(0, beta_c);
    Ok((x, beta))
}

/// Angles strictly increasing in (0, 180] ending at 180; values positive and finite.
fn validate(angles_deg: &[f64], values: &[f64]) -> Result<(), RowError> {
    let err = |row: Option<usize>, message: String| Err(RowError { row, message });
    if angles_deg.len() != values.len() {
        return err(None, format!("{} angles but {} values: need one value per angle", angles_deg.len(), values.len()));
    }
    if angles_deg.len() < 2 {
        return err(
            None,
            format!("{} row(s): need at least 2 angles, from a smallest angle > 0° to 180°", angles_deg.len()),
        );
    }
    for (i, (&a, &v)) in angles_deg.iter().zip(values).enumerate() {
        if !(a.is_finite() && a > 0.0 && a <= 180.0) {
            return err(Some(i), format!("angle {a}° is out of range: angles must lie in (0°, 180°]"));
        }
        if !(v.is_finite() && v > 0.0) {
            return err(Some(i), format!("value {v} at {a}° is not allowed: values must be positive and finite"));
        }
        if i > 0 && a <= angles_deg[i - 1] {
            return err(Some(i), format!("angle {a}° follows {}°: angles must increase strictly", angles_deg[i - 1]));
        }
    }
    let last = angles_deg.len() - 1;
    if angles_deg[last] != 180.0 {
        return err(Some(last), format!("the last angle is {}°: the table must end at 180°", angles_deg[last]));
    }
    Ok(())
}

/// 1-based line numbers, angles and values of a table's rows.
type Rows = (Vec<usize>, Vec<f64>, Vec<f64>);

/// Rows of `angle,value` with their line numbers; comment lines start with `#`, and the first
/// non-comment line may be a header.
fn parse_csv(path: &Path, text: &str) -> Result<Rows, String> {
    let (mut lines, mut angles, mut values) = (Vec::new(), Vec::new(), Vec::new());
    let mut header_allowed = true;
    for (i, raw) in text.lines().enumerate() {
        let line = raw.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        match parse_row(line) {
            Some((a, v)) => {
                lines.push(i + 1);
                angles.push(a);
                values.push(v);
            }
            None if header_allowed && line.chars().any(|c| c.is_alphabetic()) => {}
            None => {
                return Err(format!(
                    "{}:{}: expected two numbers 'angle_deg,value_per_sr', found '{line}'",
                    path.display(),
                    i + 1
                ));
            }
        }
        header_allowed = false;
    }
    Ok((lines, angles, values))
}

fn parse_row(line: &str) -> Option<(f64, f64)> {
    let mut fields = line.split(',').map(str::trim);
    let a = fields.next()?.parse().ok()?;
    let v = fields.next()?.parse().ok()?;
    fields.next().is_none().then_some((a, v))
}
