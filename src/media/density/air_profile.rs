//! The molecular number density of an atmosphere, relative to a reference density:
//! d(x) = N(h(x))/N_ref with N = P N_A/(R* T) from the atmosphere's profile (USA76 or a table,
//! with its height-only edits) and h the height above the atmosphere's Earth (flat or spherical).
//! The density of the air that scatters by Rayleigh scattering ([`crate::media::rayleigh_air`]).
//!
//! # The table
//! N(h)/N_ref is tabulated at heights h_i = i Δh from the ground to the atmosphere's top
//! (Δh ≤ 5 m) and interpolated linearly in h; d = 0 at and above the top, and d = d(0) below the
//! ground (which a scene closes with a surface). For a profile whose density scale height
//! H = −N/(dN/dh) is at least 5.8 km (USA76 below 86 km: 5.9 km at its coldest), linear
//! interpolation changes N by at most Δh² |N''|/8 ≈ Δh²/(8H²) N < 10⁻⁷ N.
//!
//! # Optical depth
//! Along a straight chord the integral ∫ d ds is computed by 16-point Gauss–Legendre quadrature
//! on panels of the part of the chord below the top that each span at most a panel height Δp of
//! height: 1 km, halved for a table whose vertical column needs it (chosen when the table is
//! built; USA76's density keeps 1 km, the AFGL ozone shape takes 500 m). The height along a
//! chord is monotone on either side of its lowest point (its closest approach to the Earth's
//! centre, at distance p), so the panel ends are where the chord crosses the levels hₖ = k Δp, at
//! t = t_low ± √((rₖ − p)(rₖ + p)) with rₖ = R + hₖ. A chord that grazes the Earth thus takes
//! about as many panels as a vertical one (86 rather than 1,050 for a horizon ray through USA76's
//! 86 km), the integrand d(h(t)) is smooth on each, and a kink of the profile at a level falls on
//! a panel's end, as it does up a vertical column.

//! # Majorants
//! Free-flight sampling splits the chord into pieces of at most 1 km of length instead. Each
//! piece is bounded by the largest tabulated value at or above its lowest height (a running
//! maximum from the top down), which bounds the interpolant anywhere on the piece whether or not
//! N decreases with height (it may not, under a strong inversion).

use super::column_table::ColumnTable;
use super::height_moments::{HeightMoments, Moments};
use crate::atmosphere::{Atmosphere, Earth, gas};
use glam::DVec3;
use std::sync::{Arc, OnceLock};

/// Longest height step of the table, m.
const MAX_STEP_M: f64 = 5.0;
/// Longest piece of a chord for majorants, m.
const PIECE_M: f64 = 1_000.0;
/// Largest height span of one quadrature panel, m; a table whose shape needs finer panels
/// halves it (see [`calibrated_panel_m`]).
const PANEL_HEIGHT_M: f64 = 1_000.0;
/// Halvings of [`PANEL_HEIGHT_M`] a table may ask for (down to 31.25 m).
const MAX_PANEL_HALVINGS: u32 = 5;
/// What the panels may lose up a vertical column, relative to the exact integral of the table:
/// a third of the table's own accuracy (10⁻⁷, module docs) and above the ~5 × 10⁻⁹ at which 16
/// nodes per panel stop resolving the 5 m cells of the interpolant.
const PANEL_TOLERANCE: f64 = 3e-8;
/// The most tables [`AirProfile::integrals`] takes in one call (the quadrature's lane count).
pub const MAX_TABLES: usize = 8;

/// d(x) = N(h)/N_ref tabulated in height (see the module docs).
#[derive(Clone, Debug)]
pub struct AirProfile {
    earth: Earth,
    top_m: f64,
    step_m: f64,
    values: Arc<[f64]>,
    max_above: Arc<[f64]>,
    panel_m: f64,
    /// The least e-folding height of d over 1 km windows where d is above 10⁻³ of its largest
    /// value, m ([`AirProfile::least_scale_height_m`]).
    scale_m: f64,
    /// The columns to the top over a spherical Earth, built at first need (shared by clones).
    to_top: Arc<OnceLock<Option<ColumnTable>>>,
    /// The cumulative height moments, built at first need (shared by clones).
    moments: Arc<OnceLock<HeightMoments>>,
    /// False for a profile with slope breaks between tabulated levels, which no column table
    /// may stand for ([`AirProfile::with_slope_breaks`]).
    smooth: bool,
}

impl AirProfile {
    /// The Earth whose heights the profile follows.
    pub fn earth(&self) -> &Earth {
        &self.earth
    }

    /// The number density of `atmosphere` over `earth`, relative to `reference_per_m3`. Fails when
    /// an edit of the atmosphere depends on more than height (a bubble, a grid): then N is not a
    /// function of height.
    pub fn new(atmosphere: &Atmosphere, earth: Earth, reference_per_m3: f64) -> Result<AirProfile, String> {
        if let Some(e) = atmosphere.edits.iter().find(|e| !e.is_height_only()) {
            return Err(format!(
                "atmosphere \"{}\": its edit {e:?} varies along the ground; scattering air needs air that depends on height alone",
                atmosphere.name
            ));
        }
        let at_height = |h: f64| {
            let air = atmosphere.air(point_at_height(&earth, h));
            gas::number_density_per_m3(air.pressure_pa, air.temperature_k) / reference_per_m3
        };
        Ok(AirProfile::from_heights(earth, atmosphere.top_m(), at_height))
    }

    /// Any function `d(h)` ≥ 0 of the height above `earth`, tabulated from the ground to `top_m`
    /// on the same nodes as an atmosphere's air of that top (so tables of one atmosphere's
    /// constituents share their heights, pieces and majorant intervals).
    pub fn from_heights(earth: Earth, top_m: f64, d: impl Fn(f64) -> f64) -> AirProfile {
        let cells = (top_m / MAX_STEP_M).ceil() as usize;
        let step_m = top_m / cells as f64;
        let values: Vec<f64> = (0..=cells).map(|i| d(i as f64 * step_m)).collect();
        let mut max_above = values.clone();
        for i in (0..cells).rev() {
            max_above[i] = max_above[i].max(max_above[i + 1]);
        }
        let scale_m = least_scale_height(&values, step_m);
        let mut table = AirProfile {
            earth,
            top_m,
            step_m,
            values: values.into(),
            max_above: max_above.into(),
            panel_m: 0.0,
            scale_m,
            to_top: Arc::default(),
            moments: Arc::default(),
            smooth: true,
        };
        table.panel_m = calibrated_panel_m(&table);
        table
    }

    /// The same profile marked as having slope breaks — a table read linearly or log-linearly
    /// between levels, such as a scene's ozone profile: shadow rays then integrate it rather than
    /// read a [`ColumnTable`], whose interpolation keeps its error bound
    /// ([`super::COLUMN_TOLERANCE`]) for smooth profiles only. (A table of 1 km levels keeps the
    /// 1 km panels, its breaks on their edges, so the panel test below does not catch it; the
    /// benchmark ozone of Zawada et al. 2021 tabulated erred by up to 2.4 × the bound.)
    pub fn with_slope_breaks(self) -> AirProfile {
        AirProfile { smooth: false, ..self }
    }

    /// The atmosphere's top, m: d = 0 at and above it.
    pub fn top_m(&self) -> f64 {
        self.top_m
    }

    /// The least e-folding height of d, m: min over 1 km windows [h, h + 1 km] below the top,
    /// where d is above 10⁻³ of its largest value at both ends, of 1 km/|ln(d(h)/d(h + 1 km))|
    /// (6.2 km for USA76's air, the aerosol's own scale height for an exponential haze);
    /// infinite for a profile that is constant there. A march resolves d by steps that climb a
    /// fraction of it.
    pub fn least_scale_height_m(&self) -> f64 {
        self.scale_m
    }

    /// ∫ₐᵇ uʲ d(u) du for j = 0…3 over heights u (m), d zero below the ground and above the
    /// top: exact for the table's interpolant (cumulative sums built at the first call; see [`Moments`]).
    pub fn height_moments(&self, a: f64, b: f64) -> Moments {
        self.moments.get_or_init(|| HeightMoments::new(self.step_m, self.values.clone())).between(a, b)
    }

    /// d at height `h` (m).
    pub fn at_height(&self, h: f64) -> f64 {
        if h >= self.top_m {
            return 0.0;
        }
        if h <= 0.0 {
            return self.values[0];
        }
        let x = h / self.step_m;
        let i = (x as usize).min(self.values.len() - 2);
        let f = x - i as f64;
        self.values[i] + f * (self.values[i + 1] - self.values[i])
    }

    /// d at `p`.
    pub fn at(&self, p: DVec3) -> f64 {
        self.at_height(self.earth.height(p))
    }

    /// The height of `p` above the table's Earth, m.
    pub fn height(&self, p: DVec3) -> f64 {
        self.earth.height(p)
    }

    /// ∫₀ᵗ d(o + s·dir) ds by piecewise Gauss–Legendre quadrature on panels of `panel_m` of
    /// height (for [`ColumnTable`]'s nodes).
    pub(super) fn integral_in_panels(&self, o: DVec3, dir: DVec3, t: f64, panel_m: f64) -> f64 {
        let coarse = AirProfile { panel_m, ..self.clone() };
        coarse.integral(o, dir, t)
    }

    /// ∫₀ᵗ d(o + s·dir) ds by piecewise Gauss–Legendre quadrature below the top (`dir` a unit
    /// vector).
    pub fn integral(&self, o: DVec3, dir: DVec3, t: f64) -> f64 {
        let mut out = [0.0];
        AirProfile::integrals(&[self], o, dir, t, &mut out);
        out[0]
    }

    /// ∫₀ᵗ dₖ(o + s·dir) ds of several tables of one atmosphere (same Earth and top) into
    /// `out[k]` (`dir` a unit vector, at most [`MAX_TABLES`] tables): tables calibrated to the
    /// same panel height share one quadrature (the height found once per node), and each
    /// integral equals [`AirProfile::integral`] of that table to the bit.
    pub fn integrals(tables: &[&AirProfile], o: DVec3, dir: DVec3, t: f64, out: &mut [f64]) {
        out.iter_mut().for_each(|v| *v = 0.0);
        let Some(first) = tables.first() else { return };
        let Some((a, b)) = first.below_top(o, dir, t) else { return };
        if b.is_infinite() {
            for (v, table) in out.iter_mut().zip(tables) {
                *v = if table.values[0] > 0.0 { f64::INFINITY } else { 0.0 };
            }
            return;
        }
        // One quadrature per distinct panel height, over the tables calibrated to it, so that a
        // table's integral never depends on which other tables share the call.
        for (first_k, lead) in tables.iter().enumerate() {
            let panel_m = lead.panel_m;
            if tables[..first_k].iter().any(|t| t.panel_m == panel_m) {
                continue;
            }
            let group = |k: &usize| tables[*k].panel_m == panel_m;
            let mut f = |s: f64, values: &mut [f64]| {
                let h = first.earth.height(o + s * dir);
                for k in (0..tables.len()).filter(group) {
                    values[k] = tables[k].at_height(h);
                }
            };
            let mut sums = [0.0; MAX_TABLES];
            let sums = &mut sums[..tables.len()];
            first.height_panels(o, dir, a, b, panel_m, &mut |t0, t1| {
                crate::quadrature::gauss_legendre_panel_many(&mut f, t0, t1, sums)
            });
            for k in (0..tables.len()).filter(group) {
                out[k] = sums[k];
            }
        }
    }

    /// Builds the table of columns to the top now, on the rayon pool's threads, unless it was
    /// built; whether this call built it. Not from within a task of that pool.
    pub fn build_column_table(&self) -> bool {
        if self.to_top.get().is_some() {
            return false;
        }
        self.to_top.set(self.tabulates().then(|| ColumnTable::build(self, true)).flatten()).is_ok()
    }

    /// Whether the profile is smooth enough for a table of columns ([`ColumnTable`]): it kept
    /// the 1 km quadrature panels (USA76's density, an aerosol's exponential; not the AFGL
    /// ozone shape, whose kinks between levels make its column vary too sharply with the
    /// lowest height of a grazing ray for the table's grid) and is not marked as having slope
    /// breaks ([`AirProfile::with_slope_breaks`]).
    fn tabulates(&self) -> bool {
        self.smooth && self.panel_m == PANEL_HEIGHT_M
    }

    /// The table of columns to the top ([`ColumnTable`]; `None` over a flat Earth or for a
    /// profile too sharp for its grid, such as the AFGL ozone shape), built now (on this thread) if it was
    /// not yet, and whether this call built it.
    pub fn column_table(&self) -> (Option<&ColumnTable>, bool) {
        let mut built = false;
        let table = self.to_top.get_or_init(|| {
            built = true;
            self.tabulates().then(|| ColumnTable::build(self, false)).flatten()
        });
        (table.as_ref(), built)
    }

    /// [`AirProfile::integrals`] read from the tables of columns to the top ([`ColumnTable`])
    /// where the ray o + s·dir, s ∈ [0, t], runs from inside the atmosphere past its top
    /// without meeting the ground (a shadow ray to the sun): true then, with `out` filled;
    /// false, `out` untouched, otherwise (over a flat Earth, or when none of the profiles has a
    /// table). Tables of one atmosphere share their grid, so the ray's cell is found once; a
    /// profile without a table (ozone) is integrated.
    pub fn columns_to_top(tables: &[&AirProfile], o: DVec3, dir: DVec3, t: f64, out: &mut [f64]) -> bool {
        let Some(first) = tables.first() else { return false };
        let Earth::Spherical(s) = first.earth else { return false };
        let Some(table) = tables.iter().find_map(|p| p.column_table().0) else { return false };
        let Some(cell) = table.cell(s.centre, o, dir, t) else { return false };
        let (mut rest, mut at) = ([*first; MAX_TABLES], [0usize; MAX_TABLES]);
        let mut n = 0;
        for (k, (v, profile)) in out.iter_mut().zip(tables).enumerate() {
            match profile.column_table().0 {
                Some(c) => *v = c.column(cell),
                None => {
                    (rest[n], at[n]) = (profile, k);
                    n += 1;
                }
            }
        }
        if n > 0 {
            // The profiles without a table (ozone) are integrated together.
            let mut exact = [0.0; MAX_TABLES];
            AirProfile::integrals(&rest[..n], o, dir, t, &mut exact[..n]);
            for (k, v) in at[..n].iter().zip(&exact) {
                out[*k] = *v;
            }
        }
        true
    }

    /// [`AirProfile::integral`], read from the table of columns to the top where the ray
    /// allows ([`AirProfile::columns_to_top`]).
    pub fn integral_to_top(&self, o: DVec3, dir: DVec3, t: f64) -> f64 {
        let mut out = [0.0];
        if !AirProfile::columns_to_top(&[self], o, dir, t, &mut out) {
            AirProfile::integrals(&[self], o, dir, t, &mut out);
        }
        out[0]
    }

    /// Calls `panel(t0, t1)` for consecutive panels covering [a, b] (finite) of the ray
    /// o + t·dir, split where the ray crosses the heights k·`panel_m` (see the module docs).
    fn height_panels(&self, o: DVec3, dir: DVec3, a: f64, b: f64, panel_m: f64, panel: &mut dyn FnMut(f64, f64)) {
        match &self.earth {
            Earth::Flat { up } => {
                let (h0, rate) = (o.dot(*up), dir.dot(*up));
                let at = |h: f64| (h - h0) / rate;
                split_at_levels(h0 + a * rate, h0 + b * rate, panel_m, &at, (a, b), panel);
            }
            Earth::Spherical(s) => {
                let q = o - s.centre;
                let t_low = -q.dot(dir);
                let p = (q + t_low * dir).length();
                let height = |t: f64| (q + t * dir).length() - s.radius_m;
                let mut side = |t0: f64, t1: f64| {
                    let rising = t1 > t_low;
                    let at = |h: f64| {
                        let r = s.radius_m + h;
                        let u = ((r - p) * (r + p)).max(0.0).sqrt();
                        if rising { t_low + u } else { t_low - u }
                    };
                    split_at_levels(height(t0), height(t1), panel_m, &at, (t0, t1), panel);
                };
                if a < t_low && t_low < b {
                    side(a, t_low);
                    side(t_low, b);
                } else {
                    side(a, b);
                }
            }
        }
    }

    /// Pieces of at most 1 km below the top, each bounded by the running maximum at its lowest
    /// height, and bound 0 elsewhere; see [`super::Density::majorant_intervals`].
    pub fn majorant_intervals(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        self.pieces(o, dir, t_max, &mut |t0, t1, h| visit(t0, t1, self.bound_from(h)))
    }

    /// Calls `visit(t0, t1, h)` for consecutive intervals covering [0, t_max]: pieces of at most
    /// 1 km below the top with h the least height on each (−∞ for a ray down or level for ever
    /// under a flat Earth's top), and the parts above the top with h = +∞. `visit` returns false
    /// to stop. The pieces depend only on the Earth and the top, so tables of one atmosphere
    /// share them.
    pub fn pieces(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        let Some((a, b)) = self.below_top(o, dir, t_max) else {
            visit(0.0, t_max, f64::INFINITY);
            return;
        };
        if a > 0.0 && !visit(0.0, a, f64::INFINITY) {
            return;
        }
        if b.is_infinite() {
            // Down or level for ever under a flat Earth's top: one interval, bounded by the
            // largest value of the table.
            visit(a, b, f64::NEG_INFINITY);
            return;
        }
        let n = pieces(b - a);
        let dt = (b - a) / n as f64;
        for i in 0..n {
            let (t0, t1) = (a + i as f64 * dt, if i + 1 == n { b } else { a + (i + 1) as f64 * dt });
            if !visit(t0, t1, self.lowest_height(o, dir, t0, t1)) {
                return;
            }
        }
        if b < t_max {
            visit(b, t_max, f64::INFINITY);
        }
    }

    /// The largest tabulated value at or above height `h` (0 at and above the top; the largest
    /// of the table for h ≤ 0).
    pub fn bound_from(&self, h: f64) -> f64 {
        if h >= self.top_m {
            return 0.0;
        }
        let i = ((h.max(0.0) / self.step_m) as usize).min(self.values.len() - 1);
        self.max_above[i]
    }

    /// The least height on the segment o + t·dir, t ∈ [t0, t1].
    fn lowest_height(&self, o: DVec3, dir: DVec3, t0: f64, t1: f64) -> f64 {
        match &self.earth {
            Earth::Flat { up } => (o + t0 * dir).dot(*up).min((o + t1 * dir).dot(*up)),
            Earth::Spherical(s) => {
                let t = (-(o - s.centre).dot(dir)).clamp(t0, t1);
                self.earth.height(o + t * dir)
            }
        }
    }

    /// The part [a, b] of [0, t_max] where the ray o + t·dir is below the top, if any: outside
    /// it the profile is 0.
    pub fn below_top(&self, o: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, f64)> {
        let (a, b) = match &self.earth {
            Earth::Flat { up } => {
                let (h0, rate) = (o.dot(*up), dir.dot(*up));
                if rate == 0.0 {
                    if h0 < self.top_m { (0.0, t_max) } else { return None }
                } else {
                    let t_top = (self.top_m - h0) / rate;
                    if rate > 0.0 { (0.0, t_top) } else { (t_top, f64::INFINITY) }
                }
            }
            Earth::Spherical(s) => {
                let r = s.radius_m + self.top_m;
                let q = o - s.centre;
                let (half_b, c) = (q.dot(dir), q.length_squared() - r * r);
                let disc = half_b * half_b - c;
                if disc <= 0.0 {
                    return None;
                }
                let root = disc.sqrt();
                (-half_b - root, -half_b + root)
            }
        };
        let (a, b) = (a.max(0.0), b.min(t_max));
        (a < b).then_some((a, b))
    }
}

/// [`AirProfile::least_scale_height_m`] of the table `values` on nodes `step_m` apart.
fn least_scale_height(values: &[f64], step_m: f64) -> f64 {
    let floor = 1e-3 * values.iter().copied().fold(0.0, f64::max);
    let window = ((1_000.0 / step_m).round() as usize).max(1);
    let width = window as f64 * step_m;
    values
        .iter()
        .zip(values.iter().skip(window))
        .filter(|(a, b)| **a > floor && **b > floor)
        .map(|(a, b)| width / (a / b).ln().abs())
        .fold(f64::INFINITY, f64::min)
}

/// Pieces of at most `PIECE_M` covering a length.
fn pieces(length: f64) -> usize {
    ((length / PIECE_M).ceil() as usize).max(1)
}

/// Calls `panel` for consecutive panels covering [t0, t1], a stretch of a ray along which the
/// height runs monotonically from `h0` to `h1`, split at the parameters `at(h)` where it crosses
/// the levels k·`panel_m` strictly between them: each panel spans at most that much height, and
/// a kink of the profile at a level falls on a panel's end, as it does up a vertical column.
fn split_at_levels(
    h0: f64,
    h1: f64,
    panel_m: f64,
    at: &dyn Fn(f64) -> f64,
    (t0, t1): (f64, f64),
    panel: &mut dyn FnMut(f64, f64),
) {
    let (lo, hi) = (h0.min(h1) / panel_m, h0.max(h1) / panel_m);
    let (first, last) = (lo.floor() as i64 + 1, hi.ceil() as i64 - 1);
    let mut start = t0;
    let mut cross = |k: i64| {
        let end = at(k as f64 * panel_m).clamp(start, t1);
        panel(start, end);
        start = end;
    };
    if h1 >= h0 {
        (first..=last).for_each(&mut cross);
    } else {
        (first..=last).rev().for_each(&mut cross);
    }
    panel(start, t1);
}

/// ∫ d dh up the whole column of `table` by Simpson's rule on its nodes (the last cell by the
/// trapezoid rule when their number is odd).
fn simpson_column(table: &AirProfile) -> f64 {
    let v = &table.values;
    let pairs = (v.len() - 1) / 2;
    let mut sum: f64 =
        (0..pairs).map(|k| v[2 * k] + 4.0 * v[2 * k + 1] + v[2 * k + 2]).sum::<f64>() * table.step_m / 3.0;
    if 2 * pairs + 1 < v.len() {
        sum += 0.5 * table.step_m * (v[v.len() - 2] + v[v.len() - 1]);
    }
    sum
}

/// The panel height for `table`: the largest of [`PANEL_HEIGHT_M`] halved 0 to
/// [`MAX_PANEL_HALVINGS`] times at which 16-point Gauss–Legendre panels between its multiples
/// integrate the table up a vertical column with Σ |panel error| ≤ ε × the column, where ε is
/// [`PANEL_TOLERANCE`] or, when larger, the table's own error: the relative difference between
/// the trapezoid and Simpson sums of its column (the linear interpolant between nodes
/// [`MAX_STEP_M`] apart errs by about that against the profile it samples, so integrating it
/// more exactly than that buys nothing). The exact integral of the linear interpolant is the
/// trapezoid sum over its nodes. A smooth profile (USA76's density, an aerosol's exponential)
/// keeps 1 km; one with kinks between the levels (the AFGL ozone shape, log-linear between
/// levels 2.5–5 km apart) gets finer panels.
fn calibrated_panel_m(table: &AirProfile) -> f64 {
    let v = &table.values;
    let mut cumulative = vec![0.0; v.len()];
    for i in 1..v.len() {
        cumulative[i] = cumulative[i - 1] + 0.5 * table.step_m * (v[i - 1] + v[i]);
    }
    let exact_to = |h: f64| {
        let x = (h / table.step_m).clamp(0.0, (v.len() - 1) as f64);
        let i = (x as usize).min(v.len() - 2);
        let f = x - i as f64;
        cumulative[i] + 0.5 * f * table.step_m * (2.0 * v[i] + f * (v[i + 1] - v[i]))
    };
    let column = exact_to(table.top_m);
    let tolerance = PANEL_TOLERANCE.max((column - simpson_column(table)).abs() / column);
    let mut panel_m = PANEL_HEIGHT_M;
    for _ in 0..MAX_PANEL_HALVINGS {
        let mut error = 0.0;
        split_at_levels(0.0, table.top_m, panel_m, &|h| h, (0.0, table.top_m), &mut |a, b| {
            let mut got = [0.0];
            crate::quadrature::gauss_legendre_panel_many(&mut |h, out| out[0] = table.at_height(h), a, b, &mut got);
            error += (got[0] - (exact_to(b) - exact_to(a))).abs();
        });
        if error <= tolerance * column {
            break;
        }
        panel_m *= 0.5;
    }
    panel_m
}

/// A point at height `h` above the ground point under the scene origin.
fn point_at_height(earth: &Earth, h: f64) -> DVec3 {
    match earth {
        Earth::Flat { up } => h * *up,
        Earth::Spherical(s) => {
            let up = (-s.centre).try_normalize().unwrap_or(DVec3::Y);
            s.centre + (s.radius_m + h) * up
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::usa76;

    fn usa76_profile() -> AirProfile {
        AirProfile::new(&Atmosphere::usa76(), Earth::standard(), 2.5e25).unwrap()
    }

    /// N(h)/N_ref straight from the standard's P and T (the molecular-scale temperature gives
    /// the exact density, see `usa76`).
    fn exact(h: f64) -> f64 {
        let s = usa76::at_geometric(h);
        s.pressure_pa * gas::AVOGADRO_PER_MOL / (gas::R_STAR * s.temperature_k) / 2.5e25
    }

    #[test]
    fn the_table_interpolates_the_standard_to_1e_7() {
        let p = usa76_profile();
        // Sea level: N = 2.547 × 10²⁵ m⁻³ (USA76 Table I: number density 2.5470E+25 at 0 m).
        assert!((p.at_height(0.0) * 2.5e25 / 2.5470e25 - 1.0).abs() < 1e-4);
        for k in 0..2000 {
            let h = 3.0 + k as f64 * 42.9; // between nodes, up to 85.8 km
            let (got, want) = (p.at_height(h), exact(h));
            assert!((got / want - 1.0).abs() < 1e-7, "h = {h}: {got} vs {want}");
        }
        assert_eq!(p.at_height(86_000.0), 0.0);
        assert_eq!(p.at_height(-10.0), p.at_height(0.0));
    }

    #[test]
    fn the_majorant_bounds_the_density_on_every_piece() {
        let p = usa76_profile();
        for (o, d) in [
            (DVec3::new(0.0, 3000.0, 0.0), DVec3::new(1.0, -0.05, 0.2).normalize()),
            (DVec3::new(0.0, 10.0, 0.0), DVec3::Y),
            (DVec3::new(-2e6, 2e5, 0.0), DVec3::new(1.0, -0.1, 0.0).normalize()),
        ] {
            let mut covered = 0.0;
            p.majorant_intervals(o, d, 3e6, &mut |t0, t1, bound| {
                assert_eq!(t0, covered, "intervals are consecutive");
                covered = t1;
                for k in 0..=40 {
                    let t = t0 + (t1 - t0) * k as f64 / 40.0;
                    assert!(p.at(o + t * d) <= bound, "t = {t}");
                }
                true
            });
            assert_eq!(covered, 3e6);
        }
    }

    #[test]
    fn a_vertical_column_integrates_the_standard() {
        // ∫₀^86 km N dh by Simpson's rule on the exact standard (1 m steps) against the table's
        // Gauss–Legendre integral up a vertical chord.
        let p = usa76_profile();
        let got = p.integral(DVec3::ZERO, DVec3::Y, 1e6);
        let n = 86_000;
        let simpson: f64 = (0..n / 2)
            .map(|i| {
                let h = 2.0 * i as f64;
                (exact(h) + 4.0 * exact(h + 1.0) + exact(h + 2.0)) / 3.0
            })
            .sum();
        assert!((got / simpson - 1.0).abs() < 1e-7, "{got} vs {simpson}");
    }

    /// ∫ of the exact standard along o + s·dir over [0, t] by Simpson's rule in ~2 m steps.
    fn exact_chord(p: &AirProfile, o: DVec3, dir: DVec3, t: f64) -> f64 {
        let n = 2 * ((t / 4.0).ceil() as usize);
        let f = |s: f64| {
            let h = p.height(o + s * dir);
            if h >= 86_000.0 { 0.0 } else { exact(h.max(0.0)) }
        };
        crate::quadrature::simpson(&f, 0.0, t, n)
    }

    #[test]
    fn grazing_and_slanted_chords_integrate_the_standard_to_1e_7() {
        // The panels follow the height, not the length: a chord that grazes the ground spends
        // ~1,000 km below the top but crosses only 86 km of height. Against Simpson's rule on
        // the exact standard along the same chord (the test above, for slanted paths).
        let p = usa76_profile();
        let r = crate::atmosphere::EARTH_RADIUS_M;
        let horizon = (2.0 * r * 86_000.0 + 86_000.0f64.powi(2)).sqrt();
        let slant = DVec3::new(1.0, 0.2, 0.0).normalize();
        for (what, o, d, t) in [
            ("from the ground along the horizon", DVec3::ZERO, DVec3::X, 1.2e6),
            ("through its lowest point at 2 km", DVec3::new(-horizon, 2000.0, 0.0), DVec3::X, 2.0 * horizon),
            ("a 300 km piece ending before its lowest point", DVec3::new(-4e5, 500.0, 0.0), DVec3::X, 3e5),
            ("slanted up from 3 km", DVec3::new(0.0, 3000.0, 0.0), slant, 4e5),
        ] {
            let (got, want) = (p.integral(o, d, t), exact_chord(&p, o, d, t));
            assert!((got / want - 1.0).abs() < 1e-7, "{what}: {got} vs {want}");
        }
    }

    #[test]
    fn quadrature_panels_cover_the_chord_and_span_at_most_1_km_of_height() {
        let p = usa76_profile();
        let r = crate::atmosphere::EARTH_RADIUS_M;
        for (o, d, a, b) in [
            (DVec3::ZERO, DVec3::X, 0.0, 1.05e6),
            (DVec3::new(-1e6, 2000.0, 0.0), DVec3::X, 1.0, 2.0e6),
            (DVec3::new(0.0, 10.0, 0.0), DVec3::Y, 0.0, 85_000.0),
            (DVec3::new(0.0, 40_000.0, 0.0), DVec3::new(1.0, -0.3, 0.1).normalize(), 5.0, 2.0e5),
        ] {
            assert_eq!(p.panel_m, PANEL_HEIGHT_M, "USA76's smooth density keeps 1 km panels");
            let (mut covered, mut count) = (a, 0);
            p.height_panels(o, d, a, b, p.panel_m, &mut |t0, t1| {
                assert_eq!(t0, covered, "panels are consecutive");
                assert!(t1 >= t0);
                let heights: Vec<f64> =
                    (0..=50).map(|k| p.height(o + (t0 + (t1 - t0) * k as f64 / 50.0) * d)).collect();
                let span =
                    heights.iter().cloned().fold(f64::MIN, f64::max) - heights.iter().cloned().fold(f64::MAX, f64::min);
                assert!(span <= 1000.0 * (1.0 + 1e-9), "a panel spans {span} m of height");
                covered = t1;
                count += 1;
            });
            assert_eq!(covered, b);
            // At most one panel per km of height crossed on either side of the lowest point, +2.
            let crossed = |t0: f64, t1: f64| (p.height(o + t1 * d) - p.height(o + t0 * d)).abs();
            let t_low = (-(o - DVec3::new(0.0, -r, 0.0)).dot(d)).clamp(a, b);
            let bound = (crossed(a, t_low) / 1000.0).ceil() + (crossed(t_low, b) / 1000.0).ceil() + 2.0;
            assert!(count as f64 <= bound, "{count} panels for a bound of {bound}");
        }
    }

    #[test]
    fn grazing_chords_through_the_ozone_layer_integrate_its_profile_to_1e_7() {
        // The AFGL ozone shape is log-linear between levels 1 km apart up to 25 km and 2.5–5 km
        // apart above (kinks off the whole-km panel ends): against Simpson's rule on the exact
        // profile along the same chord.
        let shape = crate::media::ozone::profile(300.0, 86_000.0);
        let p = AirProfile::from_heights(Earth::standard(), 86_000.0, &shape);
        let slant = DVec3::new(1.0, 0.05, 0.0).normalize();
        for (what, o, d, t) in [
            ("from the ground along the horizon", DVec3::ZERO, DVec3::X, 1.2e6),
            ("grazing at 20 km", DVec3::new(-1.1e6, 20_000.0, 0.0), DVec3::X, 2.2e6),
            ("slanted up from 12 km", DVec3::new(0.0, 12_000.0, 0.0), slant, 1e6f64),
        ] {
            let n = 2 * ((t / 4.0).ceil() as usize);
            let f = |s: f64| {
                let h = p.height(o + s * d);
                if h >= 86_000.0 { 0.0 } else { shape(h.max(0.0)) }
            };
            let want = crate::quadrature::simpson(&f, 0.0, t, n);
            let got = p.integral(o, d, t);
            assert!((got / want - 1.0).abs() < 1e-7, "{what}: {got} vs {want}");
        }
    }

    #[test]
    fn an_aerosol_haze_keeps_1_km_panels_and_integrates_to_the_tables_own_accuracy() {
        // A 1.5 km scale height: the 5 m interpolant errs by ~(5 m)²/(12 H²) ≈ 9e-7 of the
        // column (the trapezoid rule's error on an exponential), so 1 km panels, whose error
        // against the interpolant is ~1.6e-7, are as good as any; against Simpson's rule on the
        // exact exponential along the chord.
        let shape = crate::media::aerosol::profile(1500.0, 100_000.0);
        let p = AirProfile::from_heights(Earth::standard(), 100_000.0, &shape);
        assert_eq!(p.panel_m, PANEL_HEIGHT_M);
        for (what, o, d, t) in [
            ("along the horizon", DVec3::new(0.0, 2.0, 0.0), DVec3::X, 1.2e6),
            ("slanted up", DVec3::new(0.0, 300.0, 0.0), DVec3::new(1.0, 0.1, 0.0).normalize(), 3e5f64),
        ] {
            let n = 2 * ((t / 2.0).ceil() as usize);
            let f = |s: f64| shape(p.height(o + s * d).clamp(0.0, 100_000.0));
            let want = crate::quadrature::simpson(&f, 0.0, t, n);
            let got = p.integral(o, d, t);
            assert!((got / want - 1.0).abs() < 1e-6, "{what}: {got} vs {want}");
        }
    }
}
