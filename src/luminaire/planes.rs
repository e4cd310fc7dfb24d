//! From stored planes to a [`PhotometricWeb`]: the step every gridded reader shares once it
//! knows its photometric type and symmetry (LM-63, TM-33).
//!
//! The stored planes are expanded to the full circle by their symmetry ([`super::symmetry`]); a
//! plane repeating an earlier one (C360 after C0) is dropped with a note when their values
//! differ; the angles are mapped to the web's axes by type (LM-63-2002 §3, the conventions of
//! [`super::web`]):
//!
//! - type C: planes C, polar angles γ as given;
//! - type A: γ = V + 90° (V is an elevation), H clockwise seen from above;
//! - type B: γ = 90° − V about the transverse axis (the polar angles reversed so they ascend).
//!
//! Types A and B form a periodic web only when their planes span the full circle (the last,
//! repeating the first, is dropped); otherwise the web emits nothing outside them.

use super::symmetry::{self, Plane, Symmetry};
use super::web::{PhotometricWeb, WebAxes};
use super::{ParseError, PhotometricType};

/// The web of `planes` (stored, with polar angles `v` in the file's own convention), each value
/// times `scale`. `table_field` names the intensity table in errors ("LM-63 candela table").
pub fn web_from_planes(
    ptype: PhotometricType,
    symmetry: Symmetry,
    planes: Vec<Plane>,
    v: Vec<f64>,
    scale: f64,
    table_field: &str,
    notes: &mut Vec<String>,
) -> Result<PhotometricWeb, ParseError> {
    let mut full = symmetry::expand(planes, symmetry);
    let span = full[full.len() - 1].0 - full[0].0;
    let periodic = ptype == PhotometricType::C || span >= 360.0 - 1e-9;
    if ptype != PhotometricType::C && span >= 360.0 - 1e-9 {
        full.pop();
    }
    dedup_planes(&mut full, notes);
    let (axes, gamma, reverse) = match ptype {
        PhotometricType::C => (WebAxes::TYPE_C, v, false),
        PhotometricType::A => (WebAxes::TYPE_A, v.iter().map(|x| x + 90.0).collect(), false),
        PhotometricType::B => (WebAxes::TYPE_B, v.iter().rev().map(|x| 90.0 - x).collect(), true),
    };
    let c: Vec<f64> = full.iter().map(|p| p.0).collect();
    let cd: Vec<f64> = full
        .into_iter()
        .flat_map(|(_, mut row)| {
            if reverse {
                row.reverse();
            }
            row
        })
        .map(|x| x * scale)
        .collect();
    let web = PhotometricWeb::new(axes, c, periodic, gamma, cd)
        .map_err(|e| ParseError::whole_file(table_field, e, "a valid photometric web"))?;
    if let Some(n) = web.pole_note() {
        notes.push(n.to_string());
    }
    Ok(web)
}

/// Drops a plane that repeats an earlier one (C360 after C0), noting when their values differ.
fn dedup_planes(planes: &mut Vec<Plane>, notes: &mut Vec<String>) {
    let mut out: Vec<Plane> = Vec::with_capacity(planes.len());
    for p in planes.drain(..) {
        match out.last() {
            Some(q) if (q.0 - p.0).abs() < 1e-9 => {
                let differ = q.1.iter().zip(&p.1).any(|(a, b)| (a - b).abs() > 0.01 * a.abs().max(b.abs()));
                if differ {
                    notes.push(format!("the planes at {}° and {}° differ; the first is used", q.0, q.0 + 360.0));
                }
            }
            _ => out.push(p),
        }
    }
    *planes = out;
}

/// The symmetry type C plane angles imply (LM-63-2002 §5.14 and LM-63-2019: one plane —
/// rotational; 0–90° — quadrant; 0–180° — about C0–C180; 90–270° (or −90–90°, as EULUMDAT and
/// some TM-33 writers store it) — about C90–C270; 0° to more than 180° — none), or the first
/// and last angle when they fit none of these.
pub fn type_c_symmetry(h: &[f64]) -> Result<Symmetry, String> {
    let (first, last) = (h[0], h[h.len() - 1]);
    match (h.len(), first, last) {
        (1, _, _) => Ok(Symmetry::Rotational),
        (_, 0.0, 90.0) => Ok(Symmetry::Quadrant),
        (_, 0.0, 180.0) => Ok(Symmetry::C0C180),
        (_, 90.0, 270.0) | (_, -90.0, 90.0) => Ok(Symmetry::C90C270),
        (_, 0.0, l) if l > 180.0 => Ok(Symmetry::None),
        _ => Err(format!("first {first}°, last {last}°")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn type_c_symmetry_follows_the_first_and_last_plane() {
        assert_eq!(type_c_symmetry(&[0.0]), Ok(Symmetry::Rotational));
        assert_eq!(type_c_symmetry(&[0.0, 45.0, 90.0]), Ok(Symmetry::Quadrant));
        assert_eq!(type_c_symmetry(&[0.0, 90.0, 180.0]), Ok(Symmetry::C0C180));
        assert_eq!(type_c_symmetry(&[90.0, 180.0, 270.0]), Ok(Symmetry::C90C270));
        assert_eq!(type_c_symmetry(&[-90.0, 0.0, 90.0]), Ok(Symmetry::C90C270));
        assert_eq!(type_c_symmetry(&[0.0, 120.0, 240.0]), Ok(Symmetry::None));
        assert_eq!(type_c_symmetry(&[0.0, 60.0, 120.0]), Err("first 0°, last 120°".to_string()));
    }

    #[test]
    fn a_repeated_c360_plane_is_dropped_with_a_note_when_it_differs() {
        let planes = vec![(0.0, vec![1.0, 1.0]), (180.0, vec![2.0, 2.0]), (360.0, vec![5.0, 1.0])];
        let mut notes = Vec::new();
        let web =
            web_from_planes(PhotometricType::C, Symmetry::None, planes, vec![0.0, 90.0], 2.0, "t", &mut notes).unwrap();
        assert_eq!(web.c_deg(), &[0.0, 180.0]);
        assert_eq!(web.node(1, 1), 4.0);
        assert!(notes.iter().any(|n| n.contains("differ")), "{notes:?}");
    }
}
