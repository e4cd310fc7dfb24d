//! 3×3 matrices for colour transforms (row-major, acting on column vectors).

/// A 3×3 matrix, `m[row][column]`.
pub type Mat3 = [[f64; 3]; 3];

/// m · v.
pub fn mul_vec(m: &Mat3, v: [f64; 3]) -> [f64; 3] {
    [0, 1, 2].map(|r| m[r][0] * v[0] + m[r][1] * v[1] + m[r][2] * v[2])
}

/// a · b.
pub fn mul(a: &Mat3, b: &Mat3) -> Mat3 {
    [0, 1, 2].map(|r| [0, 1, 2].map(|c| a[r][0] * b[0][c] + a[r][1] * b[1][c] + a[r][2] * b[2][c]))
}

/// The diagonal matrix diag(d).
pub fn diagonal(d: [f64; 3]) -> Mat3 {
    [[d[0], 0.0, 0.0], [0.0, d[1], 0.0], [0.0, 0.0, d[2]]]
}

/// The inverse by cofactors, or `None` when |det m| is not positive and finite.
pub fn invert(m: &Mat3) -> Option<Mat3> {
    let c = |r: usize, k: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (k1, k2) = ((k + 1) % 3, (k + 2) % 3);
        m[r1][k1] * m[r2][k2] - m[r1][k2] * m[r2][k1]
    };
    let det = m[0][0] * c(0, 0) + m[0][1] * c(0, 1) + m[0][2] * c(0, 2);
    if !(det.is_finite() && det != 0.0) {
        return None;
    }
    Some([0, 1, 2].map(|r| [0, 1, 2].map(|k| c(k, r) / det)))
}

/// XYZ of chromaticity (x, y) with luminance Y = 1: (x/y, 1, (1 − x − y)/y).
pub fn xy_to_xyz(xy: [f64; 2]) -> [f64; 3] {
    [xy[0] / xy[1], 1.0, (1.0 - xy[0] - xy[1]) / xy[1]]
}

/// Chromaticity (x, y) = (X, Y)/(X + Y + Z); `None` for a zero or non-finite sum.
pub fn xyz_to_xy(xyz: [f64; 3]) -> Option<[f64; 2]> {
    let s = xyz[0] + xyz[1] + xyz[2];
    (s.is_finite() && s > 0.0).then(|| [xyz[0] / s, xyz[1] / s])
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inverse_times_matrix_is_the_identity() {
        let m = [[0.8951, 0.2664, -0.1614], [-0.7502, 1.7135, 0.0367], [0.0389, -0.0685, 1.0296]];
        let p = mul(&invert(&m).unwrap(), &m);
        for (r, row) in p.iter().enumerate() {
            for (c, v) in row.iter().enumerate() {
                assert!((v - f64::from(u8::from(r == c))).abs() < 1e-12, "{p:?}");
            }
        }
        assert!(invert(&[[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]]).is_none());
        assert_eq!(mul_vec(&diagonal([1.0, 2.0, 3.0]), [1.0, 1.0, 1.0]), [1.0, 2.0, 3.0]);
    }

    #[test]
    fn chromaticity_round_trips() {
        let xyz = xy_to_xyz([0.3127, 0.3290]);
        assert!((xyz[0] - 0.950_455).abs() < 1e-6 && (xyz[2] - 1.089_058).abs() < 1e-6, "{xyz:?}");
        let xy = xyz_to_xy(xyz).unwrap();
        assert!((xy[0] - 0.3127).abs() < 1e-15 && (xy[1] - 0.3290).abs() < 1e-15);
        assert!(xyz_to_xy([0.0; 3]).is_none());
    }
}
