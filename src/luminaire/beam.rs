//! Polar curves and beam spread.
//!
//! A plane curve is the intensity in the vertical plane pair C / C + 180° of the luminaire frame
//! (type C angles, whatever the file's type): a signed angle a ≥ 0 is γ = a in plane C, a < 0 is
//! γ = −a in plane C + 180°. These are the C0–C180 and C90–C270 curves of a polar diagram.
//!
//! The beam angle (I ≥ 50% of the curve's peak) and field angle (10%) are the full angles between
//! the first directions on either side of the peak where the curve falls to that fraction
//! (linearly interpolated between samples), as in ANSI/NEMA/IES practice for floodlights and
//! CIE 121 for the "half-peak spread".

use super::web::{PhotometricWeb, WebAxes};

/// Intensities along a plane pair (module docs).
#[derive(Clone, Debug, PartialEq)]
pub struct PlaneCurve {
    /// Plane angle C of the positive angles, degrees (negative angles lie in C + 180°).
    pub c_deg: f64,
    /// Signed angles from −180° to 180°.
    pub angles_deg: Vec<f64>,
    /// Intensity at each angle, cd.
    pub cd: Vec<f64>,
}

/// The curve in planes `c_deg` / `c_deg` + 180°, sampled every `step_deg`.
pub fn plane_curve(web: &PhotometricWeb, c_deg: f64, step_deg: f64) -> PlaneCurve {
    let n = (360.0 / step_deg).round().max(2.0) as usize;
    let angles_deg: Vec<f64> = (0..=n).map(|i| -180.0 + 360.0 * i as f64 / n as f64).collect();
    let cd = angles_deg
        .iter()
        .map(|a| {
            let (c, g) = if *a >= 0.0 { (c_deg, *a) } else { (c_deg + 180.0, -a) };
            web.intensity(WebAxes::TYPE_C.direction(c, g))
        })
        .collect();
    PlaneCurve { c_deg, angles_deg, cd }
}

/// Full angle about the peak within which I ≥ `fraction` × peak; `None` when the curve does not
/// fall that low on both sides (an isotropic source has no beam angle) or is dark. The curve is
/// a closed loop (−180° and 180° are the zenith seen from both planes), so a beam around the
/// zenith is measured across it.
pub fn spread_angle_deg(curve: &PlaneCurve, fraction: f64) -> Option<f64> {
    // The last sample repeats the first direction.
    let m = curve.cd.len().saturating_sub(1);
    if m < 2 {
        return None;
    }
    let v = |i: i64| curve.cd[i.rem_euclid(m as i64) as usize];
    let a = |i: i64| curve.angles_deg[i.rem_euclid(m as i64) as usize] + 360.0 * i.div_euclid(m as i64) as f64;
    let (k, peak) = (0..m).fold((0, 0.0), |best, i| if curve.cd[i] > best.1 { (i as i64, curve.cd[i]) } else { best });
    if peak <= 0.0 {
        return None;
    }
    let level = fraction * peak;
    let cross = |i: i64, j: i64| a(i) + (a(j) - a(i)) * (v(i) - level) / (v(i) - v(j));
    let left = (0..m as i64).map(|s| k - s).find(|&i| v(i - 1) < level).map(|i| cross(i, i - 1))?;
    let right = (0..m as i64).map(|s| k + s).find(|&i| v(i + 1) < level).map(|i| cross(i, i + 1))?;
    Some(right - left)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cosine_distribution_has_beam_120_and_field_2_acos_01() {
        // I = I0 cos γ below the horizon: 50% at γ = 60°, 10% at γ = acos 0.1 = 84.26°.
        let g: Vec<f64> = (0..=90).map(f64::from).collect();
        let cd = g.iter().map(|x| 100.0 * x.to_radians().cos()).collect();
        let web = PhotometricWeb::new(WebAxes::TYPE_C, vec![0.0], true, g, cd).unwrap();
        let curve = plane_curve(&web, 0.0, 0.05);
        let beam = spread_angle_deg(&curve, 0.5).unwrap();
        let field = spread_angle_deg(&curve, 0.1).unwrap();
        // Linear interpolation in cos γ between 1° nodes errs by < 0.01° here.
        assert!((beam - 120.0).abs() < 0.02, "{beam}");
        assert!((field - 2.0 * 0.1f64.acos().to_degrees()).abs() < 0.02, "{field}");
    }

    #[test]
    fn an_uplight_beam_is_measured_across_the_zenith() {
        // I = I0 |cos γ| above the horizon only: the beam spans the zenith, 120° wide.
        let g: Vec<f64> = (90..=180).map(f64::from).collect();
        let cd = g.iter().map(|x| (-100.0 * x.to_radians().cos()).max(0.0)).collect();
        let web = PhotometricWeb::new(WebAxes::TYPE_C, vec![0.0], true, g, cd).unwrap();
        let beam = spread_angle_deg(&plane_curve(&web, 0.0, 0.05), 0.5).unwrap();
        assert!((beam - 120.0).abs() < 0.02, "{beam}");
    }

    #[test]
    fn an_isotropic_source_has_no_beam_angle() {
        let web = PhotometricWeb::new(WebAxes::TYPE_C, vec![0.0], true, vec![0.0, 180.0], vec![5.0, 5.0]).unwrap();
        assert_eq!(spread_angle_deg(&plane_curve(&web, 0.0, 1.0), 0.5), None);
    }

    #[test]
    fn the_curve_joins_plane_c_and_c_plus_180() {
        let web = PhotometricWeb::new(
            WebAxes::TYPE_C,
            vec![0.0, 90.0, 180.0, 270.0],
            true,
            vec![0.0, 90.0],
            vec![1.0, 10.0, 1.0, 20.0, 1.0, 30.0, 1.0, 40.0],
        )
        .unwrap();
        let c = plane_curve(&web, 90.0, 90.0);
        assert_eq!(c.angles_deg, vec![-180.0, -90.0, 0.0, 90.0, 180.0]);
        for (got, want) in c.cd.iter().zip([0.0, 40.0, 1.0, 20.0, 0.0]) {
            assert!((got - want).abs() < 1e-9, "{:?}", c.cd);
        }
    }
}
