//! Projection maps for lights at infinity where paths curve (Jensen 2001, *Realistic Image
//! Synthesis Using Photon Mapping*, §5.1.2: emit photons only toward where they matter).
//!
//! A directional light aimed at a target box starts its photons on the box's straight shadow on
//! the emitting plane. Where the atmosphere bends light (a low sun crosses hundreds of km of air
//! and is bent by up to a degree) those photons miss the box. The map is made in three steps:
//! 1. *aim*: the curved ray from the shadow's centre is traced and its point of closest approach
//!    to the box's centre measured; the start point is moved by the miss, in the beam plane, and
//!    traced again (bending is nearly a translation over the box, so a few rounds converge);
//! 2. *mark*: a grid of [`GRID`]×[`GRID`] cells over a window around the aimed point (the
//!    shadow's size, grown until no marked cell touches its border) is tested by tracing axial
//!    rays from every grid vertex to their first surface; a ray that passes through the box
//!    (grown by one cell's width) marks the cells around its vertex;
//! 3. the marked cells, grown by one ring, are where photons start ([`BeamCells`]), and the
//!    light's power is E times their area.
//!
//! A disc (the sun) is aimed at its axis and at its four edges, each traced from where such a
//! photon starts ([`DirectionalLight::aimed_origin`]): its edges cross the air elsewhere and
//! bend differently (near the horizon the lower limb is lifted more than the upper), so a
//! photon's cells move with its direction by the aimed points' differences, interpolated
//! linearly over the disc (`BeamCells::disc_shift`).
//!
//! Light that reaches the box only from unmarked cells is not simulated: a ray from every cell
//! corner and one ring of margin keep that to light whose path changes faster than the cell size
//! (a caustic of the atmosphere), which `report.json`'s stated beam area lets a user check.

use super::{Event, Propagator, RayState};
use crate::geometry::{Aabb, Frame};
use crate::light::{BeamCells, DirectionalLight};
use crate::ode::CurvedSettings;
use crate::world::World;
use glam::DVec3;
use rayon::prelude::*;

/// Boundaries between media a test ray passes through before it gives up.
const MAX_BOUNDARIES: usize = 16;

/// Cells per side of the grid.
pub const GRID: usize = 64;
/// Rounds of aiming, and of growing the window.
const AIM_ROUNDS: usize = 6;
/// Doublings of the step that lifts a blocked aiming ray off the surface it ran into, and
/// bisections of its height after.
const MAX_LIFTS: usize = 24;
const BISECTIONS: usize = 48;
const GROW_ROUNDS: usize = 4;

/// What [`build`] reads of a light: two lights equal in all of it get the same map (the
/// spectrum is not among it), so a scene traces one map for them.
#[derive(PartialEq)]
pub struct MapInputs {
    dir: DVec3,
    frame: Frame,
    beam: [[f64; 2]; 2],
    sin_max: f64,
    target: Option<Aabb>,
    scene: (DVec3, f64),
    medium: Option<u32>,
}

impl MapInputs {
    /// The inputs of the map of `light` emitting into `medium`.
    pub fn of(light: &DirectionalLight, medium: Option<u32>) -> Self {
        let (dir, frame, beam, sin_max, target) = (light.dir, light.frame, light.beam, light.sin_max, light.target);
        MapInputs { dir, frame, beam, sin_max, target, scene: (light.scene_centre, light.scene_radius), medium }
    }
}

/// The projection map of directional light `light` (emitting into `medium`), or `None` when it
/// has no target or nothing of it reaches the target.
pub fn build(
    world: &World,
    curved: &CurvedSettings,
    light: &DirectionalLight,
    medium: Option<u32>,
) -> Option<BeamCells> {
    let target = light.target?;
    let prop = Propagator::new(world, Some(curved));
    let frame = light.frame;
    let half = [0.5 * (light.beam[0][1] - light.beam[0][0]), 0.5 * (light.beam[1][1] - light.beam[1][0])];
    let centre = [0.5 * (light.beam[0][0] + light.beam[0][1]), 0.5 * (light.beam[1][0] + light.beam[1][1])];
    // Each direction of the disc is aimed on its own: rays from its edges cross the air
    // elsewhere and bend differently (a low sun's lower limb is lifted more than its upper),
    // so each photon's cells move with its direction, by the aimed points' differences
    // interpolated over the disc; the cells themselves are the axis's.
    let aims: Vec<[f64; 2]> =
        disc_dirs(light, &frame).iter().map(|d| aim(&prop, light, &frame, medium, &target, centre, *d)).collect();
    let aimed = aims[0];
    let disc_shift = (aims.len() == 5).then(|| {
        let half_diff = |a: [f64; 2], b: [f64; 2]| [0.5 * (a[0] - b[0]), 0.5 * (a[1] - b[1])];
        [half_diff(aims[1], aims[2]), half_diff(aims[3], aims[4])]
    });
    let mut window = [half[0].max(1e-6) * 1.5, half[1].max(1e-6) * 1.5];
    for _ in 0..GROW_ROUNDS {
        let origin = [aimed[0] - window[0], aimed[1] - window[1]];
        let size = [2.0 * window[0] / GRID as f64, 2.0 * window[1] / GRID as f64];
        let marks = mark(&prop, light, medium, &target, origin, size);
        if marks.is_empty() {
            return None;
        }
        let last = GRID as u32 - 1;
        let touches = marks.iter().any(|[i, j]| *i == 0 || *j == 0 || *i == last || *j == last);
        if !touches {
            return Some(BeamCells { origin, size, cells: grow(&marks), disc_shift });
        }
        window = [2.0 * window[0], 2.0 * window[1]];
    }
    None
}

/// The axis and, for a disc of finite size, the four edges of the disc.
fn disc_dirs(light: &DirectionalLight, frame: &Frame) -> Vec<DVec3> {
    let cos_m = (1.0 - light.sin_max * light.sin_max).sqrt();
    let mut dirs = vec![light.dir];
    if light.sin_max > 0.0 {
        for e in [frame.s, -frame.s, frame.t, -frame.t] {
            dirs.push((cos_m * light.dir + light.sin_max * e).normalize());
        }
    }
    dirs
}

/// The beam point whose curved path along `dir` (started where such a photon starts) passes
/// closest to the target's centre.
fn aim(
    prop: &Propagator,
    light: &DirectionalLight,
    frame: &Frame,
    medium: Option<u32>,
    target: &Aabb,
    start: [f64; 2],
    dir: DVec3,
) -> [f64; 2] {
    let c = target.centre();
    let size = target.diagonal().length().max(1e-9);
    let shot = |st: [f64; 2]| {
        let from = light.aimed_origin(light.plane_point(st[0], st[1]), dir);
        let (_, closest, end_normal) = trace(prop, from, dir, medium, target, c);
        let miss = closest.map(|p| p - c);
        // Blocked: the ray ended on a surface well before the target's depth.
        let blocked = miss.and_then(|m| end_normal.filter(|_| m.dot(dir) < -size));
        (miss, blocked)
    };
    let mut st = start;
    for _ in 0..AIM_ROUNDS {
        let (Some(miss), blocked) = shot(st) else { return st };
        if let Some(n) = blocked {
            return aim_past(&shot, frame, dir, st, n, size);
        }
        st = [st[0] - miss.dot(frame.s), st[1] - miss.dot(frame.t)];
        if miss.length() < 1e-3 * size {
            break;
        }
    }
    st
}

/// Aiming when the ray runs into a surface first (a sun near or below the true horizon: the
/// straight shadow meets the Earth). Near grazing the bending changes fast with height, so the
/// miss is no guide: the start point is lifted away from that surface (normal `n`) by a doubling
/// step until the ray gets past it, and the height is then found by bisection between blocked and
/// passing above the target's centre.
fn aim_past(
    shot: &dyn Fn([f64; 2]) -> (Option<DVec3>, Option<DVec3>),
    frame: &Frame,
    dir: DVec3,
    start: [f64; 2],
    n: DVec3,
    size: f64,
) -> [f64; 2] {
    let up = if n.dot(dir) < 0.0 { n } else { -n };
    let (us, ut) = (up.dot(frame.s), up.dot(frame.t));
    let norm = (us * us + ut * ut).sqrt();
    if norm < 1e-12 {
        return start;
    }
    let (us, ut) = (us / norm, ut / norm);
    let at = |h: f64| [start[0] + h * us, start[1] + h * ut];
    // How far above (+) or below (−) the target's centre the ray passes; blocked counts as below.
    let height = |h: f64| match shot(at(h)) {
        (Some(m), None) => Some(m.dot(frame.s) * us + m.dot(frame.t) * ut),
        (Some(_), Some(_)) => Some(f64::NEG_INFINITY),
        (None, _) => None,
    };
    let (mut lo, mut hi) = (0.0, size.max(100.0));
    let mut lifts = 0;
    while height(hi).is_some_and(|v| v < 0.0) {
        lo = hi;
        hi *= 2.0;
        lifts += 1;
        if lifts == MAX_LIFTS {
            return start;
        }
    }
    for _ in 0..BISECTIONS {
        let mid = 0.5 * (lo + hi);
        match height(mid) {
            Some(v) if v.abs() < 1e-3 * size => return at(mid),
            Some(v) if v < 0.0 => lo = mid,
            Some(_) => hi = mid,
            None => break,
        }
    }
    at(hi)
}

/// Cells around the grid vertices whose axial rays pass through the target (grown by a cell).
fn mark(
    prop: &Propagator,
    light: &DirectionalLight,
    medium: Option<u32>,
    target: &Aabb,
    origin: [f64; 2],
    size: [f64; 2],
) -> Vec<[u32; 2]> {
    let grown = target.padded(size[0].max(size[1]));
    let hits: Vec<[u32; 2]> = (0..(GRID + 1) * (GRID + 1))
        .into_par_iter()
        .filter_map(|k| {
            let (i, j) = (k % (GRID + 1), k / (GRID + 1));
            let p = light.plane_point(origin[0] + i as f64 * size[0], origin[1] + j as f64 * size[1]);
            let reaches = trace(prop, p, light.dir, medium, &grown, grown.centre()).0;
            reaches.then_some([i as u32, j as u32])
        })
        .collect();
    let mut cells = Vec::new();
    for [i, j] in hits {
        for (di, dj) in [(0, 0), (1, 0), (0, 1), (1, 1)] {
            let (ci, cj) = (i as i64 - di, j as i64 - dj);
            if (0..GRID as i64).contains(&ci) && (0..GRID as i64).contains(&cj) {
                cells.push([ci as u32, cj as u32]);
            }
        }
    }
    cells.sort_unstable();
    cells.dedup();
    cells
}

/// The cells and their eight neighbours (within the grid), sorted.
fn grow(cells: &[[u32; 2]]) -> Vec<[u32; 2]> {
    let mut out = Vec::with_capacity(cells.len() * 4);
    for [i, j] in cells {
        for di in -1i64..=1 {
            for dj in -1i64..=1 {
                let (a, b) = (*i as i64 + di, *j as i64 + dj);
                if (0..GRID as i64).contains(&a) && (0..GRID as i64).contains(&b) {
                    out.push([a as u32, b as u32]);
                }
            }
        }
    }
    out.sort_unstable();
    out.dedup();
    out
}

/// Follows a ray from `p` along `d` to its first surface: whether it passes through `box_`,
/// its point of closest approach to `c`, and the normal of the surface it ended on (if it
/// missed the box).
fn trace(
    prop: &Propagator,
    p: DVec3,
    d: DVec3,
    medium: Option<u32>,
    box_: &Aabb,
    c: DVec3,
) -> (bool, Option<DVec3>, Option<DVec3>) {
    let mut through = false;
    let mut end_normal = None;
    let mut closest: Option<(f64, DVec3)> = None;
    let mut state = RayState { position: p, dir: d, wavelength_nm: None, medium };
    let mut note = |q: DVec3| {
        let dist = (q - c).length();
        if closest.is_none_or(|(best, _)| dist < best) {
            closest = Some((dist, q));
        }
    };
    for _ in 0..MAX_BOUNDARIES {
        let event = prop.next_event_with(&state, &mut |chord| {
            let end = chord.origin + chord.length * chord.dir;
            through |= segment_meets_box(chord.origin, end, box_);
            let t = (c - chord.origin).dot(chord.dir).clamp(0.0, chord.length);
            note(chord.origin + t * chord.dir);
            None
        });
        let Event::Surface { hit, dir, medium, .. } = event else { break };
        through |= box_.contains(hit.point);
        note(hit.point);
        let scene_prim = &prop.world().prims[hit.prim as usize];
        if through || scene_prim.material.is_some() || scene_prim.light.is_some() {
            end_normal = (!through).then_some(hit.normal);
            break;
        }
        // A boundary between media (a fog bank's box): go on through it.
        let (d, across) = prop.cross(&hit, dir, medium, crate::raypath::curved::REFERENCE_WAVELENGTH_NM, 0.999_999);
        state = prop.leave(&hit, d, None, across);
    }
    (through, closest.map(|(_, q)| q), end_normal)
}

/// Whether the segment a→b meets the box (slab test).
fn segment_meets_box(a: DVec3, b: DVec3, box_: &Aabb) -> bool {
    let d = b - a;
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for k in 0..3 {
        if d[k] == 0.0 {
            if a[k] < box_.min[k] || a[k] > box_.max[k] {
                return false;
            }
            continue;
        }
        let (u, v) = ((box_.min[k] - a[k]) / d[k], (box_.max[k] - a[k]) / d[k]);
        t0 = t0.max(u.min(v));
        t1 = t1.min(u.max(v));
        if t0 > t1 {
            return false;
        }
    }
    true
}
