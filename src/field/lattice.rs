//! A scalar sampled on a regular 3-D lattice, interpolated trilinearly (C⁰) or by tricubic
//! Catmull–Rom splines (C¹), with the gradient of the interpolant in closed form.
//!
//! Lattice point (i, j, k) sits at origin + (i·dx, j·dy, k·dz); values are stored x fastest, then
//! y, then z. With u = (p − origin)/spacing, the cell index is ⌊u⌋ and t = u − ⌊u⌋ per axis.
//!
//! - Trilinear: f = Σ wᵢ(tx) wⱼ(ty) wₖ(tz) v, w₀ = 1 − t, w₁ = t.
//! - Catmull–Rom (the cubic Hermite spline with central-difference tangents, which interpolates
//!   the lattice values): per axis over the points −1, 0, 1, 2 of the cell,
//!   w₋₁ = (−t³ + 2t² − t)/2, w₀ = (3t³ − 5t² + 2)/2, w₁ = (−3t³ + 4t² + t)/2, w₂ = (t³ − t²)/2.
//!
//! ∂f/∂x = Σ w′ᵢ(tx) wⱼ wₖ v / dx, and likewise for y and z.
//!
//! Beyond the lattice, [`Beyond::Clamp`] holds the values of the nearest face (points are clamped
//! into the box; the stencil repeats the edge values) and [`Beyond::Zero`] treats every point
//! outside the lattice as 0 (for perturbations that fade out at the faces).
//!
//! # References
//! - E. Catmull & R. Rom 1974, "A class of local interpolating splines", in *Computer Aided
//!   Geometric Design* (Academic Press), 317–326.
//! - R. G. Keys 1981, "Cubic convolution interpolation for digital image processing", IEEE Trans.
//!   ASSP 29:1153–1160 (the same kernel with a = −1/2).

use crate::geometry::Aabb;
use glam::DVec3;

/// How values between lattice points are found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Interpolation {
    /// C⁰; the gradient jumps across cell faces.
    Trilinear,
    /// Catmull–Rom in each axis: C¹.
    Tricubic,
}

impl Interpolation {
    /// The name scene and atmosphere files use.
    pub fn name(&self) -> &'static str {
        match self {
            Interpolation::Trilinear => "trilinear",
            Interpolation::Tricubic => "tricubic",
        }
    }
}

/// What the lattice is outside its box.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Beyond {
    /// The value of the nearest face.
    Clamp,
    /// Zero.
    Zero,
}

/// Values on a regular lattice.
#[derive(Clone, Debug, PartialEq)]
pub struct Lattice {
    /// Lattice points per axis (x, y, z), each ≥ 2.
    pub dims: [usize; 3],
    /// Position of lattice point (0, 0, 0), m.
    pub origin: DVec3,
    /// Distance between neighbouring points per axis, m.
    pub spacing: DVec3,
    values: Vec<f64>,
}

/// Largest lattice accepted (points), so a corrupt header cannot ask for terabytes.
pub const MAX_LATTICE_POINTS: usize = 1 << 28;

impl Lattice {
    /// Checks dims (≥ 2 per axis, at most [`MAX_LATTICE_POINTS`] in all), a finite origin, finite
    /// positive spacing and one finite value per point.
    pub fn new(dims: [usize; 3], origin: DVec3, spacing: DVec3, values: Vec<f64>) -> Result<Lattice, String> {
        check_shape(dims, origin, spacing)?;
        let count = dims[0] * dims[1] * dims[2];
        if values.len() != count {
            return Err(format!(
                "{} values for a {}×{}×{} lattice ({count} points)",
                values.len(),
                dims[0],
                dims[1],
                dims[2]
            ));
        }
        if let Some(i) = values.iter().position(|v| !v.is_finite()) {
            return Err(format!("value #{i} is {}; values must be finite", values[i]));
        }
        Ok(Lattice { dims, origin, spacing, values })
    }

    /// Samples `f` at every lattice point.
    pub fn from_fn(
        dims: [usize; 3],
        origin: DVec3,
        spacing: DVec3,
        f: impl Fn(DVec3) -> f64,
    ) -> Result<Lattice, String> {
        check_shape(dims, origin, spacing)?;
        let mut values = Vec::with_capacity(dims[0] * dims[1] * dims[2]);
        for k in 0..dims[2] {
            for j in 0..dims[1] {
                for i in 0..dims[0] {
                    values.push(f(origin + spacing * DVec3::new(i as f64, j as f64, k as f64)));
                }
            }
        }
        Lattice::new(dims, origin, spacing, values)
    }

    /// The values, x fastest, then y, then z.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// The box spanned by the lattice points.
    pub fn bounds(&self) -> Aabb {
        let n = DVec3::new((self.dims[0] - 1) as f64, (self.dims[1] - 1) as f64, (self.dims[2] - 1) as f64);
        Aabb { min: self.origin, max: self.origin + self.spacing * n }
    }

    /// The smallest and largest lattice value (bounds of the trilinear interpolant; Catmull–Rom
    /// can overshoot them).
    pub fn value_range(&self) -> (f64, f64) {
        self.values.iter().fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| (lo.min(v), hi.max(v)))
    }

    /// The largest |difference| between neighbouring lattice values along any axis.
    pub fn max_step(&self) -> f64 {
        let [nx, ny, nz] = self.dims;
        let mut m = 0.0_f64;
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    let v = self.at(i, j, k);
                    if i + 1 < nx {
                        m = m.max((self.at(i + 1, j, k) - v).abs());
                    }
                    if j + 1 < ny {
                        m = m.max((self.at(i, j + 1, k) - v).abs());
                    }
                    if k + 1 < nz {
                        m = m.max((self.at(i, j, k + 1) - v).abs());
                    }
                }
            }
        }
        m
    }

    /// The values on the six faces of the lattice, as (min, max).
    pub fn face_range(&self) -> (f64, f64) {
        let [nx, ny, nz] = self.dims;
        let mut r = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..nz {
            for j in 0..ny {
                for i in 0..nx {
                    if i == 0 || j == 0 || k == 0 || i == nx - 1 || j == ny - 1 || k == nz - 1 {
                        let v = self.at(i, j, k);
                        r = (r.0.min(v), r.1.max(v));
                    }
                }
            }
        }
        r
    }

    fn at(&self, i: usize, j: usize, k: usize) -> f64 {
        self.values[i + self.dims[0] * (j + self.dims[1] * k)]
    }

    /// The value at signed lattice index (i, j, k), by the `beyond` rule.
    fn fetch(&self, idx: [i64; 3], beyond: Beyond) -> f64 {
        let mut u = [0usize; 3];
        for a in 0..3 {
            let n = self.dims[a] as i64;
            if idx[a] < 0 || idx[a] >= n {
                match beyond {
                    Beyond::Zero => return 0.0,
                    Beyond::Clamp => u[a] = idx[a].clamp(0, n - 1) as usize,
                }
            } else {
                u[a] = idx[a] as usize;
            }
        }
        self.at(u[0], u[1], u[2])
    }

    /// The interpolated value and its gradient at `p`.
    pub fn value_grad(&self, p: DVec3, interpolation: Interpolation, beyond: Beyond) -> (f64, DVec3) {
        let mut u = ((p - self.origin) / self.spacing).to_array();
        let mut live = [1.0; 3];
        if beyond == Beyond::Clamp {
            for a in 0..3 {
                let top = (self.dims[a] - 1) as f64;
                if !(0.0..=top).contains(&u[a]) {
                    live[a] = 0.0;
                    u[a] = u[a].clamp(0.0, top);
                }
            }
        }
        if u.iter().any(|v| !v.is_finite()) {
            return (f64::NAN, DVec3::splat(f64::NAN));
        }
        let (base, axis_weights) = match interpolation {
            Interpolation::Trilinear => stencil::<2>(u, self.dims, beyond, linear_weights),
            Interpolation::Tricubic => stencil::<4>(u, self.dims, beyond, catmull_rom_weights),
        };
        let (f, g) = match interpolation {
            Interpolation::Trilinear => self.accumulate::<2>(base, &axis_weights, beyond),
            Interpolation::Tricubic => self.accumulate::<4>(base, &axis_weights, beyond),
        };
        let inv = DVec3::from_array(live) / self.spacing;
        (f, g * inv)
    }

    /// Σ over the N³ stencil of w_x w_y w_z v, and the three derivative sums (per unit of u).
    fn accumulate<const N: usize>(&self, base: [i64; 3], w: &[[[f64; 4]; 2]; 3], beyond: Beyond) -> (f64, DVec3) {
        let (mut f, mut g) = (0.0, DVec3::ZERO);
        for k in 0..N {
            for j in 0..N {
                for i in 0..N {
                    let v = self.fetch([base[0] + i as i64, base[1] + j as i64, base[2] + k as i64], beyond);
                    if v == 0.0 {
                        continue;
                    }
                    let (wx, wy, wz) = (w[0][0][i], w[1][0][j], w[2][0][k]);
                    let (dx, dy, dz) = (w[0][1][i], w[1][1][j], w[2][1][k]);
                    f += wx * wy * wz * v;
                    g += DVec3::new(dx * wy * wz, wx * dy * wz, wx * wy * dz) * v;
                }
            }
        }
        (f, g)
    }
}

fn check_shape(dims: [usize; 3], origin: DVec3, spacing: DVec3) -> Result<(), String> {
    if dims.iter().any(|&n| n < 2) {
        return Err(format!("lattice dims {dims:?}: each axis needs at least 2 points"));
    }
    let count = dims.iter().try_fold(1usize, |acc, &n| acc.checked_mul(n));
    if count.is_none_or(|c| c > MAX_LATTICE_POINTS) {
        return Err(format!("lattice dims {dims:?}: more than {MAX_LATTICE_POINTS} points"));
    }
    if !origin.is_finite() {
        return Err(format!("lattice origin {origin} must be finite"));
    }
    if !(spacing.is_finite() && spacing.cmpgt(DVec3::ZERO).all()) {
        return Err(format!("lattice spacing {spacing} must be finite and positive on every axis"));
    }
    Ok(())
}

/// The first stencil index per axis and the weights [value, derivative][point] per axis.
fn stencil<const N: usize>(
    u: [f64; 3],
    dims: [usize; 3],
    beyond: Beyond,
    weights: fn(f64) -> [[f64; 4]; 2],
) -> ([i64; 3], [[[f64; 4]; 2]; 3]) {
    let mut base = [0i64; 3];
    let mut w = [[[0.0; 4]; 2]; 3];
    for a in 0..3 {
        let mut cell = u[a].floor();
        if beyond == Beyond::Clamp {
            // Keep the last face inside the last cell (t = 1) rather than starting a new one.
            cell = cell.min((dims[a] - 2) as f64);
        }
        let t = u[a] - cell;
        base[a] = cell as i64 - if N == 4 { 1 } else { 0 };
        w[a] = weights(t);
    }
    (base, w)
}

fn linear_weights(t: f64) -> [[f64; 4]; 2] {
    [[1.0 - t, t, 0.0, 0.0], [-1.0, 1.0, 0.0, 0.0]]
}

fn catmull_rom_weights(t: f64) -> [[f64; 4]; 2] {
    let (t2, t3) = (t * t, t * t * t);
    [
        [
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ],
        [
            0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
            0.5 * (9.0 * t2 - 10.0 * t),
            0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
            0.5 * (3.0 * t2 - 2.0 * t),
        ],
    ]
}

/// How far below the lowest lattice value the interpolant can go.
///
/// Per axis the negative Catmull–Rom weights sum to t(1 − t)/2 ≤ 1/8, so Σ|w| ≤ 5/4 and the
/// tensor product's negative weights sum to at most ((5/4)³ − 1)/2 < 0.48. The interpolant is then
/// at least the stencil's minimum minus 0.48 × the stencil's range, and a 4×4×4 stencil spans at
/// most 9 neighbour steps.
pub fn catmull_rom_overshoot(lattice: &Lattice, interpolation: Interpolation) -> f64 {
    match interpolation {
        Interpolation::Trilinear => 0.0,
        Interpolation::Tricubic => {
            let (lo, hi) = lattice.value_range();
            0.48 * (hi - lo).min(9.0 * lattice.max_step())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lattice(f: impl Fn(DVec3) -> f64) -> Lattice {
        Lattice::from_fn([5, 4, 6], DVec3::new(-1.0, 0.0, 2.0), DVec3::new(0.5, 1.0, 0.25), f).unwrap()
    }

    #[test]
    fn both_schemes_interpolate_lattice_values_and_trilinear_reproduces_linear_functions() {
        let lin = |p: DVec3| 2.0 + 0.3 * p.x - 1.5 * p.y + 4.0 * p.z;
        let l = lattice(lin);
        for p in [DVec3::new(-0.5, 1.0, 2.5), DVec3::new(0.2, 2.7, 3.1), DVec3::new(0.9, 0.1, 2.01)] {
            let (f, g) = l.value_grad(p, Interpolation::Trilinear, Beyond::Clamp);
            assert!((f - lin(p)).abs() < 1e-12, "f({p}) = {f}");
            assert!((g - DVec3::new(0.3, -1.5, 4.0)).length() < 1e-11, "∇f({p}) = {g}");
        }
        let wiggle = |p: DVec3| (3.0 * p.x).sin() + p.y * p.z;
        let l = lattice(wiggle);
        for interp in [Interpolation::Trilinear, Interpolation::Tricubic] {
            for (i, j, k) in [(0, 0, 0), (4, 3, 5), (2, 1, 3), (4, 0, 2)] {
                let p = l.origin + l.spacing * DVec3::new(i as f64, j as f64, k as f64);
                let (f, _) = l.value_grad(p, interp, Beyond::Clamp);
                assert!((f - wiggle(p)).abs() < 1e-12, "{interp:?}: f({p}) = {f} vs {}", wiggle(p));
            }
        }
    }

    #[test]
    fn catmull_rom_reproduces_quadratics_inside() {
        // The Catmull–Rom kernel has second-order accuracy: it is exact for quadratics in the
        // interior, where every stencil point is a lattice point.
        let q = |p: DVec3| p.x * p.x - 2.0 * p.y * p.y + p.x * p.z;
        let l = Lattice::from_fn([8, 8, 8], DVec3::ZERO, DVec3::splat(1.0), q).unwrap();
        let p = DVec3::new(3.3, 2.6, 4.1);
        let (f, g) = l.value_grad(p, Interpolation::Tricubic, Beyond::Clamp);
        assert!((f - q(p)).abs() < 1e-12, "{f} vs {}", q(p));
        let want = DVec3::new(2.0 * p.x + p.z, -4.0 * p.y, p.x);
        assert!((g - want).length() < 1e-12, "{g} vs {want}");
    }

    #[test]
    fn beyond_the_box_values_are_clamped_or_zero() {
        let l = lattice(|p| 1.0 + p.y);
        let (f, g) = l.value_grad(DVec3::new(-5.0, 10.0, 2.5), Interpolation::Trilinear, Beyond::Clamp);
        assert!((f - 4.0).abs() < 1e-12 && g == DVec3::ZERO, "{f} {g}");
        let (f, g) = l.value_grad(DVec3::new(-5.0, 1.0, 2.5), Interpolation::Tricubic, Beyond::Zero);
        assert_eq!((f, g), (0.0, DVec3::ZERO));
        assert!(l.value_grad(DVec3::NAN, Interpolation::Tricubic, Beyond::Clamp).0.is_nan());
    }

    #[test]
    fn rejects_bad_shapes_and_values() {
        let o = DVec3::ZERO;
        assert!(Lattice::new([1, 2, 2], o, DVec3::ONE, vec![0.0; 4]).unwrap_err().contains("at least 2"));
        assert!(Lattice::new([2, 2, 2], o, DVec3::new(1.0, 0.0, 1.0), vec![0.0; 8]).unwrap_err().contains("positive"));
        assert!(Lattice::new([2, 2, 2], o, DVec3::ONE, vec![0.0; 7]).unwrap_err().contains("7 values"));
        let mut v = vec![0.0; 8];
        v[3] = f64::INFINITY;
        assert!(Lattice::new([2, 2, 2], o, DVec3::ONE, v).unwrap_err().contains("#3"));
        assert!(Lattice::new([1 << 20, 1 << 20, 2], o, DVec3::ONE, vec![]).unwrap_err().contains("more than"));
    }
}
