//! A medium whose density follows the height above a spherical Earth is defined from the
//! ground up: below the ground a profile is held at its ground value and an exponential law
//! grows without bound, which is no air at all. Such air must be closed from
//! below by a sphere about the Earth's centre — the ground or the sea — or paths that miss a
//! too-small or misplaced ground wander through thousands of kilometres of sea-level air (the
//! fuzzer found a 4 × 4 render of the sunset sky with a 65 km "Earth" take 16 s of CPU where
//! the real Earth takes 0.2 s).

use super::raw::RawScene;
use crate::atmosphere::Earth;
use crate::error::Result;
use crate::geometry::Shape;
use crate::media::density::Density;
use crate::media::{Coefficients, Medium};
use crate::validate::Ctx;
use crate::world::World;
use glam::DVec3;

/// How far below the Earth's radius the closing sphere may lie, m: terrain below sea level
/// (the Dead Sea's shore, −430 m) or a sea floor under water is fine; an Earth of the wrong
/// size is not.
pub const GROUND_ALLOWANCE_M: f64 = 10_000.0;

/// Refuses a medium of the world whose density follows the height above a spherical Earth when no
/// sphere closes it from below (see the module docs).
pub fn check_ground_closes_the_air(ctx: &Ctx, raw: &RawScene, world: &World) -> Result<()> {
    for (i, (rec, m)) in raw.medium.iter().zip(&world.media).enumerate() {
        let Some((centre, radius_m)) = spherical_earth(m) else { continue };
        if !used(world, i as u32) || closed(world, i as u32, centre, radius_m) {
            continue;
        }
        return Err(ctx.err(
            &rec.span(),
            format!(
                "medium \"{}\" has a density that follows the height above a spherical Earth (centre {:?} m, radius {} m), but no sphere closes it from below: below the ground its air is held at ground level or grows without bound. Add the ground or the sea, a [[shape]] sphere about that centre reaching at least {} m from it ({GROUND_ALLOWANCE_M} m below the Earth's radius), opaque or holding another medium; or set [world] earth_radius_m to the ground's radius",
                m.name,
                centre.to_array(),
                radius_m,
                radius_m - GROUND_ALLOWANCE_M,
            ),
        ));
    }
    Ok(())
}

/// The centre and radius of the spherical Earth whose height the density of `m` follows, if
/// any. A refractive index alone is left alone: below the ground it is held constant, paths
/// there are straight and cheap, and a ray-bending test bench needs no ground.
fn spherical_earth(m: &Medium) -> Option<(DVec3, f64)> {
    let sphere = |e: &Earth| match e {
        Earth::Spherical(s) => Some((s.centre, s.radius_m)),
        Earth::Flat { .. } => None,
    };
    if let Coefficients::Constituents(c) = &m.coefficients {
        // Air, ozone and aerosols each follow their own height profile over the same Earth.
        return c.list().iter().find_map(|k| sphere(k.profile.earth()));
    }
    match &m.density {
        Density::AirProfile(a) => sphere(a.earth()),
        Density::SphericalExponential(s) => Some((s.centre, s.radius_m)),
        Density::Uniform | Density::ExponentialHeight(_) | Density::Grid(_) | Density::Fbm(_) => None,
    }
}

/// Whether medium `i` fills some part of the scene: the world's, or on a side of a shape.
fn used(world: &World, i: u32) -> bool {
    world.global_medium == Some(i) || world.prims.iter().any(|p| p.interior == Some(i) || p.exterior == Some(i))
}

/// Whether a sphere holding everything within `radius_m − GROUND_ALLOWANCE_M` of `centre` keeps
/// medium `i` out of it: opaque, or with another medium (or vacuum) inside.
fn closed(world: &World, i: u32, centre: DVec3, radius_m: f64) -> bool {
    let inner = (radius_m - GROUND_ALLOWANCE_M).max(0.0);
    world.shapes.iter().zip(&world.prims).any(|(s, p)| {
        let Shape::Sphere(sphere) = s else { return false };
        let covers = (sphere.center - centre).length() + inner <= sphere.radius;
        let opaque = p.material.is_some_and(|m| !world.materials[m as usize].is_refractive());
        covers && (opaque || p.interior != Some(i))
    })
}
