//! Progressive passes (Knaus & Zwicker 2011): the running mean and pass-to-pass spread of
//! every output value, and the rules that end the run.
//!
//! Pass i of a run traces fresh photon maps from the seed of (seed, i) and gathers with the
//! shrunk kernels of [`crate::photon_map::progressive`]; its image, sensor readings and profile
//! rows are independent of the other passes', so their mean over N passes has the standard
//! error s/√N, s² the sample variance of the passes (Welford 1962, one pass over the data):
//!
//! nₖ = nₖ₋₁ + 1,  δ = x − x̄ₖ₋₁,  x̄ₖ = x̄ₖ₋₁ + δ/nₖ,  Mₖ = Mₖ₋₁ + δ (x − x̄ₖ),
//! SE = √(M / (n (n − 1))).
//!
//! (The passes are independent but not identically distributed: later passes have less bias
//! and more variance. The spread of the passes then bounds the error of the mean from above
//! for the variance part, and the bias that remains is what the shrinking radii remove.)
//!
//! A one-pass run keeps its values untouched (no accumulator is allocated), so its outputs are
//! those of a render without passes, byte for byte.
//!
//! # References
//! - B. P. Welford (1962), "Note on a method for calculating corrected sums of squares and
//!   products", Technometrics 4(3), 419–420.

use super::checkpoint::codec::{Reader, Result as ReadResult, Writer};
use crate::scene::IntegratorSettings;
pub use crate::scene::progressive::label as target_label;
use crate::scene::progressive::{Progressive, Target};
use serde::Serialize;

/// A value [`Welford`] accumulates: stored as itself after one pass, as f64 after two.
pub trait Value: Copy + Into<f64> {
    /// The value nearest to `x`.
    fn from_f64(x: f64) -> Self;
}

impl Value for f32 {
    fn from_f64(x: f64) -> f32 {
        x as f32
    }
}

impl Value for f64 {
    fn from_f64(x: f64) -> f64 {
        x
    }
}

/// The running mean and spread of a fixed-length vector of values over passes.
#[derive(Clone, Debug)]
pub struct Welford<T> {
    n: u32,
    /// The first pass's values, kept as they are until a second pass arrives.
    first: Vec<T>,
    mean: Vec<f64>,
    m2: Vec<f64>,
}

impl<T> Default for Welford<T> {
    fn default() -> Self {
        Welford { n: 0, first: Vec::new(), mean: Vec::new(), m2: Vec::new() }
    }
}

impl<T: Value> Welford<T> {
    /// Adds one pass's values (the same length every time).
    pub fn add(&mut self, x: Vec<T>) {
        self.n += 1;
        if self.n == 1 {
            self.first = x;
            return;
        }
        if self.n == 2 {
            self.mean = self.first.iter().map(|v| (*v).into()).collect();
            self.m2 = vec![0.0; self.mean.len()];
            self.first = Vec::new();
        }
        let n = f64::from(self.n);
        for ((m, m2), v) in self.mean.iter_mut().zip(&mut self.m2).zip(&x) {
            let v: f64 = (*v).into();
            let d = v - *m;
            *m += d / n;
            *m2 += d * (v - *m);
        }
    }

    /// Passes added.
    pub fn passes(&self) -> u32 {
        self.n
    }

    /// The mean of the passes (the first pass's values themselves after one pass).
    pub fn mean(self) -> Vec<T> {
        if self.n <= 1 { self.first } else { self.mean.iter().map(|m| T::from_f64(*m)).collect() }
    }

    /// Appends the state to a checkpoint, every value bit for bit.
    pub fn save(&self, w: &mut Writer) {
        w.u32(self.n);
        w.f64s(&self.first.iter().map(|v| (*v).into()).collect::<Vec<f64>>());
        w.f64s(&self.mean);
        w.f64s(&self.m2);
    }

    /// The state [`Welford::save`] wrote (`T` → f64 → `T` is exact for f32 and f64).
    pub fn load(r: &mut Reader) -> ReadResult<Welford<T>> {
        let n = r.u32()?;
        let first = r.f64s()?.into_iter().map(T::from_f64).collect();
        Ok(Welford { n, first, mean: r.f64s()?, m2: r.f64s()? })
    }

    /// The standard error of the mean, √(M/(n(n − 1))), per value; `None` before two passes.
    pub fn std_error(&self) -> Option<Vec<T>> {
        (self.n >= 2).then(|| {
            let n = f64::from(self.n);
            self.m2.iter().map(|m2| T::from_f64((m2.max(0.0) / (n * (n - 1.0))).sqrt())).collect()
        })
    }
}

/// The running mean and spread of one number over passes.
#[derive(Clone, Copy, Debug, Default)]
pub struct Scalar {
    n: u32,
    mean: f64,
    m2: f64,
}

impl Scalar {
    /// Adds one pass's value.
    pub fn add(&mut self, x: f64) {
        self.n += 1;
        let d = x - self.mean;
        self.mean += d / f64::from(self.n);
        self.m2 += d * (x - self.mean);
    }

    /// The mean so far.
    pub fn mean(&self) -> f64 {
        self.mean
    }

    /// Appends the state to a checkpoint.
    pub fn save(&self, w: &mut Writer) {
        w.u32(self.n);
        w.f64(self.mean);
        w.f64(self.m2);
    }

    /// The state [`Scalar::save`] wrote.
    pub fn load(r: &mut Reader) -> ReadResult<Scalar> {
        Ok(Scalar { n: r.u32()?, mean: r.f64()?, m2: r.f64()? })
    }

    /// The relative standard error of the mean, SE/|mean|; `None` before two passes or for a
    /// zero mean.
    pub fn rel_error(&self) -> Option<f64> {
        if self.n < 2 || self.mean == 0.0 {
            return None;
        }
        let n = f64::from(self.n);
        Some((self.m2.max(0.0) / (n * (n - 1.0))).sqrt() / self.mean.abs())
    }
}

/// Which rule ended a run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Rule {
    /// The passes asked for are done (one pass when no rule was given).
    Passes,
    /// The next pass would have ended past the time budget.
    Time,
    /// The relative standard error fell below the target.
    TargetRelError,
    /// The run's deadline (`--max-seconds`) cut a pass short: the passes finished before it
    /// are kept.
    MaxSeconds,
}

/// Why a run stopped, for the report.
#[derive(Clone, Debug, Serialize)]
pub struct Stop {
    /// The rule.
    pub rule: Rule,
    /// In words.
    pub why: String,
}

/// One finished pass, as `report.json` records it.
#[derive(Clone, Debug, Serialize)]
pub struct PassRecord {
    /// The pass, from 1.
    pub pass: u32,
    /// Wall time since the run started when the pass ended, s.
    pub elapsed_s: f64,
    /// Wall time of the pass, s.
    pub seconds: f64,
    /// Nearest photons per global-map estimate in the pass (the kernels shrink with k).
    pub k: usize,
    /// Largest gather radius of the global map in the pass, m.
    pub max_radius_m: f64,
    /// The mean of the target over the passes so far.
    pub target_mean: f64,
    /// The relative standard error the stopping rule saw after this pass (from the second
    /// pass): of that mean, or under `target = "pixels"` the pixels' ([`pixel_rel_error`]).
    pub rel_error: Option<f64>,
}

impl PassRecord {
    /// Appends the record to a checkpoint.
    pub fn save(&self, w: &mut Writer) {
        w.u32(self.pass);
        w.f64(self.elapsed_s);
        w.f64(self.seconds);
        w.usize(self.k);
        w.f64(self.max_radius_m);
        w.f64(self.target_mean);
        w.opt_f64(self.rel_error);
    }

    /// The record [`PassRecord::save`] wrote.
    pub fn load(r: &mut Reader) -> ReadResult<PassRecord> {
        Ok(PassRecord {
            pass: r.u32()?,
            elapsed_s: r.f64()?,
            seconds: r.f64()?,
            k: usize::try_from(r.u64()?).map_err(|_| "k is out of range".to_string())?,
            max_radius_m: r.f64()?,
            target_mean: r.f64()?,
            rel_error: r.opt_f64()?,
        })
    }
}

/// The progressive run as `report.json` records it.
#[derive(Clone, Debug, Default, Serialize)]
pub struct ProgressiveReport {
    /// Passes run.
    pub passes: u32,
    /// Knaus & Zwicker's α.
    pub alpha: f64,
    /// What the target error is measured on ("image", "pixels", a sensor or a region).
    pub target: String,
    /// The rule that ended the run and why.
    pub stopped: Option<Stop>,
    /// The passes taken from a checkpoint (`--resume`): the history holds them, the other
    /// counts of `report.json` (rays, photons, phase times) only the passes this run made.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub resumed_after_pass: Option<u32>,
    /// The checkpoint file this run keeps in its output directory (progressive runs).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub checkpoint: Option<String>,
    /// The relative standard error the stopping rule saw at the end (from two passes): of the
    /// target's mean, or under `target = "pixels"` the 95 % quantile of the pixels'
    /// ([`pixel_rel_error`]).
    pub rel_error: Option<f64>,
    /// The mean, over every pixel and band with a positive value, of its relative standard
    /// error (from two passes).
    pub image_mean_rel_error: Option<f64>,
    /// The error estimate after each pass against elapsed time.
    pub history: Vec<PassRecord>,
    /// Adaptive sampling, when it was on ([`super::adaptive`]): the budget and how the last
    /// pass spent it.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub adaptive: Option<super::adaptive::AdaptiveReport>,
    /// The least-squares line through the history on log-log axes (from two passes with an
    /// error estimate, i.e. three passes).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub convergence_fit: Option<Fit>,
}

/// The least-squares line ln e = intercept + slope · ln t through the passes' relative
/// standard errors e against the elapsed time t: the error falls as t^slope.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Fit {
    /// d ln e / d ln t.
    pub slope: f64,
    /// ln e at t = 1 s.
    pub intercept: f64,
    /// Passes fitted (those with a positive error estimate and elapsed time).
    pub points: usize,
}

/// The ordinary least-squares fit of ln e on ln t over the passes of `history` with a positive
/// relative standard error and elapsed time: slope = Σ(x − x̄)(y − ȳ) / Σ(x − x̄)²,
/// intercept = ȳ − slope x̄. `None` with fewer than two such passes or a single time.
pub fn fit(history: &[PassRecord]) -> Option<Fit> {
    let pts: Vec<(f64, f64)> = history
        .iter()
        .filter_map(|r| r.rel_error.map(|e| (r.elapsed_s, e)))
        .filter(|(t, e)| *t > 0.0 && *e > 0.0 && t.is_finite() && e.is_finite())
        .map(|(t, e)| (t.ln(), e.ln()))
        .collect();
    let n = pts.len() as f64;
    let (mx, my) = (pts.iter().map(|p| p.0).sum::<f64>() / n, pts.iter().map(|p| p.1).sum::<f64>() / n);
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (pts.len() >= 2 && sxx > 0.0).then(|| {
        let slope = sxy / sxx;
        Fit { slope, intercept: my - slope * mx, points: pts.len() }
    })
}

/// Every output of a run, accumulated over its passes.
#[derive(Clone, Debug, Default)]
pub struct Outputs {
    image: Welford<f32>,
    sensors: Vec<Welford<f64>>,
    profiles: Vec<Welford<f64>>,
    sensor_shapes: Vec<crate::sensor::Reading>,
    profile_shapes: Vec<crate::sensor::ProfileReading>,
    /// Each pixel's mean over its bands, under `target = "pixels"` ([`pixel_rel_error`]).
    pixels: Option<Welford<f64>>,
}

impl Outputs {
    /// Adds one pass's image band values and readings.
    pub fn add(
        &mut self,
        data: Vec<f32>,
        sensors: Vec<crate::sensor::Reading>,
        profiles: Vec<crate::sensor::ProfileReading>,
    ) {
        if self.image.passes() == 0 {
            self.sensors = sensors.iter().map(|_| Welford::default()).collect();
            self.profiles = profiles.iter().map(|_| Welford::default()).collect();
        }
        self.image.add(data);
        for (w, r) in self.sensors.iter_mut().zip(&sensors) {
            w.add(r.columns.iter().flat_map(|c| c.1.iter().copied()).collect());
        }
        for (w, p) in self.profiles.iter_mut().zip(&profiles) {
            w.add(profile_values(p));
        }
        self.sensor_shapes = sensors;
        self.profile_shapes = profiles;
    }

    /// Adds one pass's per-pixel band means ([`band_means`]); called for every pass of a run
    /// whose target is `pixels`, after [`Outputs::add`].
    pub fn add_pixels(&mut self, means: Vec<f64>) {
        self.pixels.get_or_insert_with(Welford::default).add(means);
    }

    /// [`pixel_rel_error`] of the pixels' band means so far (`None` before two passes, or
    /// when the run does not track them).
    pub fn pixel_rel_error(&self) -> Option<f64> {
        let w = self.pixels.as_ref()?;
        pixel_rel_error(&w.mean, &w.std_error()?)
    }

    /// Passes added.
    pub fn passes(&self) -> u32 {
        self.image.passes()
    }

    /// Appends the state to a checkpoint: the image's, each sensor's and each profile's
    /// running sums, the readings' shapes (names, points, depths) of the last pass, and the
    /// pixels' band means when the run tracks them.
    pub fn save(&self, w: &mut Writer) {
        self.image.save(w);
        w.usize(self.sensors.len());
        for (s, r) in self.sensors.iter().zip(&self.sensor_shapes) {
            s.save(w);
            save_reading(w, r);
        }
        w.usize(self.profiles.len());
        for (s, p) in self.profiles.iter().zip(&self.profile_shapes) {
            s.save(w);
            save_profile(w, p);
        }
        w.u32(u32::from(self.pixels.is_some()));
        if let Some(p) = &self.pixels {
            p.save(w);
        }
    }

    /// The state [`Outputs::save`] wrote.
    pub fn load(r: &mut Reader) -> ReadResult<Outputs> {
        let mut o = Outputs { image: Welford::load(r)?, ..Outputs::default() };
        for _ in 0..r.len(8)? {
            o.sensors.push(Welford::load(r)?);
            o.sensor_shapes.push(load_reading(r)?);
        }
        for _ in 0..r.len(8)? {
            o.profiles.push(Welford::load(r)?);
            o.profile_shapes.push(load_profile(r)?);
        }
        o.pixels = match r.u32()? {
            0 => None,
            1 => Some(Welford::load(r)?),
            _ => return Err("its pixel statistics are neither absent nor present".into()),
        };
        if o.pixels.as_ref().is_some_and(|p| p.passes() != o.passes()) {
            return Err("its pixel statistics hold another number of passes than its image".into());
        }
        Ok(o)
    }

    /// The image's band values so far (the mean of the passes) and their standard errors.
    pub fn image_error(&self) -> Option<Vec<f32>> {
        self.image.std_error()
    }

    /// The means: image band values, their standard errors (from two passes), the sensor
    /// readings (with a `<column>_se` column per column from two passes) and the profiles
    /// (with their standard errors from two passes).
    pub fn finish(self) -> Finished {
        let image_se = self.image.std_error();
        let image = self.image.mean();
        let sensors = self
            .sensors
            .into_iter()
            .zip(self.sensor_shapes)
            .map(|(w, mut r)| {
                let se = w.std_error();
                refill(&mut r, &w.mean());
                if let Some(se) = se {
                    let mut with_se = r.clone();
                    refill(&mut with_se, &se);
                    let se_columns: Vec<(String, Vec<f64>)> =
                        with_se.columns.into_iter().map(|(n, v)| (format!("{n}_se"), v)).collect();
                    r.columns.extend(se_columns);
                }
                r
            })
            .collect();
        let profiles = self
            .profiles
            .into_iter()
            .zip(self.profile_shapes)
            .map(|(w, mut p)| {
                let se = w.std_error();
                set_profile_values(&mut p, &w.mean());
                p.std_error = se.map(|se| profile_error(&p, &se));
                p
            })
            .collect();
        Finished { image, image_se, sensors, profiles }
    }
}

/// What [`Outputs::finish`] returns.
pub struct Finished {
    /// Band values per pixel, the mean over passes.
    pub image: Vec<f32>,
    /// Their standard errors (two passes or more).
    pub image_se: Option<Vec<f32>>,
    /// Sensor readings, means, with `_se` columns after two passes.
    pub sensors: Vec<crate::sensor::Reading>,
    /// Profile readings, means.
    pub profiles: Vec<crate::sensor::ProfileReading>,
}

fn save_reading(w: &mut Writer, r: &crate::sensor::Reading) {
    w.str(&r.name);
    w.str(&r.quantity);
    w.str(&r.unit);
    w.usize(r.nx);
    w.usize(r.ny);
    w.f64s(&r.points.iter().flat_map(|p| p.to_array()).collect::<Vec<f64>>());
    w.usize(r.columns.len());
    for (name, v) in &r.columns {
        w.str(name);
        w.f64s(v);
    }
}

fn load_reading(r: &mut Reader) -> ReadResult<crate::sensor::Reading> {
    let (name, quantity, unit) = (r.str()?, r.str()?, r.str()?);
    let size = |x: u64| usize::try_from(x).map_err(|_| "a grid size is out of range".to_string());
    let (nx, ny) = (size(r.u64()?)?, size(r.u64()?)?);
    let points = r.f64s()?.chunks_exact(3).map(|c| glam::DVec3::new(c[0], c[1], c[2])).collect();
    let mut columns = Vec::new();
    for _ in 0..r.len(16)? {
        columns.push((r.str()?, r.f64s()?));
    }
    Ok(crate::sensor::Reading { name, quantity, unit, nx, ny, points, columns })
}

fn save_profile(w: &mut Writer, p: &crate::sensor::ProfileReading) {
    w.str(&p.name);
    w.f64s(
        &p.rows.iter().flat_map(|r| [r.depth_m, r.wavelength_nm, r.ed, r.eu, r.eod, r.eou, r.lu]).collect::<Vec<_>>(),
    );
    w.f64s(&p.surface.iter().flatten().copied().collect::<Vec<_>>());
}

fn load_profile(r: &mut Reader) -> ReadResult<crate::sensor::ProfileReading> {
    let name = r.str()?;
    let rows = r.f64s()?;
    let rows = rows
        .chunks_exact(7)
        .map(|c| crate::sensor::ProfileRow {
            depth_m: c[0],
            wavelength_nm: c[1],
            ed: c[2],
            eu: c[3],
            eod: c[4],
            eou: c[5],
            lu: c[6],
        })
        .collect();
    let surface = r.f64s()?.chunks_exact(5).map(|c| [c[0], c[1], c[2], c[3], c[4]]).collect();
    Ok(crate::sensor::ProfileReading { name, rows, surface, std_error: None })
}

/// Puts `values` (columns one after the other) back into `r`'s columns.
fn refill(r: &mut crate::sensor::Reading, values: &[f64]) {
    let mut it = values.iter();
    for (_, c) in &mut r.columns {
        c.iter_mut().for_each(|v| *v = it.next().copied().unwrap_or(0.0));
    }
}

/// A profile's measured values in a fixed order: per row Ed, Eu, Eod, Eou, Lu; per band of
/// the surface Ed(0+), Lu(0−), Lw, Rrs.
fn profile_values(p: &crate::sensor::ProfileReading) -> Vec<f64> {
    let rows = p.rows.iter().flat_map(|r| [r.ed, r.eu, r.eod, r.eou, r.lu]);
    rows.chain(p.surface.iter().flat_map(|s| s[1..].to_vec())).collect()
}

/// The standard errors `se`, in the order of [`profile_values`], as `p`'s error.
fn profile_error(p: &crate::sensor::ProfileReading, se: &[f64]) -> crate::sensor::ProfileError {
    let (rows, surface) = se.split_at((5 * p.rows.len()).min(se.len()));
    crate::sensor::ProfileError {
        rows: rows.chunks_exact(5).map(|c| [c[0], c[1], c[2], c[3], c[4]]).collect(),
        surface: surface.chunks_exact(4).map(|c| [c[0], c[1], c[2], c[3]]).collect(),
    }
}

/// Writes values in the order of [`profile_values`] back into `p`.
fn set_profile_values(p: &mut crate::sensor::ProfileReading, values: &[f64]) {
    let mut it = values.iter().copied();
    let mut next = || it.next().unwrap_or(0.0);
    for r in &mut p.rows {
        [r.ed, r.eu, r.eod, r.eou, r.lu] = [next(), next(), next(), next(), next()];
    }
    for s in &mut p.surface {
        s[1..].iter_mut().for_each(|v| *v = next());
    }
}

/// Decides after `done` passes whether the run stops: the target reached, the passes asked for
/// done, or the next pass — predicted to take as long as the last one, `last_s` — ending past
/// the time budget measured from the run's start (`elapsed_s` now).
pub fn decide(p: &Progressive, done: u32, elapsed_s: f64, last_s: f64, rel: Option<f64>) -> Option<Stop> {
    if let (Some(target), Some(e)) = (p.target_rel_error, rel)
        && e <= target
    {
        return Some(Stop {
            rule: Rule::TargetRelError,
            why: format!("after {done} passes the relative standard error {e:.3e} is at most the target {target:e}"),
        });
    }
    if done >= p.pass_limit() {
        let why = match p.passes {
            Some(n) => format!("the {n} passes asked for are done"),
            None if p.time_s.is_none() && p.target_rel_error.is_none() => {
                "one pass: no --passes, --time or --target-rel-error given".to_string()
            }
            None => format!("the limit of {done} passes is reached"),
        };
        return Some(Stop { rule: Rule::Passes, why });
    }
    if let Some(budget) = p.time_s
        && elapsed_s + last_s > budget
    {
        return Some(Stop {
            rule: Rule::Time,
            why: format!(
                "after {done} passes and {elapsed_s:.2} s, another pass (≈ {last_s:.2} s, as the last) would end past the {budget} s budget"
            ),
        });
    }
    None
}

/// The value the target error is measured on, from one pass's image (`nb` bands per pixel,
/// `width` pixels per row) and readings: the mean over the target's values.
pub fn target_value(
    target: &Target,
    (data, width, nb): (&[f32], usize, usize),
    sensors: &[crate::sensor::Reading],
    profiles: &[crate::sensor::ProfileReading],
) -> f64 {
    let mean = |v: &mut dyn Iterator<Item = f64>| {
        let (s, n) = v.fold((0.0, 0usize), |(s, n), x| (s + x, n + 1));
        if n == 0 { 0.0 } else { s / n as f64 }
    };
    match target {
        Target::Image | Target::Pixels => mean(&mut data.iter().map(|v| f64::from(*v))),
        Target::Region([x0, y0, x1, y1]) => mean(
            &mut (*y0..*y1)
                .flat_map(|y| (*x0..*x1).map(move |x| y * width + x))
                .flat_map(|p| data[p * nb..(p + 1) * nb].iter().map(|v| f64::from(*v))),
        ),
        Target::Sensor(name) => {
            if let Some(r) = sensors.iter().find(|r| &r.name == name) {
                return mean(&mut r.columns[0].1.iter().copied());
            }
            profiles.iter().find(|p| &p.name == name).map_or(0.0, |p| mean(&mut p.rows.iter().map(|r| r.ed)))
        }
    }
}

/// The record of pass `pass` (0-based) run with settings `s`, with the target's mean and the
/// relative error the stopping rule sees (`rel_error`).
pub fn record(
    pass: u32,
    s: &IntegratorSettings,
    (elapsed_s, seconds): (f64, f64),
    (target, rel_error): (&Scalar, Option<f64>),
) -> PassRecord {
    PassRecord {
        pass: pass + 1,
        elapsed_s,
        seconds,
        k: s.k,
        max_radius_m: s.max_radius_m,
        target_mean: target.mean(),
        rel_error,
    }
}

/// Under `target = "pixels"`, the share of the pixels whose error must be at most the target.
pub const PIXEL_SHARE: f64 = 0.95;

/// Under `target = "pixels"`, a pixel darker than this fraction of the image's mean has its
/// standard error taken relative to that fraction of the mean instead of its own value.
pub const PIXEL_FLOOR: f64 = 0.1;

/// Each pixel's mean over its `nb` bands, from one pass's band values.
pub fn band_means(data: &[f32], nb: usize) -> Vec<f64> {
    let nb = nb.max(1);
    data.chunks(nb).map(|px| px.iter().map(|v| f64::from(*v)).sum::<f64>() / nb as f64).collect()
}

/// The error of a picture, which `target = "pixels"` stops on: with m_p the mean of pixel p's
/// band means over the passes, s_p its standard error (from the passes' spread, like the
/// image's error layer) and m̄ the mean of the m_p over the image, each pixel's relative error
/// is
///
/// e_p = s_p / max(m_p, f m̄),  f = [`PIXEL_FLOOR`] = 0.1,
///
/// and the statistic is the nearest-rank [`PIXEL_SHARE`] quantile of the e_p: the smallest
/// e such that at least 95 % of the pixels have e_p ≤ e (sorted ascending, the value of rank
/// ⌈0.95 N⌉). A target is met when 95 % of the pixels are within it, so a few glints or
/// edges that take far longer to converge do not hold up a picture, and a pixel much darker
/// than the image is judged by its noise against a tenth of the image's mean, which is what
/// an exposure set by the mean shows of it. `None` for an empty or black image (m̄ ≤ 0) or
/// values that are not finite.
///
/// The band mean is the pixel's own quantity here, not a sum of the bands' errors: its spread
/// over the passes carries the correlation of the bands (they share photons and paths), which
/// the bands' standard errors alone would miss.
pub fn pixel_rel_error(mean: &[f64], se: &[f64]) -> Option<f64> {
    let image = mean.iter().sum::<f64>() / mean.len() as f64;
    if mean.is_empty() || mean.len() != se.len() || !(image.is_finite() && image > 0.0) {
        return None;
    }
    let floor = PIXEL_FLOOR * image;
    let mut e: Vec<f64> = mean.iter().zip(se).map(|(m, s)| s / m.max(floor)).collect();
    if e.iter().any(|x| !x.is_finite()) {
        return None;
    }
    let rank = ((PIXEL_SHARE * e.len() as f64).ceil() as usize).clamp(1, e.len());
    let (_, x, _) = e.select_nth_unstable_by(rank - 1, f64::total_cmp);
    Some(*x)
}

/// The mean over values with a positive mean of SE/mean (`None` when there are none).
pub fn mean_rel_error(mean: &[f32], se: &[f32]) -> Option<f64> {
    let (s, n) = mean
        .iter()
        .zip(se)
        .filter(|(m, _)| **m > 0.0)
        .fold((0.0, 0usize), |(s, n), (m, e)| (s + f64::from(*e) / f64::from(*m), n + 1));
    (n > 0).then(|| s / n as f64)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn welford_matches_the_two_pass_formulas() {
        let passes = [[1.0f32, 10.0], [2.0, 10.0], [4.0, 13.0], [5.0, 7.0]];
        let mut w = Welford::<f32>::default();
        for p in passes {
            w.add(p.to_vec());
        }
        let se = w.std_error().expect("two passes or more");
        for (j, want_mean) in [3.0f64, 10.0].iter().enumerate() {
            let var: f64 = passes.iter().map(|p| (f64::from(p[j]) - want_mean).powi(2)).sum::<f64>() / 3.0;
            assert!((f64::from(se[j]) - (var / 4.0).sqrt()).abs() < 1e-6);
        }
        assert_eq!(w.mean(), vec![3.0, 10.0]);
    }

    #[test]
    fn one_pass_is_kept_bit_for_bit() {
        let mut w = Welford::<f32>::default();
        let x = vec![0.1f32, 3.3e-7, f32::MIN_POSITIVE];
        w.add(x.clone());
        assert!(w.std_error().is_none());
        assert_eq!(w.mean(), x);
    }

    #[test]
    fn the_fit_recovers_a_power_law() {
        // e = 0.3 t^(−1/3) exactly: the fit returns the exponent and ln 0.3.
        let history: Vec<PassRecord> = (1..=6)
            .map(|i| {
                let t = f64::from(i) * 1.7;
                PassRecord {
                    pass: i,
                    elapsed_s: t,
                    seconds: 1.7,
                    k: 1,
                    max_radius_m: 1.0,
                    target_mean: 1.0,
                    rel_error: (i > 1).then(|| 0.3 * t.powf(-1.0 / 3.0)),
                }
            })
            .collect();
        let f = fit(&history).expect("five points");
        assert_eq!(f.points, 5);
        assert!((f.slope + 1.0 / 3.0).abs() < 1e-12 && (f.intercept - 0.3f64.ln()).abs() < 1e-12, "{f:?}");
        assert!(fit(&history[..2]).is_none());
    }

    /// The pixel statistic against hand-counted cases: a nearest-rank quantile (the 95th of
    /// 100 pixels is the 95th smallest error, not an interpolation), the floor at a tenth of the
    /// image's mean for dark pixels, and no value for a black image or non-finite errors.
    #[test]
    fn the_pixel_error_is_the_95_percent_quantile_with_a_floor() {
        // 100 equally bright pixels whose errors are 1 %, 2 %, …, 100 %, shuffled.
        let mean = vec![2.0; 100];
        let se: Vec<f64> = (0..100).map(|i| 2.0 * f64::from((i * 37) % 100 + 1) / 100.0).collect();
        assert!((pixel_rel_error(&mean, &se).expect("a value") - 0.95).abs() < 1e-15);
        // 20 pixels: ⌈0.95 × 20⌉ = 19, so one pixel may be as noisy as it likes.
        let mut se = vec![0.01; 20];
        se[7] = 1e9;
        assert_eq!(pixel_rel_error(&[1.0; 20], &se), Some(0.01));
        se[3] = 1e9;
        assert_eq!(pixel_rel_error(&[1.0; 20], &se), Some(1e9));
        // A dark pixel (mean 0.001 in an image of mean ≈ 1): its error counts against 0.1 of
        // the image's mean, not its own value. One pixel alone sets the quantile.
        let mean = [0.001, 1.999];
        let image = (0.001 + 1.999) / 2.0;
        let got = pixel_rel_error(&mean, &[0.005, 0.0]).expect("a value");
        assert!((got - 0.005 / (0.1 * image)).abs() < 1e-15, "{got}");
        let got = pixel_rel_error(&[0.5, 1.5], &[0.005, 0.0]).expect("a value");
        assert!((got - 0.01).abs() < 1e-15, "above the floor a pixel's own mean: {got}");
        assert_eq!(pixel_rel_error(&[0.0, 0.0], &[0.0, 0.0]), None, "a black image");
        assert_eq!(pixel_rel_error(&[], &[]), None);
        assert_eq!(pixel_rel_error(&[1.0, f64::NAN], &[0.1, 0.1]), None);
        assert_eq!(band_means(&[1.0, 3.0, 5.0, 7.0], 2), vec![2.0, 6.0]);
    }

    #[test]
    fn rules_stop_in_order() {
        let p = Progressive { passes: Some(3), time_s: Some(10.0), target_rel_error: Some(0.01), ..Default::default() };
        assert!(decide(&p, 1, 1.0, 1.0, None).is_none());
        assert_eq!(decide(&p, 2, 2.0, 1.0, Some(0.005)).map(|s| s.rule), Some(Rule::TargetRelError));
        assert_eq!(decide(&p, 2, 9.5, 1.0, Some(0.5)).map(|s| s.rule), Some(Rule::Time));
        assert_eq!(decide(&p, 3, 3.0, 1.0, Some(0.5)).map(|s| s.rule), Some(Rule::Passes));
        assert_eq!(decide(&Progressive::default(), 1, 1.0, 1.0, None).map(|s| s.rule), Some(Rule::Passes));
    }
}
