//! Symmetries of a C-plane distribution and their expansion to the full circle.
//!
//! Files store only the planes a symmetry does not repeat (EULUMDAT Isym; LM-63's first and last
//! horizontal angle). A reflection about the plane through C = α maps C to 2α − C, so:
//!
//! | symmetry | stored planes (type C) | images |
//! |---|---|---|
//! | rotational | one plane | every C |
//! | about C0–C180 (EULUMDAT Isym 2) | C0–C180 | C ↦ 360° − C |
//! | about C90–C270 (Isym 3) | C270–C90 via C0 (EULUMDAT), C90–C270 (LM-63) | C ↦ 180° − C |
//! | quadrant (Isym 4) | C0–C90 | C ↦ 180° − C, 360° − C, 180° + C |
//! | lateral (LM-63 types A, B, first H = 0) | H0–H90 | H ↦ −H |
//!
//! # References
//! - A. Stockmar (1990/1998), *EULUMDAT/1 and /2 file format specification* (LCI Light
//!   Consulting International), field 3 (Isym) and the plane count Mc1…Mc2 per symmetry.
//! - ANSI/IES LM-63-2002 and LM-63-2019, the horizontal-angle rules for symmetric distributions.

use std::fmt;

/// The symmetry a file declares (or its angle list implies).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Symmetry {
    /// No symmetry: every plane is stored.
    None,
    /// About the vertical axis: one plane stands for all.
    Rotational,
    /// About the C0–C180 plane.
    C0C180,
    /// About the C90–C270 plane.
    C90C270,
    /// About both the C0–C180 and C90–C270 planes.
    Quadrant,
    /// LM-63 types A and B: about the H = 0 plane.
    Lateral,
}

impl fmt::Display for Symmetry {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Symmetry::None => "none",
            Symmetry::Rotational => "rotational (about the vertical axis)",
            Symmetry::C0C180 => "about the C0–C180 plane",
            Symmetry::C90C270 => "about the C90–C270 plane",
            Symmetry::Quadrant => "about the C0–C180 and C90–C270 planes (quadrant)",
            Symmetry::Lateral => "about the H = 0 plane",
        })
    }
}

/// One stored plane: its angle in degrees and its intensities along the polar angles.
pub type Plane = (f64, Vec<f64>);

/// The planes of the full circle (angles in [0°, 360°), ascending; or, for [`Symmetry::Lateral`],
/// in [−180°, 180°]) from the stored planes. A plane and its image at the same angle (the
/// mirror planes themselves) appear once, with the stored values.
pub fn expand(stored: Vec<Plane>, symmetry: Symmetry) -> Vec<Plane> {
    let maps: &[fn(f64) -> f64] = match symmetry {
        Symmetry::None | Symmetry::Rotational => &[],
        Symmetry::C0C180 => &[|c| 360.0 - c],
        Symmetry::C90C270 => &[|c| 180.0 - c],
        Symmetry::Quadrant => &[|c| 180.0 - c, |c| 360.0 - c, |c| 180.0 + c],
        Symmetry::Lateral => &[|c| -c],
    };
    let norm = |c: f64| if symmetry == Symmetry::Lateral { c } else { normalise(c) };
    let mut planes: Vec<Plane> = stored.iter().map(|(c, v)| (norm(*c), v.clone())).collect();
    for map in maps {
        for (c, v) in &stored {
            let image = norm(map(*c));
            if !planes.iter().any(|(p, _)| same_angle(*p, image)) {
                planes.push((image, v.clone()));
            }
        }
    }
    planes.sort_by(|a, b| a.0.total_cmp(&b.0));
    planes
}

/// C in [0°, 360°), with 360° − ε rounded to 0.
pub fn normalise(c: f64) -> f64 {
    let x = c.rem_euclid(360.0);
    if (x - 360.0).abs() < 1e-9 { 0.0 } else { x }
}

fn same_angle(a: f64, b: f64) -> bool {
    (a - b).abs() < 1e-9
}

#[cfg(test)]
mod tests {
    use super::*;

    fn angles(p: &[Plane]) -> Vec<f64> {
        p.iter().map(|x| x.0).collect()
    }

    fn stored(cs: &[f64]) -> Vec<Plane> {
        cs.iter().map(|c| (*c, vec![*c])).collect()
    }

    #[test]
    fn c0_c180_mirrors_to_the_other_half() {
        let full = expand(stored(&[0.0, 45.0, 90.0, 135.0, 180.0]), Symmetry::C0C180);
        assert_eq!(angles(&full), vec![0.0, 45.0, 90.0, 135.0, 180.0, 225.0, 270.0, 315.0]);
        // C225 is the image of C135.
        assert_eq!(full[5].1, vec![135.0]);
    }

    #[test]
    fn c90_c270_from_c270_through_c0_mirrors_about_the_c90_plane() {
        // EULUMDAT Isym 3 stores C270, C300, C330, C0, C30, C60, C90.
        let full = expand(stored(&[270.0, 300.0, 330.0, 0.0, 30.0, 60.0, 90.0]), Symmetry::C90C270);
        assert_eq!(angles(&full), (0..12).map(|i| 30.0 * i as f64).collect::<Vec<_>>());
        // C120 = 180 − 60 is the image of C60; C240 = 180 − (−60) of C300.
        assert_eq!(full[4].1, vec![60.0]);
        assert_eq!(full[8].1, vec![300.0]);
        assert_eq!(full[6].1, vec![0.0], "C180 is the image of C0");
    }

    #[test]
    fn quadrant_fills_all_four_quadrants() {
        let full = expand(stored(&[0.0, 30.0, 60.0, 90.0]), Symmetry::Quadrant);
        assert_eq!(angles(&full), (0..12).map(|i| 30.0 * i as f64).collect::<Vec<_>>());
        for (c, v) in &full {
            let first_quadrant = match *c {
                c if c <= 90.0 => c,
                c if c <= 180.0 => 180.0 - c,
                c if c <= 270.0 => c - 180.0,
                c => 360.0 - c,
            };
            assert_eq!(v[0], first_quadrant, "C{c}");
        }
    }

    #[test]
    fn lateral_mirrors_h_to_minus_h() {
        let full = expand(stored(&[0.0, 45.0, 90.0]), Symmetry::Lateral);
        assert_eq!(angles(&full), vec![-90.0, -45.0, 0.0, 45.0, 90.0]);
        assert_eq!(full[0].1, vec![90.0]);
    }

    #[test]
    fn none_and_rotational_keep_the_planes() {
        assert_eq!(angles(&expand(stored(&[0.0, 120.0, 240.0]), Symmetry::None)), vec![0.0, 120.0, 240.0]);
        assert_eq!(angles(&expand(stored(&[0.0]), Symmetry::Rotational)), vec![0.0]);
        assert_eq!(normalise(-90.0), 270.0);
        assert_eq!(normalise(360.0), 0.0);
    }
}
