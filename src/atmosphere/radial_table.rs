//! The refractive index of an atmosphere that depends on height alone, tabulated once per scene
//! (issue 18, item 3): the cheapest field evaluation that keeps the accuracy.
//!
//! Both air laws are Gladstone–Dale, n − 1 = K(λ)·D(P, T) ([`crate::atmosphere::dispersion::AirDispersion::density_grad`]), and
//! the atmosphere tapers n − 1 by s(h), so where T and P depend on height alone
//!
//! ```text
//!     n(λ, x) = 1 + K(λ)·q(h),   ∇n = K(λ)·q′(h)·∇h,   q(h) = D(P(h), T(h))·s(h),
//! ```
//!
//! one table of q serves every wavelength. On each interval q is the cubic Hermite interpolant of
//! the exact q and q′ at its ends and q′ the cubic through the exact q′ at t = 0, ⅓, ⅔, 1 (the
//! derivative of q's cubic would carry q's rounding divided by the interval, more than the bound
//! for the millimetre intervals over a hot road), with a knot on every kink of the profile (the
//! layer bases, the ends of the model, the start of the taper, a hot surface's ground), so each
//! interval holds a smooth function. Between two kinks each interval is halved until, at
//! θ = 0.211, ½ and 0.789 of it (where the errors of the two cubics peak), both are within half
//! the bound of the exact profile. The bound, for every height in the table:
//!
//! ```text
//!     |q_table − q| ≤ ε·(|q| + 10⁻⁶·q₀),   |q′_table − q′| ≤ ε·(|q′| + 10⁻³·q₀/H₀),
//! ```
//!
//! with ε = rtol of the integrator (`ode_rtol`), q₀ = q(0) and H₀ = 8 km: relative to the field
//! itself, so a step changes v = n dr/ds by ∫∇n ds within ε of the exact change, which is
//! itself a small part of |v| = n (3·10⁻⁴ of it across the whole atmosphere): the table's error
//! per step is far below the rtol·|v| the controller allows it. The floors matter only in the top
//! kilometres (n − 1 < 10⁻⁵ of its sea-level value) and where q′ crosses zero (the top of a hot
//! road's layer). `tests/radial_table.rs` checks the bound at 10⁵ random heights for USA76 with
//! Ciddor and with Cauchy dispersion and for a hot road. About 4 700 intervals at ε = 10⁻⁹ for
//! USA76.

//! Outside the table (below the model's bottom, −5 km) the exact atmosphere is evaluated; at and
//! above the top n = 1 exactly, as there.

use super::{Atmosphere, Earth, usa76};
use glam::DVec3;

/// Largest number of knots; an atmosphere that would need more is not tabulated.
pub const MAX_KNOTS: usize = 1 << 20;
/// Sea-level scale height of the floor of the bound, m.
const H0_M: f64 = 8_000.0;
/// The floor of the bound on q, relative to the sea-level value.
const FLOOR: f64 = 1e-6;
/// The floor of the bound on q′, relative to q₀/H₀: where q′ crosses zero (the top of a hot
/// road's layer, where n stops falling with height) its relative error means nothing.
const FLOOR_DQ: f64 = 1e-3;
/// Cells of the interval index per interval (`RadialTable::interval`).
const CELLS_PER_INTERVAL: usize = 4;
/// A cell of the index that spans more intervals than this is cut into sub-cells.
const CROWDED: usize = 4;
/// Check points of the refinement: where the Hermite errors of q′ and q peak.
const CHECKS: [f64; 3] = [0.211_324_865_405_187_1, 0.5, 0.788_675_134_594_812_9];

/// One interval [lo, lo + w] of the table, t = (h − lo)/w: q = c₀ + c₁t + c₂t² + c₃t³ (the
/// Hermite cubic of q and q′ at the ends) and q′ = d₀ + d₁t + d₂t² + d₃t³ (the cubic through q′
/// at t = 0, ⅓, ⅔, 1: the derivative of q's cubic would carry q's rounding divided by w, which
/// for intervals of millimetres is more than the bound on q′).
#[derive(Clone, Copy, Debug)]
struct Piece {
    inv_w: f64,
    c: [f64; 4],
    d: [f64; 4],
}

/// q(h) and q′(h) of an atmosphere, tabulated (see the module notes).
#[derive(Clone, Debug)]
pub struct RadialTable {
    earth: Earth,
    atmosphere: Atmosphere,
    /// Start of each interval, ascending; the last entry is the top (the end of the last one).
    lo: Vec<f64>,
    pieces: Vec<Piece>,
    /// The index of the intervals: the table's heights cut into equal cells, and for each cell
    /// boundary the interval it lies in (one more entry than cells).
    first: Vec<u32>,
    /// Cells per metre of height.
    inv_cell: f64,
    /// Per cell: where its sub-cells' boundaries start in `sub_first` and how many sub-cells
    /// it has (0: none; a cell is cut into sub-cells where it spans more than [`CROWDED`]
    /// intervals, as at an inversion or over a hot road).
    sub: Vec<(u32, u32)>,
    /// The sub-cells' boundaries, each with the interval it lies in (a crowded cell's n + 1).
    sub_first: Vec<u32>,
    /// Relative bound ε.
    epsilon: f64,
    /// The floors of the bound: 10⁻⁶·q₀ and 10⁻³·q₀/H₀.
    floor_q: f64,
    floor_dq: f64,
}

impl RadialTable {
    /// The table of `atmosphere` to relative bound `epsilon`; `None` when its base is not USA76,
    /// its index does not depend on height alone (an edit that depends on position), or the
    /// bound would need more than [`MAX_KNOTS`] knots.
    pub fn new(atmosphere: &Atmosphere, epsilon: f64) -> Option<RadialTable> {
        let usa76 = matches!(atmosphere.base, super::BaseProfile::Usa76);
        if !(usa76 && epsilon > 0.0 && atmosphere.edits.iter().all(|e| e.is_height_only())) {
            return None;
        }
        let (q0, _) = atmosphere.reduced_refractivity(0.0);
        let mut t = RadialTable {
            earth: atmosphere.earth,
            atmosphere: atmosphere.clone(),
            lo: Vec::new(),
            pieces: Vec::new(),
            first: Vec::new(),
            inv_cell: 0.0,
            sub: Vec::new(),
            sub_first: Vec::new(),
            epsilon,
            floor_q: FLOOR * q0,
            floor_dq: FLOOR_DQ * q0 / H0_M,
        };
        let (bottom, top) = (usa76::BOTTOM_GEOMETRIC_M, atmosphere.top_m());
        let mut breaks: Vec<f64> = atmosphere.kink_heights_m();
        breaks.extend([bottom, top]);
        breaks.retain(|h| h.is_finite() && (bottom..=top).contains(h));
        breaks.sort_by(f64::total_cmp);
        breaks.dedup();
        for w in breaks.windows(2) {
            t.piece(w[0], w[1])?;
        }
        if t.pieces.is_empty() {
            return None;
        }
        t.lo.push(top);
        t.index();
        Some(t)
    }

    /// The Gladstone–Dale factor K(λ) of the table's air, m³ kg⁻¹ (n − 1 = K·q).
    pub fn k(&self, wavelength_nm: f64) -> f64 {
        self.atmosphere.dispersion.gladstone_dale_m3_per_kg(wavelength_nm)
    }

    /// n and ∇n at `p` at `wavelength_nm`, whose Gladstone–Dale factor is `k`
    /// ([`RadialTable::k`]).
    #[inline]
    pub fn n_grad(&self, k: f64, wavelength_nm: f64, p: DVec3) -> (f64, DVec3) {
        let (h, gh) = self.earth.height_grad(p);
        match self.at(h) {
            Some((q, dq)) => (1.0 + k * q, (k * dq) * gh),
            None => self.atmosphere.n_grad(wavelength_nm, p),
        }
    }

    /// q and q′ at height `h`; `None` below the table (at and above the top: (0, 0), as the
    /// atmosphere).
    #[inline]
    pub fn at(&self, h: f64) -> Option<(f64, f64)> {
        let top = *self.lo.last()?;
        if h >= top {
            return Some((0.0, 0.0));
        }
        if h.is_nan() || h < self.lo[0] {
            return None;
        }
        let i = self.interval(h);
        Some(self.pieces[i].eval((h - self.lo[i]) * self.pieces[i].inv_w))
    }

    /// The interval i with lo[i] ≤ `h` < lo[i + 1], for lo[0] ≤ h < top: searched among the
    /// intervals of h's cell of the index (one or two for USA76, where a binary search over all
    /// ~4 700 took 13 dependent loads, 40 % of a field sample in `sunset_sea`'s eye pass), or
    /// over all of them should rounding have put h in a neighbouring cell. Either way the same
    /// interval as a binary search over all, so the table's values do not change.
    #[inline]
    fn interval(&self, h: f64) -> usize {
        let cells = self.first.len() - 1;
        let x = (h - self.lo[0]) * self.inv_cell;
        let j = (x as usize).min(cells - 1);
        let (a, b) = match self.sub[j] {
            (_, 0) => (self.first[j] as usize, self.first[j + 1] as usize),
            (start, n) => {
                let k = start as usize + (((x - j as f64) * f64::from(n)) as usize).min(n as usize - 1);
                (self.sub_first[k] as usize, self.sub_first[k + 1] as usize)
            }
        };
        let i = a + self.lo[a + 1..=b].partition_point(|x| *x <= h);
        if self.lo[i] <= h && h < self.lo[i + 1] { i } else { self.lo.partition_point(|x| *x <= h) - 1 }
    }

    /// Builds the index of the intervals: `CELLS_PER_INTERVAL` equal cells of height per
    /// interval over the table, each boundary with the interval it lies in; a cell that spans
    /// more than [`CROWDED`] intervals is cut the same way into `CELLS_PER_INTERVAL` equal
    /// sub-cells per interval it spans (an inversion's or a hot road's fine intervals crowd
    /// dozens into one cell, where the search among them took half a field sample's time in
    /// `mirage_superior`).
    fn index(&mut self) {
        let (bottom, top) = (self.lo[0], self.lo[self.lo.len() - 1]);
        let cells = CELLS_PER_INTERVAL * self.pieces.len();
        self.inv_cell = cells as f64 / (top - bottom);
        let width = (top - bottom) / cells as f64;
        self.first = (0..=cells).map(|j| self.interval_at(bottom + j as f64 * width)).collect();
        self.sub = vec![(0, 0); cells];
        self.sub_first.clear();
        for j in 0..cells {
            let spanned = (self.first[j + 1] - self.first[j]) as usize;
            if spanned <= CROWDED {
                continue;
            }
            let n = CELLS_PER_INTERVAL * spanned;
            self.sub[j] = (self.sub_first.len() as u32, n as u32);
            let cell_bottom = bottom + j as f64 * width;
            for k in 0..=n {
                let at = self.interval_at(cell_bottom + k as f64 * width / n as f64);
                self.sub_first.push(at);
            }
        }
    }

    /// The interval that height `h` lies in, by a binary search over all (for the index).
    fn interval_at(&self, h: f64) -> u32 {
        (self.lo.partition_point(|x| *x <= h).saturating_sub(1)).min(self.pieces.len() - 1) as u32
    }

    /// The Earth the heights are measured above.
    pub fn earth(&self) -> &Earth {
        &self.earth
    }

    /// The heights where the table's intervals start, ascending, and its top (the last), m.
    pub fn knot_heights_m(&self) -> &[f64] {
        &self.lo
    }

    /// The exact q and q′ at height `h` (what the table interpolates), from the atmosphere.
    pub fn exact(&self, h: f64) -> (f64, f64) {
        self.atmosphere.reduced_refractivity(h)
    }

    /// Number of intervals.
    pub fn intervals(&self) -> usize {
        self.pieces.len()
    }

    /// The bound on |q_table − q| and |q′_table − q′| at a point where the exact values are
    /// `q` and `dq` (see the module notes).
    pub fn bound(&self, q: f64, dq: f64) -> (f64, f64) {
        (self.epsilon * (q.abs() + self.floor_q), self.epsilon * (dq.abs() + self.floor_dq))
    }

    /// Tabulates the smooth piece [a, b] between two kinks; `None` when the knots run out or an
    /// interval would shrink to nothing.
    fn piece(&mut self, a: f64, b: f64) -> Option<()> {
        let (ya, yb) = (self.one_sided(a, 1.0), self.one_sided(b, -1.0));
        let mut stack = vec![(a, ya, b, yb)];
        while let Some((lo, ylo, hi, yhi)) = stack.pop() {
            if self.pieces.len() >= MAX_KNOTS || hi - lo <= 1e-9 * (1.0 + lo.abs()) {
                return None;
            }
            let p = self.piece_on(lo, ylo, hi, yhi);
            if self.fits(lo, hi, &p) {
                self.lo.push(lo);
                self.pieces.push(p);
                continue;
            }
            let mid = 0.5 * (lo + hi);
            let ym = self.atmosphere.reduced_refractivity(mid);
            // The upper half is pushed first, so the lower one is tabulated first.
            stack.push((mid, ym, hi, yhi));
            stack.push((lo, ylo, mid, ym));
        }
        Some(())
    }

    /// q at the kink `h` and q′ from the side `dir` (±1) of it: q′ at h + δ and h + 2δ
    /// extrapolated to h (error δ²·q‴, δ = 10 µm), since at the kink itself the model may
    /// evaluate the other side.
    fn one_sided(&self, h: f64, dir: f64) -> (f64, f64) {
        let delta = dir * 1e-5;
        let (q, _) = self.atmosphere.reduced_refractivity(h);
        let (_, d1) = self.atmosphere.reduced_refractivity(h + delta);
        let (_, d2) = self.atmosphere.reduced_refractivity(h + 2.0 * delta);
        (q, 2.0 * d1 - d2)
    }

    /// The piece on [lo, hi] with (q, q′) at its ends `ylo`, `yhi` (q′ at ⅓ and ⅔ sampled).
    fn piece_on(&self, lo: f64, ylo: (f64, f64), hi: f64, yhi: (f64, f64)) -> Piece {
        let at = |t: f64| self.atmosphere.reduced_refractivity(lo + t * (hi - lo)).1;
        Piece::new(lo, ylo, hi, yhi, (at(1.0 / 3.0), at(2.0 / 3.0)))
    }

    /// Whether piece `p` on [lo, hi] is within half the bound at the check points.
    fn fits(&self, lo: f64, hi: f64, p: &Piece) -> bool {
        CHECKS.iter().all(|t| {
            let (q, dq) = self.atmosphere.reduced_refractivity(lo + t * (hi - lo));
            let (tq, tdq) = p.eval(*t);
            let (bq, bdq) = self.bound(q, dq);
            (tq - q).abs() <= 0.5 * bq && (tdq - dq).abs() <= 0.5 * bdq
        })
    }
}

impl Piece {
    /// The cubics on [lo, hi]: q's Hermite of (q, q′) at both ends, q′'s through its values at
    /// both ends and at ⅓, ⅔ (`inner`).
    fn new(lo: f64, (qa, da): (f64, f64), hi: f64, (qb, db): (f64, f64), inner: (f64, f64)) -> Piece {
        let w = hi - lo;
        let (ma, mb) = (da * w, db * w);
        // q(t) = qa·h00 + ma·h10 + qb·h01 + mb·h11 with h00 = 1 − 3t² + 2t³, h10 = t − 2t² + t³,
        // h01 = 3t² − 2t³, h11 = t³ − t².
        let c2 = 3.0 * (qb - qa) - 2.0 * ma - mb;
        let c3 = 2.0 * (qa - qb) + ma + mb;
        // The cubic through (0, d0), (⅓, d1), (⅔, d2), (1, d3) in powers of t.
        let (d0, d1, d2, d3) = (da, inner.0, inner.1, db);
        let e1 = 0.5 * (-11.0 * d0 + 18.0 * d1 - 9.0 * d2 + 2.0 * d3);
        let e2 = 4.5 * (2.0 * d0 - 5.0 * d1 + 4.0 * d2 - d3);
        let e3 = 4.5 * (-d0 + 3.0 * d1 - 3.0 * d2 + d3);
        Piece { inv_w: 1.0 / w, c: [qa, ma, c2, c3], d: [d0, e1, e2, e3] }
    }

    /// q and q′ at fraction t.
    #[inline]
    fn eval(&self, t: f64) -> (f64, f64) {
        let ([c0, c1, c2, c3], [d0, d1, d2, d3]) = (self.c, self.d);
        (c0 + t * (c1 + t * (c2 + t * c3)), d0 + t * (d1 + t * (d2 + t * d3)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::atmosphere::edit::{Edit, HotSurface, Inversion};

    /// The index finds the interval a binary search over all of them finds — at every knot, just
    /// below and above it, at every cell and sub-cell boundary and at 10⁵ random heights — for
    /// USA76, for a hot road, whose millimetre intervals crowd many into one cell at the ground,
    /// and for an inversion, whose fine intervals crowd the cells about it.
    #[test]
    fn the_index_finds_the_interval_a_full_search_finds() {
        let usa76 = Atmosphere::usa76();
        let hot = HotSurface::new(30.0, 6.667).expect("valid edit");
        let road = Atmosphere::new(
            "hot road",
            usa76.earth,
            usa76.base.clone(),
            vec![Edit::HotSurface(hot)],
            usa76.dispersion,
            usa76.top_m(),
        )
        .expect("valid");
        let inversion = Inversion::new(10.0, 30.0, 3.0).expect("valid edit");
        let inverted = Atmosphere::new(
            "inversion",
            usa76.earth,
            usa76.base.clone(),
            vec![Edit::Inversion(inversion)],
            usa76.dispersion,
            usa76.top_m(),
        )
        .expect("valid");
        for atm in [usa76, road, inverted] {
            let t = RadialTable::new(&atm, 1e-9).expect("tabulated");
            let (bottom, top) = (t.lo[0], t.lo[t.lo.len() - 1]);
            let full = |h: f64| t.lo.partition_point(|x| *x <= h) - 1;
            let cells = t.first.len() - 1;
            let mut heights: Vec<f64> = Vec::new();
            for &k in &t.lo[..t.lo.len() - 1] {
                heights.extend([k, k.next_up(), k.next_down()]);
            }
            let width = (top - bottom) / cells as f64;
            heights.extend((0..cells).map(|j| bottom + j as f64 * width));
            // Every sub-cell boundary of the crowded cells, and just either side of it.
            let mut crowded = 0;
            for (j, &(_, n)) in t.sub.iter().enumerate().filter(|(_, s)| s.1 > 0) {
                crowded += 1;
                for k in 0..=n {
                    let h = bottom + j as f64 * width + f64::from(k) * width / f64::from(n);
                    heights.extend([h, h.next_up(), h.next_down()]);
                }
            }
            if atm.name != "usa76" {
                assert!(crowded > 0, "{}: the fine intervals crowd some cells", atm.name);
            }
            let mut x = 0x9e37_79b9_7f4a_7c15u64;
            for _ in 0..100_000 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let u = (x >> 11) as f64 / (1u64 << 53) as f64;
                // Half uniform over the table, half within 10 m of the ground or of the inversion.
                let near = if x & 2 == 0 { 0.0 } else { 25.0 };
                heights.push(if x & 1 == 0 { bottom + u * (top - bottom) } else { near + 10.0 * u });
            }
            for h in heights.into_iter().filter(|h| (bottom..top).contains(h)) {
                assert_eq!(t.interval(h), full(h), "{}: h = {h}", atm.name);
            }
        }
    }
}
