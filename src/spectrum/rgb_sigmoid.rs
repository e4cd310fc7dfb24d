//! RGB albedo to a smooth reflectance spectrum (Jakob & Hanika 2019).
//!
//! The reflectance is a sigmoid of a quadratic polynomial,
//!
//!   s(λ) = S(x),  x = c0 λ² + c1 λ + c2 (λ in nm),  S(x) = ½ + x / (2 √(1 + x²)),
//!
//! so 0 ≤ s ≤ 1 for any coefficients. For a linear-sRGB albedo ρ the coefficients minimise the
//! CIE76 colour difference ΔE*ab between ρ and the colour of s under D65:
//!
//!   XYZ(s) = Σ_λ s(λ) D65(λ) c̄(λ) / Σ_λ D65(λ) ȳ(λ)   (λ = 360, 361, …, 830 nm),
//!   residual r = Lab(XYZ(s)) − Lab(M⁻¹ ρ),  white = XYZ(1),
//!
//! with M the IEC 61966-2-1 XYZ → sRGB matrix. As in the authors' optimiser, the polynomial is
//! fitted in the normalised wavelength t = (λ − 360)/(830 − 360) and solved by Gauss–Newton
//! (3 residuals, 3 unknowns; analytic Jacobian; step halving when a step does not reduce ‖r‖).
//! Where their tool walks a 3D table from the grey axis outwards and warm-starts each entry from
//! its neighbour, a single colour here is reached by the same continuation along the straight
//! line from the grey of equal mean to ρ. Black (0, 0, 0) and white (1, 1, 1) are the limits
//! x → ∓∞ and are returned exactly as c = (0, 0, ∓∞).
//!
//! # References
//! - W. Jakob and J. Hanika (2019), "A Low-Dimensional Function Space for Efficient Spectral
//!   Upsampling", Computer Graphics Forum 38(2), 147–155, §3–4 (and their `rgb2spec_opt.cpp`).
//! - CIE 015:2018, *Colorimetry*, §8.2.1 (CIELAB) and §8.3.1 (ΔE*ab).

use super::cie::{cmf_1931_at_nm, illuminant};
use super::colour::{SUM_END_NM, SUM_START_NM, linear_srgb_to_xyz};
use std::sync::OnceLock;

const LAMBDA_0: f64 = SUM_START_NM as f64;
const LAMBDA_SPAN: f64 = (SUM_END_NM - SUM_START_NM) as f64;
/// Continuation steps from grey to the target colour.
const CONTINUATION_STEPS: usize = 16;
/// Gauss–Newton iterations per continuation step (the last step gets more).
const STEP_ITERATIONS: usize = 8;
const FINAL_ITERATIONS: usize = 60;
/// Stop when ΔE*ab falls below this.
const DELTA_E_TOLERANCE: f64 = 1e-9;

/// A sigmoid-polynomial reflectance s(λ) = S(c0 λ² + c1 λ + c2) in [0, 1].
#[derive(Clone, Debug, PartialEq)]
pub struct RgbSigmoid {
    /// (c0, c1, c2) of the quadratic in λ (nm); c2 = ∓∞ for black and white.
    pub coefficients: [f64; 3],
}

impl RgbSigmoid {
    /// Fits the spectrum whose linear-sRGB albedo under D65 is `rgb` (each in [0, 1]).
    pub fn fit(rgb: [f64; 3]) -> Result<RgbSigmoid, String> {
        if let Some(k) = rgb.iter().position(|c| !(0.0..=1.0).contains(c)) {
            return Err(format!(
                "RGB albedo {rgb:?}: component {k} is {}, allowed are numbers in [0, 1] (linear sRGB)",
                rgb[k]
            ));
        }
        if rgb == [0.0; 3] {
            return Ok(RgbSigmoid { coefficients: [0.0, 0.0, f64::NEG_INFINITY] });
        }
        if rgb == [1.0; 3] {
            return Ok(RgbSigmoid { coefficients: [0.0, 0.0, f64::INFINITY] });
        }
        let tables = tables();
        let mean = (rgb[0] + rgb[1] + rgb[2]) / 3.0;
        let grey = mean.clamp(1e-3, 1.0 - 1e-3);
        let mut z = [0.0, 0.0, sigmoid_inverse(grey)];
        for step in 1..=CONTINUATION_STEPS {
            let f = step as f64 / CONTINUATION_STEPS as f64;
            let target = [0, 1, 2].map(|k| grey + f * (rgb[k] - grey));
            let lab = tables.lab(linear_srgb_to_xyz(target));
            let iterations = if step == CONTINUATION_STEPS { FINAL_ITERATIONS } else { STEP_ITERATIONS };
            z = gauss_newton(tables, z, lab, iterations);
        }
        Ok(RgbSigmoid { coefficients: to_nm_coefficients(z) })
    }

    /// s(λ) at `wavelength_nm`, in [0, 1].
    pub fn eval(&self, wavelength_nm: f64) -> f64 {
        let [c0, c1, c2] = self.coefficients;
        let x = if c0 == 0.0 && c1 == 0.0 { c2 } else { (c0 * wavelength_nm + c1) * wavelength_nm + c2 };
        sigmoid(x)
    }
}

/// S(x) = ½ + x / (2 √(1 + x²)), evaluated without overflow for large |x| (S(±∞) = 1, 0).
fn sigmoid(x: f64) -> f64 {
    if x.abs() > 1.0 {
        let r = 1.0 / x;
        0.5 + 0.5 * x.signum() / (1.0 + r * r).sqrt()
    } else {
        0.5 + 0.5 * x / (1.0 + x * x).sqrt()
    }
}

/// dS/dx = ½ (1 + x²)^(−3/2).
fn sigmoid_derivative(x: f64) -> f64 {
    let q = 1.0 + x * x;
    0.5 / (q * q.sqrt())
}

/// S⁻¹(y) = (2y − 1) / (2 √(y (1 − y))) for 0 < y < 1.
fn sigmoid_inverse(y: f64) -> f64 {
    (2.0 * y - 1.0) / (2.0 * (y * (1.0 - y)).sqrt())
}

/// x = a t² + b t + c with t = (λ − λ0)/Δ, rewritten as c0 λ² + c1 λ + c2.
fn to_nm_coefficients([a, b, c]: [f64; 3]) -> [f64; 3] {
    let (l0, d) = (LAMBDA_0, LAMBDA_SPAN);
    [a / (d * d), b / d - 2.0 * a * l0 / (d * d), a * l0 * l0 / (d * d) - b * l0 / d + c]
}

/// Precomputed D65-weighted colour-matching functions on the 1 nm grid.
struct Tables {
    /// Normalised wavelength t per grid point.
    t: Vec<f64>,
    /// D65(λ) c̄(λ) / Σ D65 ȳ per grid point.
    w: Vec<[f64; 3]>,
    /// XYZ of the perfect reflector (Y = 1).
    white: [f64; 3],
}

fn tables() -> &'static Tables {
    static TABLES: OnceLock<Tables> = OnceLock::new();
    TABLES.get_or_init(|| {
        let d65 = illuminant("D65").unwrap_or_else(|| unreachable!("D65 is built in"));
        let nms: Vec<u32> = (SUM_START_NM..=SUM_END_NM).collect();
        let raw: Vec<[f64; 3]> =
            nms.iter().map(|&nm| cmf_1931_at_nm(nm).map(|c| c * d65.eval(f64::from(nm)))).collect();
        let norm: f64 = raw.iter().map(|w| w[1]).sum();
        let w: Vec<[f64; 3]> = raw.iter().map(|w| w.map(|c| c / norm)).collect();
        let white = w.iter().fold([0.0; 3], |s, w| [0, 1, 2].map(|k| s[k] + w[k]));
        let t = nms.iter().map(|&nm| (f64::from(nm) - LAMBDA_0) / LAMBDA_SPAN).collect();
        Tables { t, w, white }
    })
}

impl Tables {
    /// XYZ of the sigmoid spectrum with normalised coefficients z, and ∂XYZ/∂z (rows: X, Y, Z).
    fn xyz_and_jacobian(&self, z: [f64; 3]) -> ([f64; 3], [[f64; 3]; 3]) {
        let mut xyz = [0.0; 3];
        let mut jac = [[0.0; 3]; 3];
        for (&t, w) in self.t.iter().zip(&self.w) {
            let x = (z[0] * t + z[1]) * t + z[2];
            let s = sigmoid(x);
            let ds = sigmoid_derivative(x);
            let dx = [t * t, t, 1.0];
            for r in 0..3 {
                xyz[r] += s * w[r];
                for c in 0..3 {
                    jac[r][c] += ds * dx[c] * w[r];
                }
            }
        }
        (xyz, jac)
    }

    /// CIELAB of `xyz` relative to the D65 perfect reflector.
    fn lab(&self, xyz: [f64; 3]) -> [f64; 3] {
        let f = [0, 1, 2].map(|k| lab_f(xyz[k] / self.white[k]));
        [116.0 * f[1] - 16.0, 500.0 * (f[0] - f[1]), 200.0 * (f[1] - f[2])]
    }

    /// ∂Lab/∂XYZ at `xyz`.
    fn lab_jacobian(&self, xyz: [f64; 3]) -> [[f64; 3]; 3] {
        let d = [0, 1, 2].map(|k| lab_f_derivative(xyz[k] / self.white[k]) / self.white[k]);
        [[0.0, 116.0 * d[1], 0.0], [500.0 * d[0], -500.0 * d[1], 0.0], [0.0, 200.0 * d[1], -200.0 * d[2]]]
    }
}

/// CIELAB's f(q) = q^(1/3) above (6/29)³, else q / (3 (6/29)²) + 4/29.
fn lab_f(q: f64) -> f64 {
    const D: f64 = 6.0 / 29.0;
    if q > D * D * D { q.cbrt() } else { q / (3.0 * D * D) + 4.0 / 29.0 }
}

fn lab_f_derivative(q: f64) -> f64 {
    const D: f64 = 6.0 / 29.0;
    if q > D * D * D { 1.0 / (3.0 * q.cbrt() * q.cbrt()) } else { 1.0 / (3.0 * D * D) }
}

/// Gauss–Newton on r(z) = Lab(XYZ(z)) − target, with step halving.
fn gauss_newton(tables: &Tables, mut z: [f64; 3], target: [f64; 3], iterations: usize) -> [f64; 3] {
    let residual = |z: [f64; 3]| {
        let (xyz, _) = tables.xyz_and_jacobian(z);
        let lab = tables.lab(xyz);
        [0, 1, 2].map(|k| lab[k] - target[k])
    };
    let norm = |r: [f64; 3]| (r[0] * r[0] + r[1] * r[1] + r[2] * r[2]).sqrt();
    let mut r = residual(z);
    for _ in 0..iterations {
        let err = norm(r);
        if err < DELTA_E_TOLERANCE {
            break;
        }
        let (xyz, j_xyz) = tables.xyz_and_jacobian(z);
        let j = mat_mul(&tables.lab_jacobian(xyz), &j_xyz);
        let Some(delta) = solve3(&j, [-r[0], -r[1], -r[2]]) else {
            break;
        };
        let mut step = 1.0;
        let mut improved = false;
        for _ in 0..30 {
            let trial = [0, 1, 2].map(|k| z[k] + step * delta[k]);
            let rt = residual(trial);
            if norm(rt) < err {
                z = trial;
                r = rt;
                improved = true;
                break;
            }
            step *= 0.5;
        }
        if !improved {
            break;
        }
    }
    z
}

fn mat_mul(a: &[[f64; 3]; 3], b: &[[f64; 3]; 3]) -> [[f64; 3]; 3] {
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| (0..3).map(|k| a[r][k] * b[k][c]).sum()))
}

/// Solves A x = y by Cramer's rule; `None` when A is (numerically) singular.
fn solve3(a: &[[f64; 3]; 3], y: [f64; 3]) -> Option<[f64; 3]> {
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(a);
    if d == 0.0 || !d.is_finite() {
        return None;
    }
    let x = [0, 1, 2].map(|c| {
        let mut m = *a;
        for r in 0..3 {
            m[r][c] = y[r];
        }
        det(&m) / d
    });
    x.iter().all(|v| v.is_finite()).then_some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::spectrum::colour::{relative_xyz, xyz_to_linear_srgb};
    use crate::spectrum::{Spectrum, named_illuminant};

    /// Linear sRGB of a reflectance under D65 through the plain colorimetry route.
    fn albedo(s: &RgbSigmoid) -> [f64; 3] {
        let d65 = named_illuminant("D65").unwrap();
        let xyz = relative_xyz(&Spectrum::RgbReflectance(s.clone()), &d65);
        xyz_to_linear_srgb(xyz.map(|c| c / 100.0))
    }

    #[test]
    fn round_trips_a_grid_of_srgb_albedos() {
        let levels = [0.0, 0.01, 0.1, 0.25, 0.5, 0.75, 0.9, 0.99, 1.0];
        let mut worst = (0.0f64, [0.0; 3]);
        let start = std::time::Instant::now();
        let mut n = 0;
        for r in levels {
            for g in levels {
                for b in levels {
                    let rgb = [r, g, b];
                    let s = RgbSigmoid::fit(rgb).unwrap();
                    n += 1;
                    // A reflectance: within [0, 1] everywhere, also outside the fitted range.
                    for k in 0..=1400 {
                        let v = s.eval(300.0 + 0.5 * f64::from(k));
                        assert!((0.0..=1.0).contains(&v), "{rgb:?}: s = {v}");
                    }
                    let back = albedo(&s);
                    let err = (0..3).map(|k| (back[k] - rgb[k]).abs()).fold(0.0, f64::max);
                    if err > worst.0 {
                        worst = (err, rgb);
                    }
                }
            }
        }
        let per_colour = start.elapsed().as_secs_f64() / n as f64;
        eprintln!("worst round trip {:?}, {:.3} ms per colour", worst, per_colour * 1e3);
        assert!(worst.0 < 1e-3, "worst round trip error {worst:?}");
        // Fast enough to fit every material at scene load (timing includes the check above).
        assert!(per_colour < 5e-3, "{per_colour} s per colour");
    }

    #[test]
    fn black_white_and_grey_are_flat() {
        let black = RgbSigmoid::fit([0.0; 3]).unwrap();
        let white = RgbSigmoid::fit([1.0; 3]).unwrap();
        for l in [200.0, 360.0, 555.0, 830.0, 2000.0] {
            assert_eq!(black.eval(l), 0.0);
            assert_eq!(white.eval(l), 1.0);
        }
        // A grey albedo needs a (nearly) constant reflectance: the CIE D65 spectrum's white
        // differs from the sRGB white by < 0.02 %, so the fit may tilt only that much.
        let grey = RgbSigmoid::fit([0.5; 3]).unwrap();
        for l in (360..=830).step_by(10) {
            assert!((grey.eval(f64::from(l)) - 0.5).abs() < 1e-3, "{l} nm");
        }
    }

    #[test]
    fn sigmoid_matches_its_closed_form_and_limits() {
        assert_eq!(sigmoid(0.0), 0.5);
        assert!((sigmoid(1.0) - (0.5 + 0.5 / 2f64.sqrt())).abs() < 1e-15);
        assert!((sigmoid(-3.0) - (0.5 - 1.5 / 10f64.sqrt())).abs() < 1e-15);
        assert_eq!(sigmoid(1e300), 1.0);
        assert_eq!(sigmoid(f64::INFINITY), 1.0);
        assert_eq!(sigmoid(f64::NEG_INFINITY), 0.0);
        for y in [0.01, 0.3, 0.5, 0.97] {
            assert!((sigmoid(sigmoid_inverse(y)) - y).abs() < 1e-14);
        }
        // The normalised-wavelength polynomial and its nm form agree.
        let z = [3.0, -2.0, 0.5];
        let c = to_nm_coefficients(z);
        for l in [360.0, 512.0, 830.0] {
            let t: f64 = (l - 360.0) / 470.0;
            let want = z[0] * t * t + z[1] * t + z[2];
            let got = c[0] * l * l + c[1] * l + c[2];
            assert!((got - want).abs() < 1e-11, "{l}: {got} vs {want}");
        }
    }

    #[test]
    fn rejects_albedos_outside_the_unit_cube() {
        for rgb in [[1.1, 0.0, 0.0], [0.0, -0.01, 0.0], [0.5, 0.5, f64::NAN]] {
            let e = RgbSigmoid::fit(rgb).unwrap_err();
            assert!(e.contains("allowed are numbers in [0, 1]"), "{e}");
        }
    }
}
