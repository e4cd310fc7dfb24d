//! The layered upper air, crossed in one move: a photon that enters an atmosphere's top going
//! down is placed where its path meets the highest point of the scene below, by Bouguer's ray
//! invariant instead of integrator steps (issue 18).
//!
//! # When
//! A medium fills the shell r_low ≤ r ≤ r_top about the centre c of a spherical Earth: its top
//! is a sphere about c with the medium inside, r_low lies 1 m above every other shape (their
//! bounding boxes' farthest corners from c, or the radius of a sphere about c), and in between
//! there is nothing else. Air that is the world medium (`[world] medium`, no top sphere) has
//! an *open* top, its atmosphere's: above it n = 1 and no shape lies there, so a path from
//! above goes straight, and if the medium is clear or its density ends at the top nothing is
//! absorbed on the way; a photon from above is moved straight onto the top sphere
//! ([`LayeredShell::enter`]) and crosses the shell from there. `mirage_hot_road` and
//! `mirage_superior`, whose sun and sky photons start far above the air, are such scenes.
//!
//! # Upward
//! The invariant holds both ways: a path that leaves the bottom going up at zenith z_low sweeps
//! the same Δθ to the top, and crosses the same column, as one that arrives there at z_low
//! ([`LayeredShell::ascend`]). A path that climbs through the bottom — an eye path to the sky, a
//! photon reflected upward — or starts up to 10 m above it going up (a camera in the shell) can
//! meet nothing more on its way up and nothing scatters there, so it is moved to the top at
//! once ([`crate::raypath::Propagator::with_upward_shell`]): above an open top it escapes in its
//! direction there (sin z_top = b/(n_top·r_top)); under a shape's top it goes on from just
//! inside it, to cross it as a surface. Where the air absorbs, the visitor is handed the crossing
//! as one chord carrying its density column ([`crate::raypath::Chord::column_m`]), so its
//! transmittance is e^(−σ_t(λ)·C) for every wavelength the path carries; only the eye pass's
//! visitors take such chords (photons climb out in one move through clear air only). The
//! bottom crossing is located on the step's dense output
//! ([`LayeredShell::bottom_crossing`]), and only the part of the step below it is handed out.

use crate::atmosphere::{Earth, RadialTable};
use crate::geometry::Shape;
use crate::media::Medium;
use crate::world::World;
use glam::DVec3;
use std::f64::consts::FRAC_PI_2;

/// How far below the top sphere a path may start and still cross the shell in one move, m (it
/// starts at the top's spawn offset after crossing it).
const ENTRY_SLACK_M: f64 = 1.0;
/// How far inside an open top [`LayeredShell::enter`] puts a path, m (far below the table's
/// millimetre bound on where a path arrives).
const ENTRY_NUDGE_M: f64 = 1e-6;
/// How far above the bottom a path going up may start and still leave in one move, m
/// ([`LayeredShell::ascend`]).
const ASCEND_GAP_M: f64 = 10.0;
/// Bisections of a step in [`LayeredShell::bottom_crossing`], and the radius it stops within, m.
const BISECTIONS: usize = 64;
const CROSSING_TOL_M: f64 = 1e-9;
/// The gap between the highest other shape and the shell's bottom, m.
const BOTTOM_GAP_M: f64 = 1.0;
/// Most intervals of a table in z_low.
pub const MAX_INTERVALS: usize = 8192;
/// Panels of the first piece, each half the width of the next ([`LayeredShell::nodes`]).
const FIRST_PIECE_HALVINGS: i32 = 40;
/// Equal panels of each piece above the first.
const UPPER_PANELS: usize = 4;
/// The power of the grid's grading toward the tangent path ([`complement`]).
const GRADING: i32 = 2;
/// Intervals the refinement starts from.
const FIRST_INTERVALS: usize = 32;

/// Δθ (rad) and C (m) of one path.
type Pair = [f64; 2];

/// The tables of one Gladstone–Dale factor: Δθ and C at grid coordinates w = j/N, j = 0 … N
/// ([`complement`]).
#[derive(Clone, Debug)]
struct ZTable {
    k: f64,
    values: Vec<Pair>,
}

/// Where a path that entered the shell's top leaves its bottom.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Descent {
    /// The point on the bottom sphere, m.
    pub position: DVec3,
    /// The unit direction there.
    pub dir: DVec3,
    /// The density column C crossed on the way, m: the optical depth is σ_t(λ)·C.
    pub column_m: f64,
}

/// Where a path that leaves the shell's bottom going up reaches its top.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Ascent {
    /// The point on the top sphere, m.
    pub position: DVec3,
    /// The unit direction there (above an open top, where n = 1, the path goes on straight).
    pub dir: DVec3,
    /// The density column C crossed on the way, m.
    pub column_m: f64,
}

/// Which way along a path [`LayeredShell::on_path`] reads it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Way {
    Down,
    Up,
}

/// A path at radius r0 in the shell: its invariant b = n0·r0·sin z0 and what the tables say
/// of the path through the bottom at the same b.
struct OnPath {
    r0: f64,
    /// The unit radial at the path's point, and the unit horizontal along its plane.
    up: DVec3,
    tangent: DVec3,
    /// Gladstone–Dale factor, n at r0, the invariant, and n_low·r_low.
    k: f64,
    n0: f64,
    b: f64,
    u_low: f64,
    /// cos z_low at the bottom.
    cos_z: f64,
    /// Δθ (rad) and C (m) from the bottom to the top.
    theta: f64,
    column: f64,
}

/// A medium's layered upper air (see the module notes).
#[derive(Clone, Debug)]
pub struct LayeredShell {
    medium: u32,
    centre: DVec3,
    earth_radius: f64,
    r_low: f64,
    r_top: f64,
    /// The top is the atmosphere's, open to the world medium above it ([`LayeredShell::enter`]).
    open_top: bool,
    /// q at the bottom.
    q_low: f64,
    table: RadialTable,
    density: crate::media::density::Density,
    tables: [ZTable; 3],
}

/// A node of the quadrature in t shared by every path: t, its weight, and r, q(r), d(r) there.
#[derive(Clone, Copy, Debug)]
struct Node {
    t: f64,
    weight: f64,
    r: f64,
    q: f64,
    d: f64,
}

/// The shell's geometry: what fills it, about which centre, between which radii, and whether
/// its top is a shape's sphere or the atmosphere's top, open to the world medium above it.
struct Bounds {
    centre: DVec3,
    r_low: f64,
    r_top: f64,
    open_top: bool,
}

impl LayeredShell {
    /// The layered shell of medium `medium` in `world`, for wavelengths `range_nm` and a path
    /// tolerance `rtol`, if the medium and the scene allow one (see the module notes).
    pub fn of(
        world: &World,
        medium: u32,
        table: &RadialTable,
        range_nm: (f64, f64),
        rtol: f64,
    ) -> Option<LayeredShell> {
        let m = &world.media[medium as usize];
        let top_m = *table.knot_heights_m().last()?;
        let bounds = Self::bounds(world, medium, table.earth(), top_m)?;
        let shell = Self::between(m, medium, table, bounds.centre, (bounds.r_low, bounds.r_top), range_nm, rtol)?;
        Some(LayeredShell { open_top: bounds.open_top, ..shell })
    }

    /// The shell of medium `m` (index `medium`) between radii `r_low` and `r_top` about
    /// `centre` (the Earth's), whatever else the scene holds; `None` where the medium or its
    /// index do not allow one or the table would be too large.
    pub fn between(
        m: &Medium,
        medium: u32,
        table: &RadialTable,
        centre: DVec3,
        (r_low, r_top): (f64, f64),
        range_nm: (f64, f64),
        rtol: f64,
    ) -> Option<LayeredShell> {
        let Earth::Spherical(s) = table.earth() else { return None };
        if !(Self::medium_allows(m, centre) && (s.centre - centre).length() <= 1e-3) {
            return None;
        }
        if !(r_low > s.radius_m + table.knot_heights_m()[0] && r_low < r_top && rtol > 0.0) {
            return None;
        }
        let mut shell = LayeredShell {
            medium,
            centre,
            earth_radius: s.radius_m,
            r_low,
            r_top,
            open_top: false,
            q_low: table.exact(r_low - s.radius_m).0,
            table: table.clone(),
            density: m.density.clone(),
            tables: std::array::from_fn(|_| ZTable { k: 0.0, values: Vec::new() }),
        };
        let (lo, hi) = range_nm;
        let ks = [table.k(hi), table.k(0.5 * (lo + hi)), table.k(lo)];
        if !(ks.iter().all(|k| k.is_finite() && *k > 0.0) && ks[0] < ks[1] && ks[1] < ks[2]) {
            return None;
        }
        if !shell.no_duct(ks[2]) {
            return None;
        }
        let kinks = m.index.as_ref().map(|f| f.kink_radii_m()).unwrap_or_default();
        let nodes = shell.nodes(&kinks);
        for (i, k) in ks.iter().enumerate() {
            shell.tables[i] = shell.tabulate(&nodes, *k, rtol)?;
        }
        let quarter = [table.k(lo + 0.75 * (hi - lo)), table.k(lo + 0.25 * (hi - lo))];
        shell.check_k(&nodes, &quarter, rtol).then_some(shell)
    }

    /// Whether medium `m` allows a shell about `centre`: it absorbs but does not scatter, has
    /// no inelastic component, and its extinction is σ_t(λ)·d(r) with d depending on the
    /// distance from `centre` alone.
    fn medium_allows(m: &Medium, centre: DVec3) -> bool {
        let absorbing_only = !m.scatters() && m.inelastic.is_empty();
        let scaled = !matches!(m.coefficients, crate::media::Coefficients::Constituents(_));
        absorbing_only && scaled && m.density.is_radial_about(centre)
    }

    /// The heights above the ground of the bottom and top of the shell medium `medium` of
    /// `world` would have, and whether its top is open (the atmosphere's, with the world medium
    /// above), from the scene alone (no table is built, so a shell may still be refused where
    /// its table would not reach the bound): for the effect plan's words.
    pub fn candidate(world: &World, medium: u32) -> Option<(f64, f64, bool)> {
        let m = &world.media[medium as usize];
        let Some(crate::media::refractive_index::IndexField::Atmosphere(a)) = &m.index else { return None };
        let centre = a.radial_centre()?;
        if !(matches!(a.base, crate::atmosphere::BaseProfile::Usa76) && Self::medium_allows(m, centre)) {
            return None;
        }
        let b = Self::bounds(world, medium, &a.earth, a.top_m())?;
        let Earth::Spherical(s) = &a.earth else { return None };
        Some((b.r_low - s.radius_m, b.r_top - s.radius_m, b.open_top))
    }

    /// The shell's radii in `world` for medium `medium` whose atmosphere ends `top_m` above the
    /// ground: the top is the smallest sphere about the Earth's centre with the medium inside,
    /// or, for the world medium where none is, the atmosphere's top when nothing above it can
    /// absorb ([`LayeredShell::open_top_allowed`]). `None` when there is neither, or something
    /// lies between the top and 1 m above everything else.
    fn bounds(world: &World, medium: u32, earth: &Earth, top_m: f64) -> Option<Bounds> {
        let Earth::Spherical(s) = earth else { return None };
        let about = |sh: &Shape| match sh {
            Shape::Sphere(sp) if (sp.center - s.centre).length() <= 1e-3 => Some(sp.radius),
            _ => None,
        };
        let closed = world
            .shapes
            .iter()
            .zip(&world.prims)
            .filter(|(_, p)| p.interior == Some(medium) && p.exterior != Some(medium))
            .filter_map(|(sh, _)| about(sh))
            .fold(f64::INFINITY, f64::min);
        let open_top = !closed.is_finite();
        let r_top = if !open_top {
            closed
        } else if world.global_medium == Some(medium) && Self::open_top_allowed(&world.media[medium as usize], top_m) {
            s.radius_m + top_m
        } else {
            return None;
        };
        let mut highest = s.radius_m;
        for sh in &world.shapes {
            let r = match about(sh) {
                Some(r) if r >= r_top => continue,
                Some(r) => r,
                None => farthest_corner(&sh.bounds(), s.centre),
            };
            highest = highest.max(r);
        }
        let r_low = highest + BOTTOM_GAP_M;
        (r_low < r_top).then_some(Bounds { centre: s.centre, r_low, r_top, open_top })
    }

    /// Whether the world medium `m` may have an open top at `top_m`: above it n = 1 (the
    /// atmosphere's), so a path there is straight, and nothing absorbs — the medium is clear,
    /// or its density is an air profile that ends at or below the top.
    fn open_top_allowed(m: &Medium, top_m: f64) -> bool {
        match &m.density {
            _ if m.is_clear() => true,
            crate::media::density::Density::AirProfile(a) => a.top_m() <= top_m,
            _ => false,
        }
    }

    /// Where a path of the world medium at `position` going `dir` from above an open top meets
    /// the top sphere, just inside it: straight, as it would go there (n = 1, no shape and
    /// nothing absorbing above the top), so that [`LayeredShell::descend`] can take it on.
    /// `None` when the top is a shape's, the path starts inside the top sphere, or misses it.
    pub fn enter(&self, position: DVec3, dir: DVec3) -> Option<DVec3> {
        if !self.open_top {
            return None;
        }
        let rel = position - self.centre;
        let (a, b) = (dir.length_squared(), rel.dot(dir));
        let c = (rel.length() - self.r_top) * (rel.length() + self.r_top);
        let disc = b * b - a * c;
        if !(c > 0.0 && b < 0.0 && disc > 0.0) {
            return None;
        }
        // The nearer root t = (−b − √disc)/a, written as c/(−b + √disc) to avoid cancellation.
        let p = rel + dir * (c / (-b + disc.sqrt()));
        Some(self.centre + p * ((self.r_top - ENTRY_NUDGE_M) / p.length()))
    }

    /// The medium whose shell this is.
    pub fn medium(&self) -> u32 {
        self.medium
    }

    /// Heights of the bottom and top above the Earth, m.
    pub fn heights_m(&self) -> (f64, f64) {
        (self.r_low - self.earth_radius, self.r_top - self.earth_radius)
    }

    /// Intervals of the z_low tables (the same for each K).
    pub fn intervals(&self) -> usize {
        self.tables[0].values.len() - 1
    }

    /// q at radius r, exactly (the table's q′ is only continuous at its ~5 000 knots, which an
    /// adaptive quadrature would resolve one by one).
    fn q(&self, r: f64) -> f64 {
        self.table.exact(r - self.earth_radius).0
    }

    /// Whether n·r increases with r through the shell at the largest K: checked at every knot of
    /// the index table and every metre between (within an interval the table is a cubic).
    fn no_duct(&self, k: f64) -> bool {
        let (h_low, h_top) = self.heights_m();
        let knots = self.table.knot_heights_m();
        let grows = |h: f64| match self.table.at(h) {
            Some((q, dq)) => (1.0 + k * q) + (self.earth_radius + h) * k * dq > 0.0,
            None => false,
        };
        let mut prev = h_low;
        for &h in knots.iter().filter(|h| **h > h_low && **h < h_top).chain([h_top].iter()) {
            let steps = (h - prev).ceil().clamp(1.0, 1e6) as usize; // 1 m apart
            if !(0..=steps).all(|i| grows(prev + (h - prev) * i as f64 / steps as f64)) {
                return false;
            }
            prev = h;
        }
        true
    }

    /// The nodes of the composite 16-point Gauss–Legendre rule in t shared by every path: on the
    /// first piece (from the bottom to the first kink) panels halving in width toward t = 0, down
    /// to 2⁻⁴⁰ of it (the integrands bend at t ≈ cos z_low·√(r_low/2), at any scale as the path
    /// nears tangency); on each piece above, [`UPPER_PANELS`] equal panels.
    fn nodes(&self, kink_radii: &[f64]) -> Vec<Node> {
        let (r_low, r_top) = (self.r_low, self.r_top);
        let mut breaks = vec![0.0];
        breaks.extend(kink_radii.iter().filter(|r| **r > r_low && **r < r_top).map(|r| (r - r_low).sqrt()));
        breaks.push((r_top - r_low).sqrt());
        let mut panels = Vec::new();
        let first = breaks[1];
        panels.push((0.0, first * 0.5f64.powi(FIRST_PIECE_HALVINGS)));
        panels.extend((0..FIRST_PIECE_HALVINGS).rev().map(|i| (first * 0.5f64.powi(i + 1), first * 0.5f64.powi(i))));
        for w in breaks[1..].windows(2) {
            let h = (w[1] - w[0]) / UPPER_PANELS as f64;
            panels.extend((0..UPPER_PANELS).map(|i| (w[0] + i as f64 * h, w[0] + (i + 1) as f64 * h)));
        }
        let (x, wts) = crate::quadrature::gauss_legendre_16();
        let up = DVec3::new(0.0, 1.0, 0.0);
        panels
            .iter()
            .flat_map(|&(a, b)| {
                let (mid, half) = (0.5 * (a + b), 0.5 * (b - a));
                x.iter().zip(wts.iter()).map(move |(x, w)| (mid + half * x, w * half))
            })
            .map(|(t, weight)| {
                let r = r_low + t * t;
                Node { t, weight, r, q: self.q(r), d: self.density.at(self.centre + r * up) }
            })
            .collect()
    }

    /// Δθ and C for the path with z_low = π/2 − `zc` at factor `k`, by the shared rule.
    fn fast(&self, nodes: &[Node], k: f64, zc: f64) -> Pair {
        let q_low = self.q_low;
        let u_low = (1.0 + k * q_low) * self.r_low;
        let (cos_z, sin_z) = zc.sin_cos();
        let b = u_low * sin_z;
        let slack = u_low * cos_z * cos_z / (1.0 + sin_z);
        let rk = self.r_low * k;
        let mut sum = [0.0; 2];
        for nd in nodes {
            let n = 1.0 + k * nd.q;
            let u = n * nd.r;
            let minus = nd.t * nd.t * n + rk * (nd.q - q_low) + slack;
            let s = 2.0 * nd.t * nd.weight / (minus * (u + b)).sqrt();
            sum[0] += s * b / nd.r;
            sum[1] += s * nd.d * u;
        }
        sum
    }

    /// The bound on the table's error where the exact values are `v` (see the module notes).
    fn bound(v: Pair, rtol: f64) -> Pair {
        [rtol, 10.0 * rtol * (v[1].abs() + 1.0)]
    }

    /// The table of factor `k`: the grid doubled until cubic interpolation holds the bound at
    /// every midpoint; `None` past [`MAX_INTERVALS`].
    fn tabulate(&self, nodes: &[Node], k: f64, rtol: f64) -> Option<ZTable> {
        let mut n = FIRST_INTERVALS;
        let mut values: Vec<Pair> = (0..=n).map(|j| self.fast(nodes, k, complement(j as f64 / n as f64))).collect();
        loop {
            let table = ZTable { k, values };
            let mids: Vec<Pair> =
                (0..n).map(|j| self.fast(nodes, k, complement((j as f64 + 0.5) / n as f64))).collect();
            let holds = mids.iter().enumerate().all(|(j, m)| {
                let got = table.at((j as f64 + 0.5) / n as f64);
                let b = Self::bound(*m, rtol);
                (got[0] - m[0]).abs() <= b[0] && (got[1] - m[1]).abs() <= b[1]
            });
            if holds {
                return Some(table);
            }
            if 2 * n > MAX_INTERVALS {
                return None;
            }
            values = table.values.iter().zip(&mids).flat_map(|(v, m)| [*v, *m]).collect();
            values.push(*table.values.last()?);
            n *= 2;
        }
    }

    /// Whether quadratic interpolation across the three factors holds the bound at factors `ks`
    /// (every fourth node of the z grid).
    fn check_k(&self, nodes: &[Node], ks: &[f64], rtol: f64) -> bool {
        let n = self.intervals();
        ks.iter().all(|&k| {
            (0..=n).step_by(4).all(|j| {
                let w = j as f64 / n as f64;
                let (exact, got) = (self.fast(nodes, k, complement(w)), self.interpolate(k, w));
                let b = Self::bound(exact, rtol);
                (got[0] - exact[0]).abs() <= b[0] && (got[1] - exact[1]).abs() <= b[1]
            })
        })
    }

    /// Δθ and C at factor `k` and grid coordinate `w` ([`complement`]): cubic in w on each
    /// factor's table, quadratic (Lagrange) across the three factors.
    fn interpolate(&self, k: f64, w: f64) -> Pair {
        let [a, b, c] = &self.tables;
        let (ka, kb, kc) = (a.k, b.k, c.k);
        let l = [
            (k - kb) * (k - kc) / ((ka - kb) * (ka - kc)),
            (k - ka) * (k - kc) / ((kb - ka) * (kb - kc)),
            (k - ka) * (k - kb) / ((kc - ka) * (kc - kb)),
        ];
        let (va, vb, vc) = (a.at(w), b.at(w), c.at(w));
        [0, 1].map(|i| l[0] * va[i] + l[1] * vb[i] + l[2] * vc[i])
    }

    /// Where a path in the shell's medium at `position` going `dir` at `wavelength_nm` leaves
    /// the shell's bottom, if it has just entered through the top going down (within
    /// 1 m of it) and meets the bottom; `None` otherwise (the path is then followed
    /// step by step).
    pub fn descend(&self, position: DVec3, dir: DVec3, wavelength_nm: f64) -> Option<Descent> {
        let r0 = (position - self.centre).length();
        if !(r0 <= self.r_top && r0 >= self.r_top - ENTRY_SLACK_M) {
            return None;
        }
        let p = self.on_path(position, dir, wavelength_nm, Way::Down)?;
        // The table starts at r_top; the path starts r_top − r0 (≤ 1 m) lower.
        let gap = self.r_top - p.r0;
        let root = ((p.n0 * p.r0 - p.b) * (p.n0 * p.r0 + p.b)).sqrt();
        let theta = p.theta - gap * p.b / (p.r0 * root);
        let column = p.column - gap * self.density.at(position) * p.n0 * p.r0 / root;
        let (s, c) = theta.sin_cos();
        let (up_low, t_low) = (c * p.up + s * p.tangent, c * p.tangent - s * p.up);
        Some(Descent {
            position: self.centre + self.r_low * up_low,
            dir: (p.b / p.u_low * t_low - p.cos_z * up_low).normalize(),
            column_m: column.max(0.0),
        })
    }

    /// The invariant of a path at `position` going `dir` at `wavelength_nm` the `way` asked,
    /// and the tables' Δθ and C for it (from the bottom to the top); `None` when it goes the
    /// other way, does not reach down to the bottom (b ≥ n_low·r_low), or its wavelength is
    /// outside the tables' range.
    fn on_path(&self, position: DVec3, dir: DVec3, wavelength_nm: f64, way: Way) -> Option<OnPath> {
        let rel = position - self.centre;
        let r0 = rel.length();
        let up = rel / r0;
        let cos0 = dir.dot(up);
        let going = match way {
            Way::Down => cos0 < 0.0,
            Way::Up => cos0 > 0.0,
        };
        if !going {
            return None;
        }
        let across = dir - cos0 * up;
        let sin0 = across.length();
        let k = self.k_within(wavelength_nm)?;
        let (n0, n_low) = (1.0 + k * self.q(r0), 1.0 + k * self.q_low);
        let b = n0 * r0 * sin0;
        let u_low = n_low * self.r_low;
        if b >= u_low {
            return None;
        }
        let cos_z = ((u_low - b) * (u_low + b)).sqrt() / u_low;
        let w = 1.0 - (cos_z.atan2(b / u_low) / FRAC_PI_2).powf(1.0 / GRADING as f64);
        let [theta, column] = self.interpolate(k, w);
        let tangent = if sin0 > 0.0 { across / sin0 } else { any_perpendicular(up) };
        Some(OnPath { r0, up, tangent, k, n0, b, u_low, cos_z, theta, column })
    }

    /// Whether the top is the atmosphere's, open to the world medium above it (a path that
    /// leaves it goes straight to infinity), rather than a shape's sphere.
    pub fn open_top(&self) -> bool {
        self.open_top
    }

    /// The step fraction θ at which a path crosses the shell's bottom going up on a step from
    /// `from` to `to`, given its positions `at(θ)` (θ ∈ [0, 1]; the integrator's dense output):
    /// the step starts below r_low and ends at or above it. Bisection to 10⁻⁹ m of the radius.
    pub fn bottom_crossing(&self, from: DVec3, to: DVec3, at: impl Fn(f64) -> DVec3) -> Option<f64> {
        let r = |p: DVec3| (p - self.centre).length_squared();
        let r_low_sq = self.r_low * self.r_low;
        if !(r(from) < r_low_sq && r(to) >= r_low_sq) {
            return None;
        }
        let r = |theta: f64| (at(theta) - self.centre).length() - self.r_low;
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..BISECTIONS {
            let mid = 0.5 * (lo + hi);
            let f = r(mid);
            if f.abs() <= CROSSING_TOL_M {
                return Some(mid);
            }
            if f < 0.0 { lo = mid } else { hi = mid }
        }
        Some(hi)
    }

    /// Where a path at `position` on the shell's bottom, or up to 10 m above it, going up along
    /// `dir` at `wavelength_nm` reaches the top — the mirror of [`LayeredShell::descend`]: the
    /// Δθ and C of the path that meets the bottom at the same zenith angle z_low (the same
    /// invariant b = n·r·sin z), read from the same tables, less the part below the start.
    /// That part, over the gap δ = r₀ − r_low, is integrated with g = n²r² − b² taken linear in
    /// r across it — exact enough at any angle, tangent included, since
    /// ∫dr/√g = 2δ/(√g₀ + √g_low):
    ///
    /// ```text
    ///     Δθ_gap = 2δ·b / (r_mid·(√g₀ + √g_low)),   C_gap = 2δ·d_mid·n·r_mid / (√g₀ + √g_low).
    /// ```
    ///
    /// `None` when the path is not there going up, does not reach down to the bottom (b ≥
    /// n_low·r_low: its perigee is above it), or its wavelength is outside the tables' range.
    pub fn ascend(&self, position: DVec3, dir: DVec3, wavelength_nm: f64) -> Option<Ascent> {
        let gap = (position - self.centre).length() - self.r_low;
        if !(gap.abs() <= ASCEND_GAP_M && gap + self.r_low < self.r_top) {
            return None;
        }
        let p = self.on_path(position, dir, wavelength_nm, Way::Up)?;
        let roots = ((p.n0 * p.r0 - p.b) * (p.n0 * p.r0 + p.b)).sqrt() + p.u_low * p.cos_z;
        let r_mid = self.r_low + 0.5 * gap;
        let d_mid = self.density.at(self.centre + p.up * r_mid);
        let theta = p.theta - 2.0 * gap * p.b / (r_mid * roots);
        let column = p.column - 2.0 * gap * d_mid * (1.0 + p.k * self.q(r_mid)) * r_mid / roots;
        let u_top = (1.0 + p.k * self.q(self.r_top)) * self.r_top;
        let (sin_top, cos_top) = (p.b / u_top, ((u_top - p.b) * (u_top + p.b)).sqrt() / u_top);
        let (s, c) = theta.sin_cos();
        let (up_top, t_top) = (c * p.up + s * p.tangent, c * p.tangent - s * p.up);
        Some(Ascent {
            position: self.centre + self.r_top * up_top,
            dir: (sin_top * t_top + cos_top * up_top).normalize(),
            column_m: column.max(0.0),
        })
    }

    /// The Gladstone–Dale factor of `wavelength_nm` if the tables span it (they interpolate in
    /// K between the pass's shortest and longest wavelengths, and are not to extrapolate).
    fn k_within(&self, wavelength_nm: f64) -> Option<f64> {
        let k = self.table.k(wavelength_nm);
        let (lo, hi) = (self.tables[0].k, self.tables[2].k);
        let slack = 1e-12 * hi;
        (k >= lo - slack && k <= hi + slack).then_some(k)
    }
}

impl ZTable {
    /// Cubic (four-point Lagrange) interpolation at grid coordinate `w` ∈ [0, 1].
    fn at(&self, w: f64) -> Pair {
        let n = self.values.len() - 1;
        let x = (w * n as f64).clamp(0.0, n as f64);
        let j = (x.floor() as usize).min(n - 1);
        let first = j.saturating_sub(1).min(n.saturating_sub(3));
        let u = x - first as f64;
        let w = [
            -(u - 1.0) * (u - 2.0) * (u - 3.0) / 6.0,
            u * (u - 2.0) * (u - 3.0) / 2.0,
            -u * (u - 1.0) * (u - 3.0) / 2.0,
            u * (u - 1.0) * (u - 2.0) / 6.0,
        ];
        let v = &self.values[first..first + 4];
        [0, 1].map(|i| w[0] * v[0][i] + w[1] * v[1][i] + w[2] * v[2][i] + w[3] * v[3][i])
    }
}

/// π/2 − z_low at grid coordinate `w` ∈ [0, 1]: z_low = (π/2)·w·(2 − w), so the grid is finest
/// at the tangent path (w = 1), where Δθ and C change fastest, and twice as coarse as a uniform
/// one at the vertical.
fn complement(w: f64) -> f64 {
    FRAC_PI_2 * (1.0 - w).powi(GRADING)
}

/// The distance from `c` of the corner of `b` farthest from it.
fn farthest_corner(b: &crate::geometry::Aabb, c: DVec3) -> f64 {
    let far = (b.min - c).abs().max((b.max - c).abs());
    far.length()
}

/// A unit vector perpendicular to the unit vector `u`.
fn any_perpendicular(u: DVec3) -> DVec3 {
    let a = if u.x.abs() < 0.9 { DVec3::X } else { DVec3::Y };
    (a - a.dot(u) * u).normalize()
}
