//! CIELAB and the CIEDE2000 colour difference, for checking adapted colours.
//!
//! L* = 116 f(Y/Y_n) − 16, a* = 500 (f(X/X_n) − f(Y/Y_n)), b* = 200 (f(Y/Y_n) − f(Z/Z_n)), with
//! f(t) = t^(1/3) for t > (6/29)³ and t/(3 (6/29)²) + 4/29 otherwise (CIE 015:2018 §8.2.1).
//! ΔE₀₀ follows Sharma, Wu & Dalal (2005), Eqs. (1)–(22), with k_L = k_C = k_H = 1.
//!
//! # References
//! - CIE 015:2018, *Colorimetry*, 4th ed., §8.2.1 (CIELAB) and §8.3.2 (CIEDE2000).
//! - G. Sharma, W. Wu, E. N. Dalal (2005), "The CIEDE2000 color-difference formula:
//!   implementation notes, supplementary test data, and mathematical observations", Color
//!   Research & Application 30(1), 21–30.

/// CIELAB of `xyz` relative to the white `white` (same scale as `xyz`).
pub fn xyz_to_lab(xyz: [f64; 3], white: [f64; 3]) -> [f64; 3] {
    let f = |t: f64| {
        let d = 6.0 / 29.0;
        if t > d * d * d { t.cbrt() } else { t / (3.0 * d * d) + 4.0 / 29.0 }
    };
    let [fx, fy, fz] = [0, 1, 2].map(|k| f(xyz[k] / white[k]));
    [116.0 * fy - 16.0, 500.0 * (fx - fy), 200.0 * (fy - fz)]
}

/// The CIEDE2000 difference ΔE₀₀ between two CIELAB colours.
pub fn delta_e_2000(lab1: [f64; 3], lab2: [f64; 3]) -> f64 {
    let c_bar = 0.5 * (lab1[1].hypot(lab1[2]) + lab2[1].hypot(lab2[2]));
    let c7 = c_bar.powi(7);
    let g = 0.5 * (1.0 - (c7 / (c7 + 25f64.powi(7))).sqrt());
    let prime = |lab: [f64; 3]| {
        let a = (1.0 + g) * lab[1];
        let c = a.hypot(lab[2]);
        let h = if c == 0.0 { 0.0 } else { lab[2].atan2(a).to_degrees().rem_euclid(360.0) };
        (c, h)
    };
    let ((c1, h1), (c2, h2)) = (prime(lab1), prime(lab2));
    let dl = lab2[0] - lab1[0];
    let dc = c2 - c1;
    let dh_angle = if c1 * c2 == 0.0 {
        0.0
    } else {
        let d = h2 - h1;
        if d > 180.0 {
            d - 360.0
        } else if d < -180.0 {
            d + 360.0
        } else {
            d
        }
    };
    let dh = 2.0 * (c1 * c2).sqrt() * (0.5 * dh_angle).to_radians().sin();
    let l_bar = 0.5 * (lab1[0] + lab2[0]);
    let c_bar_p = 0.5 * (c1 + c2);
    let h_bar = mean_hue(h1, h2, c1 * c2 == 0.0);
    let t = 1.0 - 0.17 * (h_bar - 30.0).to_radians().cos()
        + 0.24 * (2.0 * h_bar).to_radians().cos()
        + 0.32 * (3.0 * h_bar + 6.0).to_radians().cos()
        - 0.20 * (4.0 * h_bar - 63.0).to_radians().cos();
    let d_theta = 30.0 * (-((h_bar - 275.0) / 25.0).powi(2)).exp();
    let c7p = c_bar_p.powi(7);
    let r_c = 2.0 * (c7p / (c7p + 25f64.powi(7))).sqrt();
    let l50 = (l_bar - 50.0).powi(2);
    let s_l = 1.0 + 0.015 * l50 / (20.0 + l50).sqrt();
    let s_c = 1.0 + 0.045 * c_bar_p;
    let s_h = 1.0 + 0.015 * c_bar_p * t;
    let r_t = -(2.0 * d_theta).to_radians().sin() * r_c;
    let (l, c, h) = (dl / s_l, dc / s_c, dh / s_h);
    (l * l + c * c + h * h + r_t * c * h).sqrt()
}

/// The mean hue h̄′ of Sharma et al. Eq. (14), degrees.
fn mean_hue(h1: f64, h2: f64, achromatic: bool) -> f64 {
    if achromatic {
        h1 + h2
    } else if (h1 - h2).abs() <= 180.0 {
        0.5 * (h1 + h2)
    } else if h1 + h2 < 360.0 {
        0.5 * (h1 + h2 + 360.0)
    } else {
        0.5 * (h1 + h2 - 360.0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn matches_the_published_test_pairs() {
        // Sharma, Wu & Dalal (2005) Table 1, pairs 1, 7, 13 (the hue-angle wrap case), 17, 18, 24, 33;
        // colour-science 0.4.7 gives the same values.
        let pairs = [
            ([50.0, 2.6772, -79.7751], [50.0, 0.0, -82.7485], 2.0425),
            ([50.0, 0.0, 0.0], [50.0, -1.0, 2.0], 2.3669),
            ([50.0, -0.001, 2.49], [50.0, 0.0011, -2.49], 4.7461),
            ([50.0, 2.5, 0.0], [73.0, 25.0, -18.0], 27.1492),
            ([50.0, 2.5, 0.0], [50.0, 3.1736, 0.5854], 1.0000),
            ([60.2574, -34.0099, 36.2677], [60.4626, -34.1751, 39.4387], 1.2644),
            ([22.7233, 20.0904, -46.6940], [23.0331, 14.9730, -42.5619], 2.0373),
        ];
        for (a, b, want) in pairs {
            let got = delta_e_2000(a, b);
            assert!((got - want).abs() < 5e-5, "{a:?} {b:?}: {got} vs {want}");
            assert!((delta_e_2000(b, a) - got).abs() < 1e-12, "symmetric");
        }
        assert_eq!(delta_e_2000([40.0, 10.0, -5.0], [40.0, 10.0, -5.0]), 0.0);
    }

    #[test]
    fn lab_of_the_white_and_of_grey() {
        let w = [0.9505, 1.0, 1.089];
        assert_eq!(xyz_to_lab(w, w), [100.0, 0.0, 0.0]);
        // Y = 0.18 gives L* = 49.496 (116 · 0.18^(1/3) − 16).
        let grey = xyz_to_lab(w.map(|c| 0.18 * c), w);
        assert!((grey[0] - 49.496).abs() < 1e-3 && grey[1].abs() < 1e-12 && grey[2].abs() < 1e-12, "{grey:?}");
        // Below (6/29)³ the linear branch: L* = 903.3 Y.
        assert!((xyz_to_lab(w.map(|c| 0.001 * c), w)[0] - 0.9033).abs() < 1e-3);
    }
}
