//! The world: everything light interacts with — shapes and their primitives, the BVH over them,
//! materials, media and lights, with the names the scene gave them — and the queries
//! propagation asks of it (which medium a point is in, which a path enters across a surface).
//!
//! The scene reader ([`crate::scene`]) builds the world together with the run description
//! (camera, wavelengths, integrator settings, effect plan, sensors); propagation
//! ([`crate::raypath`]) and the photon tracer ([`crate::photon`]) see only the world.

mod gather_share;

use crate::geometry::{Aabb, Bvh, Ray, Shape};
use crate::light::{AreaLight, Light};
use crate::material::Material;
use crate::media::Medium;
use glam::DVec3;

/// What a shape in the BVH is: its material (none for an emitter with no reflectance) and the
/// light it emits as, if any.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Prim {
    /// Index of its material in [`World::materials`] (`None`: an index-matched boundary between
    /// media, or an area light without a material, which reflects nothing).
    pub material: Option<u32>,
    /// Index of the light it belongs to in [`World::lights`] (area lights).
    pub light: Option<u32>,
    /// Medium on the back side of the shape's normal (inside a closed shape). Unless the scene
    /// says otherwise: vacuum inside glass, the world medium inside anything else; an
    /// index-matched boundary (no material) must name it.
    pub interior: Option<u32>,
    /// Medium on the front side (outside); the world medium unless the scene says otherwise.
    pub exterior: Option<u32>,
}

/// The names the scene gave the world's parts, for messages and reports.
#[derive(Clone, Debug, Default)]
pub struct Names {
    /// Material names, by index.
    pub materials: Vec<String>,
    /// Medium names, by index.
    pub media: Vec<String>,
    /// Per primitive: the label of the record it came from (`shape "ground"`, `shape #3`,
    /// `light "lamp"`).
    pub prims: Vec<String>,
    /// Light names, by index.
    pub lights: Vec<String>,
}

/// The sphere beyond which paths escape: twice the radius of the sphere bounding the geometry
/// and the camera (media extend to it).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Reach {
    /// Centre, m.
    pub centre: DVec3,
    /// Radius, m.
    pub radius: f64,
}

impl Reach {
    /// The reach of a world whose geometry and camera lie in `b`.
    pub fn around(b: &Aabb) -> Reach {
        Reach { centre: b.centre(), radius: 2.0 * (0.5 * b.diagonal().length()).max(1e-3) }
    }
}

/// Everything light interacts with.
pub struct World {
    /// The materials; [`Prim::material`] indexes them.
    pub materials: Vec<Material>,
    /// The media; a medium is referred to by its index here (`None`: vacuum).
    pub media: Vec<Medium>,
    /// The medium filling space outside every closed shape (`[world] medium`).
    pub global_medium: Option<u32>,
    /// The surfaces, one per primitive.
    pub shapes: Vec<Shape>,
    /// What each shape is: material, light and the media on its two sides.
    pub prims: Vec<Prim>,
    /// The lights.
    pub lights: Vec<Light>,
    /// The medium each light emits into.
    pub light_media: Vec<Option<u32>>,
    /// The hierarchy over `shapes`.
    pub bvh: Bvh,
    /// Bounds of the shapes.
    pub bounds: Aabb,
    /// Where paths escape.
    pub reach: Reach,
    /// The names the scene gave the parts.
    pub names: Names,
}

impl World {
    /// The material of primitive `prim`, if it has one.
    pub fn material_of(&self, prim: u32) -> Option<&Material> {
        self.prims[prim as usize].material.map(|m| &self.materials[m as usize])
    }

    /// The area light that primitive `prim` emits as, if any.
    pub fn area_light_of(&self, prim: u32) -> Option<&AreaLight> {
        match self.prims[prim as usize].light.map(|l| &self.lights[l as usize]) {
            Some(Light::Area(a)) => Some(a),
            _ => None,
        }
    }

    /// The medium at point `p`: found by a ray from `p`; the side of the first surface it meets
    /// that `p` is on decides (interior when `p` is behind the surface's normal). Points that
    /// see no surface are in the world medium.
    pub fn medium_at(&self, p: DVec3) -> Option<u32> {
        let dir = DVec3::new(0.285_745, 0.903_105, 0.320_528).normalize();
        match self.bvh.intersect(&self.shapes, &Ray::new(p, dir), f64::INFINITY) {
            None => self.global_medium,
            Some(hit) => {
                let prim = &self.prims[hit.prim as usize];
                if dir.dot(hit.normal) > 0.0 { prim.interior } else { prim.exterior }
            }
        }
    }

    /// Whether a path passes through primitive `prim` when it is not reflected (glass and
    /// index-matched boundaries) rather than stopping at it.
    pub fn is_passable(&self, prim: u32) -> bool {
        self.material_of(prim).is_none_or(Material::is_refractive) && self.prims[prim as usize].light.is_none()
    }

    /// The medium a path enters when it passes through primitive `prim` travelling along `dir`.
    pub fn medium_across(&self, prim: u32, dir: DVec3, normal: DVec3) -> Option<u32> {
        let p = &self.prims[prim as usize];
        if dir.dot(normal) < 0.0 { p.interior } else { p.exterior }
    }

    /// The medium with index `m`.
    pub fn medium(&self, m: Option<u32>) -> Option<&Medium> {
        m.map(|i| &self.media[i as usize])
    }
}
