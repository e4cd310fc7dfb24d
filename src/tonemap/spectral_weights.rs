//! Per-band weights that turn spectral radiance into X, Y, Z and scotopic luminance.
//!
//! A pixel's band values v_0 … v_{N−1} at centres c_0 < … < c_{N−1}, with outer band edges
//! λ_min ≤ c_0 and λ_max ≥ c_{N−1}, stand for the spectrum through (λ_min, v_0), (c_0, v_0),
//! (c_1, v_1), …, (c_{N−1}, v_{N−1}), (λ_max, v_{N−1}), zero outside [λ_min, λ_max]: the
//! reconstruction of [`BandsToColour`](crate::spectrum::colour::BandsToColour), here for any
//! increasing centres (spectral EXRs written by other software need not be equally spaced). With
//! φ_i the hat function of band i, X = K_m Σ_λ Σ_i v_i φ_i(λ) x̄(λ) · 1 nm = Σ_i v_i W_i over the
//! integer wavelengths λ = 360 … 830 nm, and the scotopic luminance likewise with K′_m V′(λ).

use super::scotopic::{K_M_SCOTOPIC, v_prime_at_nm};
use crate::spectrum::Bands;
use crate::spectrum::cie::cmf_1931_at_nm;
use crate::spectrum::colour::{K_M, SUM_END_NM, SUM_START_NM};

/// The weights W_i (cd m⁻² per W m⁻² sr⁻¹ nm⁻¹) of each band.
#[derive(Clone, Debug)]
pub struct BandWeights {
    xyz: Vec<[f64; 3]>,
    scotopic: Vec<f64>,
}

impl BandWeights {
    /// Weights for bands centred at `centres_nm` (strictly increasing, finite) within the outer
    /// edges `min_nm` ≤ c_0 and `max_nm` ≥ c_{N−1}.
    pub fn new(centres_nm: &[f64], min_nm: f64, max_nm: f64) -> Result<BandWeights, String> {
        check_layout(centres_nm, min_nm, max_nm)?;
        let n = centres_nm.len();
        let mut w = BandWeights { xyz: vec![[0.0; 3]; n], scotopic: vec![0.0; n] };
        for nm in SUM_START_NM..=SUM_END_NM {
            let l = f64::from(nm);
            if l < min_nm || l > max_nm {
                continue;
            }
            let cmf = cmf_1931_at_nm(nm).map(|c| K_M * c);
            let v = K_M_SCOTOPIC * v_prime_at_nm(nm);
            for (i, phi) in hat_functions(centres_nm, l) {
                for (acc, c) in w.xyz[i].iter_mut().zip(cmf) {
                    *acc += phi * c;
                }
                w.scotopic[i] += phi * v;
            }
        }
        Ok(w)
    }

    /// Weights for a scene's equal bands.
    pub fn uniform(bands: &Bands) -> BandWeights {
        let centres: Vec<f64> = (0..bands.count).map(|i| bands.centre_nm(i)).collect();
        // Equal bands always satisfy the layout checks.
        BandWeights::new(&centres, bands.min_nm, bands.max_nm)
            .unwrap_or_else(|e| unreachable!("equal bands {bands:?}: {e}"))
    }

    /// Absolute XYZ (Y in cd m⁻²) of one pixel's band values; non-finite values count as zero.
    pub fn xyz(&self, values: &[f32]) -> [f64; 3] {
        let mut out = [0.0; 3];
        for (w, &v) in self.xyz.iter().zip(values) {
            let v = finite(v);
            for k in 0..3 {
                out[k] += w[k] * v;
            }
        }
        out
    }

    /// Scotopic luminance (scotopic cd m⁻²) of one pixel's band values.
    pub fn scotopic(&self, values: &[f32]) -> f64 {
        self.scotopic.iter().zip(values).map(|(w, &v)| w * finite(v)).sum()
    }

    /// The XYZ weights W_i.
    pub fn xyz_weights(&self) -> &[[f64; 3]] {
        &self.xyz
    }
}

fn finite(v: f32) -> f64 {
    if v.is_finite() { f64::from(v) } else { 0.0 }
}

/// The bands whose hat functions are non-zero at `l` (inside the outer edges), with their values.
fn hat_functions(c: &[f64], l: f64) -> Vec<(usize, f64)> {
    let n = c.len();
    if l <= c[0] {
        return vec![(0, 1.0)];
    }
    if l >= c[n - 1] {
        return vec![(n - 1, 1.0)];
    }
    // c[j] < l < c[j + 1] or l = c[j + 1]; partition_point gives the first centre ≥ l.
    let j = c.partition_point(|&x| x < l) - 1;
    let t = (l - c[j]) / (c[j + 1] - c[j]);
    vec![(j, 1.0 - t), (j + 1, t)]
}

fn check_layout(c: &[f64], min_nm: f64, max_nm: f64) -> Result<(), String> {
    if c.is_empty() {
        return Err("no spectral bands".into());
    }
    if c.iter().any(|x| !x.is_finite()) || c.windows(2).any(|p| p[1] <= p[0]) {
        return Err(format!("band centres {c:?} nm must be finite and strictly increasing"));
    }
    if !(min_nm.is_finite() && max_nm.is_finite() && min_nm <= c[0] && max_nm >= c[c.len() - 1]) {
        return Err(format!(
            "band edges [{min_nm}, {max_nm}] nm must enclose the band centres {} … {} nm",
            c[0],
            c[c.len() - 1]
        ));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::colour::BandsToColour;

    #[test]
    fn equal_bands_give_the_weights_of_bands_to_colour() {
        for (lo, hi, n) in [(380.0, 780.0, 16), (400.0, 700.0, 7), (360.0, 830.0, 64), (500.0, 600.0, 1)] {
            let bands = Bands::new(lo, hi, n).unwrap();
            let ours = BandWeights::uniform(&bands);
            let theirs = BandsToColour::new(&bands);
            for (a, b) in ours.xyz_weights().iter().zip(theirs.xyz_weights()) {
                for k in 0..3 {
                    assert!((a[k] - b[k]).abs() <= 1e-9 * b[k].abs().max(1.0), "{a:?} vs {b:?}");
                }
            }
        }
    }

    #[test]
    fn scotopic_weights_integrate_v_prime() {
        // One band of 1 W m⁻² sr⁻¹ nm⁻¹ over 380–780 nm is flat: L′ = K′_m Σ V′.
        let w = BandWeights::new(&[580.0], 380.0, 780.0).unwrap();
        let want = K_M_SCOTOPIC * (380..=780).map(v_prime_at_nm).sum::<f64>();
        assert!((w.scotopic(&[1.0]) / want - 1.0).abs() < 1e-12);
        // Unequal centres: the hat functions sum to one everywhere inside the edges, so a flat
        // spectrum still integrates exactly.
        let w = BandWeights::new(&[400.0, 430.0, 520.0, 700.0], 380.0, 780.0).unwrap();
        assert!((w.scotopic(&[1.0; 4]) / want - 1.0).abs() < 1e-12);
        assert_eq!(w.scotopic(&[f32::NAN, 0.0, 0.0, 0.0]), 0.0);
    }

    #[test]
    fn rejects_bad_layouts() {
        assert!(BandWeights::new(&[], 380.0, 780.0).is_err());
        assert!(BandWeights::new(&[500.0, 500.0], 380.0, 780.0).unwrap_err().contains("increasing"));
        assert!(BandWeights::new(&[500.0, 600.0], 550.0, 780.0).unwrap_err().contains("enclose"));
    }
}
