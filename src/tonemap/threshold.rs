//! The human threshold-versus-intensity function ΔL_t(L_a): the smallest visible luminance
//! difference on a background the eye is adapted to.
//!
//! With l = log₁₀ L_a (cd m⁻²), log₁₀ ΔL_t =
//! - −2.86                              for l < −3.94,
//! - (0.405 l + 1.6)^2.18 − 2.86        for −3.94 ≤ l < −1.44 (rods),
//! - l − 0.395                          for −1.44 ≤ l < −0.0184,
//! - (0.249 l + 0.65)^2.7 − 0.72        for −0.0184 ≤ l < 1.9 (cones),
//! - l − 1.255                          for l ≥ 1.9 (Weber's law),
//!
//! the envelope of the rod and cone threshold curves fitted by Ferwerda et al. (1996, Eqs. 1–2,
//! Fig. 4) and used by Ward Larson et al. (1997, Eq. 7) for the histogram ceiling.
//!
//! # References
//! - J. A. Ferwerda, S. N. Pattanaik, P. Shirley, D. P. Greenberg (1996), "A Model of Visual
//!   Adaptation for Realistic Image Synthesis", SIGGRAPH '96, 249–258.
//! - G. Ward Larson, H. Rushmeier, C. Piatko (1997), IEEE TVCG 3(4), 291–306, §4.2.

/// ΔL_t in cd m⁻² at adaptation luminance `la_cd_m2` (values ≤ 0 give the dark-adapted limit).
pub fn threshold_cd_m2(la_cd_m2: f64) -> f64 {
    let l = if la_cd_m2 > 0.0 { la_cd_m2.log10() } else { f64::NEG_INFINITY };
    let log_dl = if l < -3.94 {
        -2.86
    } else if l < -1.44 {
        (0.405 * l + 1.6).powf(2.18) - 2.86
    } else if l < -0.0184 {
        l - 0.395
    } else if l < 1.9 {
        (0.249 * l + 0.65).powf(2.7) - 0.72
    } else {
        l - 1.255
    };
    10f64.powf(log_dl)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn is_continuous_and_increasing_with_weber_behaviour_in_daylight() {
        // Continuity at the branch points (within 0.013 log units, the fits' own mismatch).
        for l in [-3.94f64, -1.44, -0.0184, 1.9] {
            let (a, b) = (threshold_cd_m2(10f64.powf(l - 1e-9)), threshold_cd_m2(10f64.powf(l + 1e-9)));
            assert!((a.log10() - b.log10()).abs() < 0.013, "jump at {l}: {a} vs {b}");
        }
        let mut last = 0.0;
        for i in -60..=60 {
            let t = threshold_cd_m2(10f64.powf(f64::from(i) / 10.0));
            assert!(t >= last, "not monotone at 1e{}", f64::from(i) / 10.0);
            last = t;
        }
        // Weber's law above 10^1.9 cd m⁻²: ΔL/L = 10^−1.255 ≈ 5.6 %.
        assert!((threshold_cd_m2(1000.0) / 1000.0 - 10f64.powf(-1.255)).abs() < 1e-12);
        assert!((threshold_cd_m2(0.0) - 10f64.powf(-2.86)).abs() < 1e-15);
    }
}
