//! `[[shape]]` records → shapes. A box becomes six quads and a mesh its triangles; every
//! resulting shape refers to the record's material.

use super::raw::RawShape;
use crate::geometry::mesh::load_obj;
use crate::geometry::{Disk, Quad, Shape, Sphere, Triangle};
use crate::validate::present_fields;
use crate::validate::{Ctx, MAX_LENGTH_M, MIN_LENGTH_M, R};
use glam::{DMat3, DVec3};
use toml::Spanned;

/// The shapes one record produced and the material they use.
pub struct ShapeGroup {
    pub name: String,
    /// None for an index-matched boundary (a surface that only separates media).
    pub material: Option<Spanned<String>>,
    pub shapes: Vec<Shape>,
}

const KINDS: &[&str] = &["sphere", "quad", "box", "disk", "triangle", "mesh"];

pub fn shape(ctx: &Ctx, rec: &Spanned<RawShape>, index: usize) -> R<ShapeGroup> {
    let span = rec.span();
    let s = rec.get_ref();
    let name =
        s.name.as_ref().map_or_else(|| format!("shape #{}", index + 1), |n| format!("shape \"{}\"", n.get_ref()));
    let kind = ctx.choice(ctx.require(&s.kind, "type", &span, &name)?, &format!("{name}: type"), KINDS)?;
    let what = format!("{name} ({kind})");
    let material = s.material.clone();
    let present = present_fields!(s; center, radius, normal, origin, u, v, min, max, vertices, file, scale, translate, rotate_y_deg);
    let shapes = match kind {
        "sphere" => {
            ctx.only(&present, &["center", "radius"], &what)?;
            let center = ctx.vec3(ctx.require(&s.center, "center", &span, &what)?, "center")?;
            let radius = ctx.number(
                ctx.require(&s.radius, "radius", &span, &what)?,
                "radius",
                MIN_LENGTH_M,
                MAX_LENGTH_M,
                false,
            )?;
            vec![Shape::Sphere(Sphere { center, radius })]
        }
        "disk" => {
            ctx.only(&present, &["center", "radius", "normal"], &what)?;
            let center = ctx.vec3(ctx.require(&s.center, "center", &span, &what)?, "center")?;
            let radius = ctx.number(
                ctx.require(&s.radius, "radius", &span, &what)?,
                "radius",
                MIN_LENGTH_M,
                MAX_LENGTH_M,
                false,
            )?;
            let normal = ctx.direction(ctx.require(&s.normal, "normal", &span, &what)?, "normal")?;
            vec![Shape::Disk(Disk { center, normal, radius })]
        }
        "quad" => {
            ctx.only(&present, &["origin", "u", "v"], &what)?;
            vec![Shape::Quad(quad(ctx, s, &span, &what)?)]
        }
        "box" => {
            ctx.only(&present, &["min", "max"], &what)?;
            let lo = ctx.vec3(ctx.require(&s.min, "min", &span, &what)?, "min")?;
            let hi_field = ctx.require(&s.max, "max", &span, &what)?;
            let hi = ctx.vec3(hi_field, "max")?;
            if !(hi.cmpgt(lo).all()) {
                return Err(ctx.err(&hi_field.span(), format!("{what}: max {hi} must exceed min {lo} on every axis")));
            }
            box_quads(lo, hi)
        }
        "triangle" => {
            ctx.only(&present, &["vertices"], &what)?;
            let v = ctx.require(&s.vertices, "vertices", &span, &what)?;
            let p: Vec<[f64; 3]> = v.get_ref().iter().map(|x| x.0).collect();
            if p.len() != 3 || p.iter().flatten().any(|x| x.abs() > MAX_LENGTH_M) {
                return Err(ctx.err(
                    &v.span(),
                    format!("{what}: vertices must be three points of three finite numbers within ±{MAX_LENGTH_M:e}"),
                ));
            }
            let tri = [DVec3::from_array(p[0]), DVec3::from_array(p[1]), DVec3::from_array(p[2])];
            if (tri[1] - tri[0]).cross(tri[2] - tri[0]).length() < MIN_LENGTH_M * MIN_LENGTH_M {
                return Err(ctx.err(&v.span(), format!("{what}: the triangle is degenerate (area below 1e-18 m²)")));
            }
            vec![Shape::Triangle(Triangle { p: tri })]
        }
        _ => {
            ctx.only(&present, &["file", "scale", "translate", "rotate_y_deg"], &what)?;
            mesh(ctx, s, &span, &what)?
        }
    };
    Ok(ShapeGroup { name, material, shapes })
}

fn quad(ctx: &Ctx, s: &RawShape, span: &std::ops::Range<usize>, what: &str) -> R<Quad> {
    let origin = ctx.vec3(ctx.require(&s.origin, "origin", span, what)?, "origin")?;
    let u = ctx.vec3(ctx.require(&s.u, "u", span, what)?, "u")?;
    let v = ctx.vec3(ctx.require(&s.v, "v", span, what)?, "v")?;
    if u.cross(v).length() < MIN_LENGTH_M * MIN_LENGTH_M {
        return Err(
            ctx.err(span, format!("{what}: edges u and v are parallel or zero; the quad has no area (below 1e-18 m²)"))
        );
    }
    Ok(Quad { origin, u, v })
}

/// Six quads with outward normals (u × v points out of the box).
pub fn box_quads(lo: DVec3, hi: DVec3) -> Vec<Shape> {
    let d = hi - lo;
    let (x, y, z) = (DVec3::new(d.x, 0.0, 0.0), DVec3::new(0.0, d.y, 0.0), DVec3::new(0.0, 0.0, d.z));
    [(lo, z, y), (hi, -y, -z), (lo, x, z), (hi, -z, -x), (lo, y, x), (hi, -x, -y)]
        .into_iter()
        .map(|(origin, u, v)| Shape::Quad(Quad { origin, u, v }))
        .collect()
}

/// Triangles of an OBJ file, transformed by scale, then rotation about +y, then translation.
fn mesh(ctx: &Ctx, s: &RawShape, span: &std::ops::Range<usize>, what: &str) -> R<Vec<Shape>> {
    let file = ctx.require(&s.file, "file", span, what)?;
    let path = ctx.path(file);
    let tris = load_obj(&path).map_err(|e| ctx.err(&file.span(), format!("{what}: {e}")))?;
    let scale = s.scale.as_ref().map_or(Ok(1.0), |v| ctx.number(v, "scale", 0.0, f64::INFINITY, true))?;
    let translate = s.translate.as_ref().map_or(Ok(DVec3::ZERO), |v| ctx.vec3(v, "translate"))?;
    let angle = s.rotate_y_deg.as_ref().map_or(Ok(0.0), |v| ctx.number(v, "rotate_y_deg", -360.0, 360.0, false))?;
    let rot = DMat3::from_rotation_y(angle.to_radians());
    let xf = |p: DVec3| rot * (p * scale) + translate;
    let placed: Vec<[DVec3; 3]> = tris.into_iter().map(|t| t.p.map(xf)).collect();
    if let Some(p) = placed.iter().flatten().find(|p| !p.is_finite() || p.abs().max_element() > MAX_LENGTH_M) {
        let at = s.scale.as_ref().map_or_else(|| file.span(), |v| v.span());
        return Err(ctx.err(
            &at,
            format!(
                "{what}: scale and translate put a vertex at {p}, beyond ±{MAX_LENGTH_M:e} m (make the scale smaller)"
            ),
        ));
    }
    Ok(placed.into_iter().map(|p| Shape::Triangle(Triangle { p })).collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn box_quads_face_outwards_and_cover_the_surface() {
        let quads = box_quads(DVec3::new(-1.0, -2.0, -3.0), DVec3::new(1.0, 2.0, 3.0));
        let mut area = 0.0;
        for q in &quads {
            let Shape::Quad(q) = q else { unreachable!() };
            let centre = q.origin + 0.5 * (q.u + q.v);
            let n = q.u.cross(q.v).normalize();
            assert!(n.dot(centre) > 0.0, "normal {n} at {centre} points inward");
            area += q.u.cross(q.v).length();
        }
        assert!((area - 2.0 * (2.0 * 4.0 + 2.0 * 6.0 + 4.0 * 6.0)).abs() < 1e-12);
    }
}
