//! One ray followed through a scene's media — curved where their index fields
//! bend it — without scattering, to see where a pixel's ray goes (which surface a mirage pixel
//! shows, how low a ray dips before it turns, which part of the sky it escapes to).
//!
//! The ray starts at `--from` in the medium found there ([`World::medium_at`]) with the
//! direction `--dir` or toward `--toward`, at one wavelength. [`Propagator::next_event_with`]
//! moves it from event to event; a visitor records every chord it is handed (one per
//! integrator step in clear air away from geometry, finer near surfaces). At a boundary between
//! media without a material ([`Propagator::cross`]) the trace goes on along the refracted ray —
//! reflected only under total internal reflection — and stops at the first surface with a
//! material or a light, at escape, or after `--events` events. Elevations are measured from the
//! scene's xz-plane (+y up, as the sky light measures them).
//!
//! Each surface line gives the path length `s` along the arc from the start, as the propagator
//! measures it (the integrator's arc length). `--csv` writes the chord points
//! `s_m,x,y,z,dx,dy,dz,n`: the length of the polyline through the points up to there, the
//! chord's start point and unit direction and n there; each surface point and the end point
//! of the path. A chord of length L on an arc of curvature κ = |∇n⊥|/n is shorter than the arc by
//! about κ²L³/24, so `s_m` falls short of the arc length by the sum of these.

use super::{Chord, Event, Propagator, RayState};
use crate::atmosphere::Earth;
use crate::media::refractive_index::IndexField;
use crate::ode::CurvedSettings;
use crate::world::World;
use glam::DVec3;
use std::fmt::Write as _;

/// One recorded point of the path.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PathPoint {
    /// Path length from the start, m.
    pub s_m: f64,
    /// Position, m.
    pub position: DVec3,
    /// Unit direction of travel there.
    pub dir: DVec3,
    /// Refractive index there.
    pub n: f64,
}

/// How a trace ended.
#[derive(Clone, Debug, PartialEq)]
pub enum End {
    /// At a surface with a material or a light (named).
    Surface(String),
    /// Out of the world, along this direction.
    Escape(DVec3),
    /// The integrator failed at this point.
    Lost(DVec3),
    /// `--events` events were followed.
    EventLimit,
    /// The path reached `--max-length-m`.
    LengthLimit,
}

/// A followed ray: its points, one line per event, and how it ended.
#[derive(Clone, Debug)]
pub struct Traced {
    /// Points along the path: chord starts, surface points and the end.
    pub points: Vec<PathPoint>,
    /// One human-readable line per event.
    pub lines: Vec<String>,
    /// How the trace ended.
    pub end: End,
    /// What the integrator did along the path.
    pub work: super::CurvedWorkTotals,
}

/// How far a trace goes at most.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// Events (surfaces, boundaries, escape).
    pub events: usize,
    /// Path length, m.
    pub length_m: f64,
}

/// Follows the ray from `from` along unit `dir` at `wavelength_nm` within `limits`.
#[allow(clippy::too_many_arguments)]
pub fn trace(
    world: &World,
    curved: Option<&CurvedSettings>,
    from: DVec3,
    dir: DVec3,
    wavelength_nm: f64,
    limits: Limits,
) -> Traced {
    let prop = Propagator::new(world, curved);
    let mut state = RayState { position: from, dir, wavelength_nm: Some(wavelength_nm), medium: world.medium_at(from) };
    let (mut points, mut lines) = (Vec::new(), Vec::new());
    // `s0`: the polyline's length at the start of this leg; `arc`: the path length along the
    // arc through the last surface, as the propagator measures it.
    let (mut s0, mut arc) = (0.0, 0.0);
    for k in 1..=limits.events {
        let start = points.len();
        let mut s = s0;
        let mut tip = None;
        let event = prop.next_event_with(&state, &mut |c: &Chord| {
            let n = prop.n_at(c.medium, wavelength_nm, c.origin);
            points.push(PathPoint { s_m: s, position: c.origin, dir: c.dir, n });
            let stop = (s + c.length > limits.length_m).then(|| (limits.length_m - s).max(0.0));
            let length = stop.unwrap_or(c.length);
            s += length;
            tip = Some(PathPoint { s_m: s, position: c.origin + length * c.dir, dir: c.dir, n });
            stop
        });
        if points.len() == start {
            // No chord was handed over (vacuum): the path is the straight segment itself.
            let n = prop.n_at(state.medium, wavelength_nm, state.position);
            points.push(PathPoint { s_m: s0, position: state.position, dir: state.dir, n });
        }
        let medium_name = |m: Option<u32>| medium_label(world, m);
        match event {
            Event::Surface { hit, dir: d, path_length, medium } => {
                arc += path_length;
                // The hit is located on the arc, a little past the last chord's origin.
                let last = points[points.len() - 1];
                s0 = last.s_m + (hit.point - last.position).length();
                let n = prop.n_at(medium, wavelength_nm, hit.point);
                points.push(PathPoint { s_m: s0, position: hit.point, dir: d, n });
                let name = &world.names.prims[hit.prim as usize];
                let pr = &world.prims[hit.prim as usize];
                let at = format!("s = {arc:.6} m at {} going {}", xyz(hit.point), heading(d));
                if pr.material.is_some() || pr.light.is_some() {
                    let what = match pr.material {
                        Some(m) => format!("material \"{}\"", world.names.materials[m as usize]),
                        None => "an emitter".to_string(),
                    };
                    lines.push(format!("{k:>3}  surface   {at}: {name} ({what}); the trace stops here"));
                    return Traced { points, lines, end: End::Surface(name.clone()), work: prop.work.totals() };
                }
                let (nd, across) = prop.cross(&hit, d, medium, wavelength_nm, 1.0);
                let n_across = prop.n_at(across, wavelength_nm, hit.point);
                let into = world.medium_across(hit.prim, d, hit.normal);
                let how = if across != into {
                    format!("totally reflected back into {}", medium_name(across))
                } else if nd == d {
                    format!("straight on into {} (n = {n_across:.8})", medium_name(across))
                } else {
                    format!("refracted into {} (n = {n_across:.8})", medium_name(across))
                };
                lines.push(format!("{k:>3}  boundary  {at}: {name}, from {} (n = {n:.8}), {how}", medium_name(medium)));
                state = prop.leave(&hit, nd, Some(wavelength_nm), across);
            }
            Event::Escape { dir: d } => {
                if let Some(t) = tip {
                    s0 = t.s_m;
                    points.push(PathPoint { dir: d, n: prop.n_at(state.medium, wavelength_nm, t.position), ..t });
                }
                let sees = sees(world, d, wavelength_nm);
                lines.push(format!("{k:>3}  escape    after {s0:.3} m of chords, going {}: {sees}", heading(d)));
                return Traced { points, lines, end: End::Escape(d), work: prop.work.totals() };
            }
            Event::Lost { position } => {
                lines.push(format!("{k:>3}  lost      at {}: the integrator failed there", xyz(position)));
                return Traced { points, lines, end: End::Lost(position), work: prop.work.totals() };
            }
            Event::Medium { position, dir: d, medium, .. } => {
                // Only the length limit stops a path inside a medium.
                let n = prop.n_at(Some(medium), wavelength_nm, position);
                points.push(PathPoint { s_m: limits.length_m, position, dir: d, n });
                lines.push(format!(
                    "{k:>3}  stopped   at s = {:.3} m (--max-length-m) at {} going {}, still in {}",
                    limits.length_m,
                    xyz(position),
                    heading(d),
                    medium_label(world, Some(medium))
                ));
                return Traced { points, lines, end: End::LengthLimit, work: prop.work.totals() };
            }
        }
    }
    lines.push(format!("stopped after {} events (--events)", limits.events));
    Traced { points, lines, end: End::EventLimit, work: prop.work.totals() }
}

/// Which lights at infinity a ray escaping along `d` sees.
fn sees(world: &World, d: DVec3, wavelength_nm: f64) -> String {
    let names: Vec<String> = world
        .lights
        .iter()
        .zip(&world.names.lights)
        .filter(|(l, _)| l.escape_radiance(d, wavelength_nm) > 0.0)
        .map(|(_, n)| format!("light \"{n}\""))
        .collect();
    if names.is_empty() { "sees no light".to_string() } else { format!("sees {}", names.join(", ")) }
}

/// A medium's name in quotes, or `vacuum`, for messages.
pub fn medium_label(world: &World, m: Option<u32>) -> String {
    m.map_or_else(|| "vacuum".to_string(), |i| format!("\"{}\"", world.names.media[i as usize]))
}

/// The Earth heights are measured from: that of the first medium whose index is an atmosphere
/// (its file's, or the scene's `[world] earth`), else flat ground y = 0.
pub fn world_earth(world: &World) -> (Earth, String) {
    let atmosphere = world.media.iter().zip(&world.names.media).find_map(|(m, name)| match &m.index {
        Some(IndexField::Atmosphere(a)) => Some((a.earth, name)),
        _ => None,
    });
    match atmosphere {
        Some((e, name)) => (e, format!("above the Earth of the atmosphere in \"{name}\"")),
        None => (Earth::flat_y(), "y (no atmosphere in the scene)".to_string()),
    }
}

/// The CSV of the path's points.
pub fn csv_text(points: &[PathPoint]) -> String {
    let mut text = String::from("s_m,x,y,z,dx,dy,dz,n\n");
    for p in points {
        let (r, d) = (p.position, p.dir);
        let _ = writeln!(
            text,
            "{:.6},{:.6},{:.6},{:.6},{:.12},{:.12},{:.12},{:.12}",
            p.s_m, r.x, r.y, r.z, d.x, d.y, d.z, p.n
        );
    }
    text
}

/// A point as "(x, y, z)" with three decimals.
pub fn xyz(p: DVec3) -> String {
    format!("({:.3}, {:.3}, {:.3})", p.x, p.y, p.z)
}

/// A direction and its elevation above the xz-plane, in degrees.
pub fn heading(d: DVec3) -> String {
    let elev = d.y.clamp(-1.0, 1.0).asin().to_degrees();
    format!("({:.6}, {:.6}, {:.6}) at elevation {elev:.5}°", d.x, d.y, d.z)
}
