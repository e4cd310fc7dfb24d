//! The luminous opening: the part of a luminaire that emits, from the file's dimensions.
//!
//! In the luminaire frame (x along the length = C0, y along the width = C90, z up, origin at
//! the photometric centre) an opening is a point, a flat rectangle or ellipse, or a solid (box,
//! cylinder, ellipsoid) centred on the origin. For near-field work photons start at points drawn
//! uniformly over the opening's area (flat shapes) or volume (solids), each carrying the
//! far-field distribution: the opening then has the luminaire's intensity I(ω) in total and a
//! uniform luminance over its extent, the usual near-field assumption when only far-field data
//! exist.
//!
//! # LM-63 shapes (LM-63-2002 §5.10 and LM-63-2019 Table 1)
//! Width w (along C90), length l (along C0) and height h; negative values mean round:
//! all zero: point; w, l > 0, h = 0: rectangle; w, l < 0, h = 0: circle/ellipse; w, l, h > 0:
//! rectangle with luminous sides (box); w, l < 0, h > 0: vertical cylinder; all < 0: sphere or
//! ellipsoid; w, h < 0, l > 0: horizontal cylinder along C0; l, h < 0, w > 0: horizontal cylinder
//! along C90; one of w, l zero and h ≠ 0: a vertical rectangle/circle facing that axis.
//!
//! # EULUMDAT (Stockmar 1990/1998, fields 16–21)
//! Length (or diameter) and width of the luminous area in mm, width 0 meaning circular; the
//! heights of the luminous area at C0, C90, C180, C270, all 0 for a flat area (otherwise the
//! opening is a box or cylinder of their mean height).

use crate::rng::Rng;
use crate::sampling::{concentric_disk, uniform_sphere};
use glam::DVec3;

/// The shape of an opening (extents in [`Opening::size_m`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Kind {
    /// No extent: all light leaves the photometric centre.
    Point,
    /// A flat shape spanning the two non-zero extents; `round` for an ellipse.
    Flat {
        /// Ellipse (true) or rectangle (false).
        round: bool,
    },
    /// A box with luminous sides.
    Box,
    /// A cylinder whose axis is coordinate `axis` (0 = x, 1 = y, 2 = z), elliptic across it.
    Cylinder {
        /// Index of the axis, 0 = x, 1 = y, 2 = z.
        axis: usize,
    },
    /// An ellipsoid (a sphere when the extents are equal).
    Ellipsoid,
}

/// A luminous opening in the luminaire frame.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Opening {
    /// The shape.
    pub kind: Kind,
    /// Full extents along x (length), y (width), z (height), m.
    pub size_m: DVec3,
}

impl Opening {
    /// The point opening at the photometric centre.
    pub const POINT: Opening = Opening { kind: Kind::Point, size_m: DVec3::ZERO };

    /// From LM-63 width, length, height in metres (signs as in the module docs). The second
    /// value notes a sign pattern the standard does not define (treated as a box).
    pub fn from_lm63(width: f64, length: f64, height: f64) -> (Opening, Option<String>) {
        let size_m = DVec3::new(length.abs(), width.abs(), height.abs());
        let (w, l, h) = (sign(width), sign(length), sign(height));
        let kind = match (w, l, h) {
            (0, 0, 0) => Kind::Point,
            (a, b, 0) if a != 0 && b != 0 => Kind::Flat { round: a < 0 && b < 0 },
            (0, b, c) if b != 0 && c != 0 => Kind::Flat { round: b < 0 && c < 0 },
            (a, 0, c) if a != 0 && c != 0 => Kind::Flat { round: a < 0 && c < 0 },
            (1, 1, 1) => Kind::Box,
            (-1, -1, 1) => Kind::Cylinder { axis: 2 },
            (-1, -1, -1) => Kind::Ellipsoid,
            (-1, 1, -1) => Kind::Cylinder { axis: 0 },
            (1, -1, -1) => Kind::Cylinder { axis: 1 },
            _ => {
                let note = format!(
                    "luminous opening w = {width}, l = {length}, h = {height} m is not an LM-63 shape; emitting from a box of those extents"
                );
                return (Opening { kind: Kind::Box, size_m }, Some(note));
            }
        };
        (Opening { kind, size_m }, None)
    }

    /// From EULUMDAT luminous-area length (or diameter), width (0: circular) and the four
    /// heights, in mm.
    pub fn from_eulumdat(length_mm: f64, width_mm: f64, heights_mm: [f64; 4]) -> Opening {
        let round = width_mm <= 0.0;
        let l = length_mm.max(0.0) * 1e-3;
        let w = if round { l } else { width_mm * 1e-3 };
        let h = heights_mm.iter().map(|x| x.max(0.0)).sum::<f64>() * 0.25e-3;
        let size_m = DVec3::new(l, w, h);
        let kind = match (l > 0.0 && w > 0.0, h > 0.0, round) {
            (false, _, _) => Kind::Point,
            (true, false, round) => Kind::Flat { round },
            (true, true, true) => Kind::Cylinder { axis: 2 },
            (true, true, false) => Kind::Box,
        };
        Opening { kind, size_m: if kind == Kind::Point { DVec3::ZERO } else { size_m } }
    }

    /// True for a point opening.
    pub fn is_point(&self) -> bool {
        self.kind == Kind::Point
    }

    /// A point drawn uniformly over the opening's area or volume (module docs), luminaire frame.
    pub fn sample(&self, rng: &mut Rng) -> DVec3 {
        self.sample_u([rng.uniform(), rng.uniform(), rng.uniform()])
    }

    /// [`Opening::sample`] from three uniforms in [0, 1) (flat shapes use the first two).
    pub fn sample_u(&self, u: [f64; 3]) -> DVec3 {
        let half = 0.5 * self.size_m;
        let centred = |u: f64| 2.0 * u - 1.0;
        match self.kind {
            Kind::Point => DVec3::ZERO,
            Kind::Flat { round } => {
                let uv = [u[0], u[1]];
                let [a, b] = if round { concentric_disk(uv) } else { uv.map(centred) };
                let axes = self.flat_axes();
                let mut p = DVec3::ZERO;
                p[axes[0]] = a * half[axes[0]];
                p[axes[1]] = b * half[axes[1]];
                p
            }
            Kind::Box => DVec3::new(centred(u[0]), centred(u[1]), centred(u[2])) * half,
            Kind::Cylinder { axis } => {
                let [a, b] = concentric_disk([u[0], u[1]]);
                let (i, j) = ((axis + 1) % 3, (axis + 2) % 3);
                let mut p = DVec3::ZERO;
                p[i] = a * half[i];
                p[j] = b * half[j];
                p[axis] = centred(u[2]) * half[axis];
                p
            }
            Kind::Ellipsoid => uniform_sphere([u[0], u[1]]) * u[2].cbrt() * half,
        }
    }

    /// The two axes a flat shape spans (the ones with non-zero extent; x and y by default).
    fn flat_axes(&self) -> [usize; 2] {
        match (self.size_m.x > 0.0, self.size_m.y > 0.0) {
            (true, true) => [0, 1],
            (true, false) => [0, 2],
            (false, true) => [1, 2],
            (false, false) => [0, 1],
        }
    }

    /// In words, for reports.
    pub fn describe(&self) -> String {
        let s = self.size_m * 1000.0;
        match self.kind {
            Kind::Point => "point".into(),
            Kind::Flat { round: false } => format!("rectangle {:.0} × {:.0} mm", s.x.max(s.z), s.y.max(s.z)),
            Kind::Flat { round: true } if s.x == s.y => format!("disk ⌀ {:.0} mm", s.x),
            Kind::Flat { round: true } => format!("ellipse {:.0} × {:.0} mm", s.x.max(s.z), s.y.max(s.z)),
            Kind::Box => format!("box {:.0} × {:.0} × {:.0} mm", s.x, s.y, s.z),
            Kind::Cylinder { axis } => {
                format!("cylinder {:.0} × {:.0} × {:.0} mm (axis {})", s.x, s.y, s.z, ["x", "y", "z"][axis])
            }
            Kind::Ellipsoid => format!("ellipsoid {:.0} × {:.0} × {:.0} mm", s.x, s.y, s.z),
        }
    }
}

fn sign(x: f64) -> i8 {
    if x > 0.0 {
        1
    } else if x < 0.0 {
        -1
    } else {
        0
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::rng::Stream;

    #[test]
    fn lm63_sign_patterns_give_the_standard_shapes() {
        let k = |w, l, h| Opening::from_lm63(w, l, h).0.kind;
        assert_eq!(k(0.0, 0.0, 0.0), Kind::Point);
        assert_eq!(k(0.2, 0.3, 0.0), Kind::Flat { round: false });
        assert_eq!(k(-0.057, -0.057, 0.0), Kind::Flat { round: true });
        assert_eq!(k(0.2, 0.2, 0.1), Kind::Box);
        assert_eq!(k(-0.1, -0.1, 0.3), Kind::Cylinder { axis: 2 });
        assert_eq!(k(-0.1, -0.1, -0.1), Kind::Ellipsoid);
        assert_eq!(k(-0.1, 1.2, -0.1), Kind::Cylinder { axis: 0 });
        assert_eq!(k(1.2, -0.1, -0.1), Kind::Cylinder { axis: 1 });
        assert_eq!(k(-0.1, 0.0, -0.1), Kind::Flat { round: true });
        let (o, note) = Opening::from_lm63(-0.1, 0.2, 0.3);
        assert_eq!(o.kind, Kind::Box);
        assert!(note.is_some());
    }

    #[test]
    fn eulumdat_dimensions_are_millimetres_and_width_zero_is_round() {
        let o = Opening::from_eulumdat(200.0, 0.0, [0.0; 4]);
        assert_eq!(o.kind, Kind::Flat { round: true });
        assert_eq!(o.size_m, DVec3::new(0.2, 0.2, 0.0));
        let o = Opening::from_eulumdat(1183.0, 62.0, [0.0; 4]);
        assert_eq!(o.kind, Kind::Flat { round: false });
        assert!((o.size_m - DVec3::new(1.183, 0.062, 0.0)).length() < 1e-12);
        assert_eq!(Opening::from_eulumdat(0.0, 0.0, [0.0; 4]), Opening::POINT);
        assert_eq!(Opening::from_eulumdat(100.0, 50.0, [20.0, 20.0, 20.0, 20.0]).kind, Kind::Box);
    }

    #[test]
    fn samples_stay_inside_and_fill_the_shape() {
        let mut rng = Rng::for_task(5, Stream::Test, 0);
        let shapes = [
            Opening::from_lm63(0.2, 0.4, 0.0).0,
            Opening::from_lm63(-0.2, -0.4, 0.0).0,
            Opening::from_lm63(0.2, 0.4, 0.1).0,
            Opening::from_lm63(-0.2, -0.4, 0.1).0,
            Opening::from_lm63(-0.2, -0.4, -0.1).0,
            Opening::from_lm63(-0.2, 0.4, -0.2).0,
        ];
        for o in shapes {
            let half = 0.5 * o.size_m;
            let n = 20_000;
            let mut sum = DVec3::ZERO;
            let mut max = DVec3::ZERO;
            for _ in 0..n {
                let p = o.sample(&mut rng);
                assert!(p.abs().cmple(half + 1e-12).all(), "{o:?}: {p}");
                sum += p;
                max = max.max(p.abs());
            }
            // Centred, and reaching close to the edges along every extent it has.
            assert!((sum / n as f64).abs().cmple(0.02 * half.max(DVec3::splat(1e-9))).all(), "{o:?}");
            assert!(max.cmpge(0.95 * half).all(), "{o:?}: reached {max} of {half}");
        }
    }

    #[test]
    fn a_disk_is_uniform_in_area() {
        // For a uniform disk of radius R, P(r < R/2) = 1/4.
        let o = Opening::from_lm63(-0.2, -0.2, 0.0).0;
        let mut rng = Rng::for_task(6, Stream::Test, 0);
        let n = 40_000;
        let inner = (0..n).filter(|_| o.sample(&mut rng).length() < 0.05).count() as f64 / n as f64;
        // Binomial standard deviation √(pq/n) = 0.0022; allow 5σ.
        assert!((inner - 0.25).abs() < 0.011, "{inner}");
    }
}
