//! A density sampled on a regular 3-D lattice over a box, trilinearly interpolated; zero
//! outside the box.
//!
//! # File format (`.mgrid`)
//! An ASCII header of four lines, then the samples:
//! ```text
//! MORGANA-GRID 1
//! nx ny nz                  (each ≥ 2: lattice points per axis)
//! min_x min_y min_z         (box corner, m)
//! max_x max_y max_z         (opposite corner, m)
//! <nx·ny·nz little-endian f32 values, x varying fastest, then y, then z>
//! ```
//! Values must be finite and ≥ 0. [`Grid3D::write`] writes this format; `morgana grid` makes
//! one from procedural fBm noise.
//!
//! Majorants come from a coarse grid of macro-cells (each the maximum of the lattice values
//! it touches), traversed along a ray with the 3-D DDA of Amanatides & Woo 1987.

use glam::DVec3;
use std::io::{BufRead, Read, Write};
use std::path::Path;

/// First line of an `.mgrid` file.
pub const GRID_MAGIC: &str = "MORGANA-GRID 1";

/// Lattice cells per macro-cell side.
const MACRO: usize = 8;

/// A density on a regular lattice over [`min`, `max`], trilinear inside, zero outside.
#[derive(Clone, Debug)]
pub struct Grid3D {
    /// Lattice points per axis (x, y, z), each ≥ 2.
    pub n: [usize; 3],
    /// Lower corner of the box, m.
    pub min: DVec3,
    /// Upper corner of the box, m.
    pub max: DVec3,
    values: Vec<f32>,
    macro_n: [usize; 3],
    macro_max: Vec<f32>,
}

impl Grid3D {
    /// Builds a grid from lattice values (x fastest); checks sizes and values.
    pub fn new(n: [usize; 3], min: DVec3, max: DVec3, values: Vec<f32>) -> Result<Grid3D, String> {
        if n.iter().any(|&k| k < 2) {
            return Err(format!("grid size {n:?}: each axis needs at least 2 lattice points"));
        }
        if !(min.is_finite() && max.is_finite() && max.cmpgt(min).all()) {
            return Err(format!("grid box {min} – {max}: max must exceed min on every axis"));
        }
        let count = n[0].checked_mul(n[1]).and_then(|v| v.checked_mul(n[2])).ok_or("grid size overflows")?;
        if values.len() != count {
            return Err(format!(
                "grid has {} values but {}×{}×{} = {count} are needed",
                values.len(),
                n[0],
                n[1],
                n[2]
            ));
        }
        if let Some(i) = values.iter().position(|v| !(v.is_finite() && *v >= 0.0)) {
            return Err(format!("grid value #{i} is {}; values must be finite and ≥ 0", values[i]));
        }
        let macro_n = n.map(|k| (k - 1).div_ceil(MACRO));
        let mut g = Grid3D { n, min, max, values, macro_n, macro_max: Vec::new() };
        g.macro_max = g.build_macro();
        Ok(g)
    }

    /// Samples `f` at every lattice point of an `n`-point grid over [min, max].
    pub fn from_fn(n: [usize; 3], min: DVec3, max: DVec3, f: impl Fn(DVec3) -> f64) -> Result<Grid3D, String> {
        if n.iter().any(|&k| k < 2) {
            return Err(format!("grid size {n:?}: each axis needs at least 2 lattice points"));
        }
        let mut values = Vec::with_capacity(n[0] * n[1] * n[2]);
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    let t = DVec3::new(
                        i as f64 / (n[0] - 1) as f64,
                        j as f64 / (n[1] - 1) as f64,
                        k as f64 / (n[2] - 1) as f64,
                    );
                    values.push(f(min + (max - min) * t) as f32);
                }
            }
        }
        Grid3D::new(n, min, max, values)
    }

    fn value(&self, i: usize, j: usize, k: usize) -> f32 {
        self.values[(k * self.n[1] + j) * self.n[0] + i]
    }

    fn build_macro(&self) -> Vec<f32> {
        let [mx, my, mz] = self.macro_n;
        let mut out = vec![0f32; mx * my * mz];
        for (c, o) in out.iter_mut().enumerate() {
            let (ci, cj, ck) = (c % mx, (c / mx) % my, c / (mx * my));
            let range = |c: usize, n: usize| (c * MACRO)..=((c + 1) * MACRO).min(n - 1);
            for k in range(ck, self.n[2]) {
                for j in range(cj, self.n[1]) {
                    for i in range(ci, self.n[0]) {
                        *o = o.max(self.value(i, j, k));
                    }
                }
            }
        }
        out
    }

    /// Continuous lattice coordinates of `p` (lattice point i at coordinate i).
    fn lattice(&self, p: DVec3) -> DVec3 {
        let cells = DVec3::new((self.n[0] - 1) as f64, (self.n[1] - 1) as f64, (self.n[2] - 1) as f64);
        (p - self.min) / (self.max - self.min) * cells
    }

    /// Trilinear interpolation; zero outside the box.
    pub fn at(&self, p: DVec3) -> f64 {
        let q = self.lattice(p);
        let hi = [self.n[0] - 1, self.n[1] - 1, self.n[2] - 1];
        if q.x < 0.0 || q.y < 0.0 || q.z < 0.0 || q.x > hi[0] as f64 || q.y > hi[1] as f64 || q.z > hi[2] as f64 {
            return 0.0;
        }
        let i = [(q.x as usize).min(hi[0] - 1), (q.y as usize).min(hi[1] - 1), (q.z as usize).min(hi[2] - 1)];
        let f = [q.x - i[0] as f64, q.y - i[1] as f64, q.z - i[2] as f64];
        let mut v = 0.0;
        for (dk, wk) in [(0, 1.0 - f[2]), (1, f[2])] {
            for (dj, wj) in [(0, 1.0 - f[1]), (1, f[1])] {
                for (di, wi) in [(0, 1.0 - f[0]), (1, f[0])] {
                    v += wi * wj * wk * self.value(i[0] + di, i[1] + dj, i[2] + dk) as f64;
                }
            }
        }
        v
    }

    /// The largest lattice value (0 for an empty grid).
    pub fn max_value(&self) -> f64 {
        self.macro_max.iter().fold(0.0f64, |m, v| m.max(f64::from(*v)))
    }

    /// Intervals of [0, t_max] by macro-cell, each with that cell's maximum.
    pub fn majorant_intervals(&self, o: DVec3, dir: DVec3, t_max: f64, visit: &mut dyn FnMut(f64, f64, f64) -> bool) {
        let Some((t_in, t_out)) = self.clip(o, dir, t_max) else {
            visit(0.0, t_max, 0.0);
            return;
        };
        if t_in > 0.0 && !visit(0.0, t_in, 0.0) {
            return;
        }
        let cell_size =
            (self.max - self.min) / DVec3::new(self.macro_n[0] as f64, self.macro_n[1] as f64, self.macro_n[2] as f64);
        let p = o + dir * (0.5 * (t_in + t_out.min(t_in + cell_size.min_element())));
        let mut c = [0usize; 3];
        let (mut t_next, mut dt, mut step) = ([0.0; 3], [0.0; 3], [0i64; 3]);
        for a in 0..3 {
            let rel = (p[a] - self.min[a]) / cell_size[a];
            c[a] = (rel.max(0.0) as usize).min(self.macro_n[a] - 1);
            if dir[a] > 0.0 {
                step[a] = 1;
                t_next[a] = (self.min[a] + (c[a] + 1) as f64 * cell_size[a] - o[a]) / dir[a];
                dt[a] = cell_size[a] / dir[a];
            } else if dir[a] < 0.0 {
                step[a] = -1;
                t_next[a] = (self.min[a] + c[a] as f64 * cell_size[a] - o[a]) / dir[a];
                dt[a] = -cell_size[a] / dir[a];
            } else {
                t_next[a] = f64::INFINITY;
                dt[a] = f64::INFINITY;
            }
        }
        let mut t = t_in;
        loop {
            let a = (0..3).min_by(|&x, &y| t_next[x].total_cmp(&t_next[y])).unwrap_or(0);
            let t1 = t_next[a].min(t_out);
            let m = self.macro_max[(c[2] * self.macro_n[1] + c[1]) * self.macro_n[0] + c[0]] as f64;
            if t1 > t && !visit(t, t1, m) {
                return;
            }
            t = t1;
            if t >= t_out {
                break;
            }
            let next = c[a] as i64 + step[a];
            if next < 0 || next >= self.macro_n[a] as i64 {
                break;
            }
            c[a] = next as usize;
            t_next[a] += dt[a];
        }
        if t_out < t_max {
            visit(t_out, t_max, 0.0);
        }
    }

    /// The part of [0, t_max] inside the box (slab test).
    fn clip(&self, o: DVec3, dir: DVec3, t_max: f64) -> Option<(f64, f64)> {
        let (mut t0, mut t1) = (0.0f64, t_max);
        for a in 0..3 {
            if dir[a] == 0.0 {
                if o[a] < self.min[a] || o[a] > self.max[a] {
                    return None;
                }
                continue;
            }
            let (mut ta, mut tb) = ((self.min[a] - o[a]) / dir[a], (self.max[a] - o[a]) / dir[a]);
            if ta > tb {
                std::mem::swap(&mut ta, &mut tb);
            }
            t0 = t0.max(ta);
            t1 = t1.min(tb);
        }
        (t0 < t1).then_some((t0, t1))
    }

    /// Writes the grid in the `.mgrid` format.
    pub fn write(&self, path: &Path) -> std::io::Result<()> {
        let mut f = std::io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(f, "{GRID_MAGIC}")?;
        writeln!(f, "{} {} {}", self.n[0], self.n[1], self.n[2])?;
        writeln!(f, "{} {} {}", self.min.x, self.min.y, self.min.z)?;
        writeln!(f, "{} {} {}", self.max.x, self.max.y, self.max.z)?;
        for v in &self.values {
            f.write_all(&v.to_le_bytes())?;
        }
        f.flush()
    }

    /// Reads a `.mgrid` file; errors name the line (header) or the problem (data).
    pub fn read(path: &Path) -> Result<Grid3D, (Option<usize>, String)> {
        let file = std::fs::File::open(path).map_err(|e| (None, format!("cannot open grid file: {e}")))?;
        let mut r = std::io::BufReader::new(file);
        let mut line = |no: usize| -> Result<String, (Option<usize>, String)> {
            let mut s = String::new();
            r.read_line(&mut s).map_err(|e| (Some(no), format!("cannot read header: {e}")))?;
            Ok(s.trim().to_string())
        };
        let magic = line(1)?;
        if magic != GRID_MAGIC {
            return Err((Some(1), format!("expected \"{GRID_MAGIC}\", found \"{magic}\"")));
        }
        let nums = |s: String, no: usize, what: &str| -> Result<Vec<f64>, (Option<usize>, String)> {
            let v: Option<Vec<f64>> = s.split_whitespace().map(|x| x.parse().ok()).collect();
            v.filter(|v| v.len() == 3).ok_or((Some(no), format!("expected three numbers ({what}), found \"{s}\"")))
        };
        let n = nums(line(2)?, 2, "nx ny nz")?;
        if n.iter().any(|x| x.fract() != 0.0 || *x < 2.0 || *x > 4096.0) {
            return Err((Some(2), format!("lattice sizes {n:?} must be integers from 2 to 4096")));
        }
        let n = [n[0] as usize, n[1] as usize, n[2] as usize];
        let min = nums(line(3)?, 3, "min corner")?;
        let max = nums(line(4)?, 4, "max corner")?;
        let count = n[0] * n[1] * n[2];
        let mut bytes = Vec::new();
        r.read_to_end(&mut bytes).map_err(|e| (None, format!("cannot read grid data: {e}")))?;
        if bytes.len() != 4 * count {
            return Err((
                None,
                format!("grid data holds {} bytes but {count} f32 values need {}", bytes.len(), 4 * count),
            ));
        }
        let values = bytes.chunks_exact(4).map(|c| f32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect();
        Grid3D::new(n, DVec3::from_slice(&min), DVec3::from_slice(&max), values).map_err(|e| (None, e))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp() -> Grid3D {
        // d = x + 2y + 3z sampled on a 17×9×5 lattice over [0,1]×[0,2]×[0,3]: trilinear
        // interpolation reproduces a linear function exactly.
        let n = [17, 9, 5];
        let (min, max) = (DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0));
        let mut v = Vec::new();
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    let p = min + (max - min) * DVec3::new(i as f64 / 16.0, j as f64 / 8.0, k as f64 / 4.0);
                    v.push((p.x + 2.0 * p.y + 3.0 * p.z) as f32);
                }
            }
        }
        Grid3D::new(n, min, max, v).unwrap()
    }

    #[test]
    fn trilinear_reproduces_linear_functions_and_is_zero_outside() {
        let g = ramp();
        for p in [DVec3::new(0.3, 1.1, 2.7), DVec3::new(0.999, 0.01, 0.5), DVec3::ZERO, DVec3::new(1.0, 2.0, 3.0)] {
            assert!((g.at(p) - (p.x + 2.0 * p.y + 3.0 * p.z)).abs() < 1e-5, "{p}");
        }
        assert_eq!(g.at(DVec3::new(-0.01, 1.0, 1.0)), 0.0);
        assert_eq!(g.at(DVec3::new(0.5, 1.0, 3.01)), 0.0);
    }

    #[test]
    fn majorant_intervals_cover_the_ray_and_bound_the_density() {
        let g = ramp();
        let o = DVec3::new(-0.5, -0.3, -0.2);
        let dir = DVec3::new(0.5, 0.9, 1.3).normalize();
        let mut last = 0.0;
        let mut ok = true;
        g.majorant_intervals(o, dir, 10.0, &mut |t0, t1, m| {
            ok &= (t0 - last).abs() < 1e-12 && t1 >= t0;
            // Interior points: on an interval's end the density may belong to the neighbour.
            for s in 0..20 {
                let t = t0 + (t1 - t0) * (s as f64 + 0.5) / 20.0;
                ok &= g.at(o + t * dir) <= m + 1e-6;
            }
            last = t1;
            true
        });
        assert!(ok && (last - 10.0).abs() < 1e-12);
    }

    #[test]
    fn file_round_trip_and_errors() {
        let g = ramp();
        let dir = std::env::temp_dir().join(format!("morgana-grid-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let p = dir.join("ramp.mgrid");
        g.write(&p).unwrap();
        let h = Grid3D::read(&p).unwrap();
        assert_eq!((h.n, h.values.len()), (g.n, g.values.len()));
        assert!((h.at(DVec3::new(0.3, 1.1, 2.7)) - g.at(DVec3::new(0.3, 1.1, 2.7))).abs() < 1e-12);
        std::fs::write(&p, "MORGANA-GRID 1\n2 2 x\n").unwrap();
        assert_eq!(Grid3D::read(&p).unwrap_err().0, Some(2));
        std::fs::write(&p, "MORGANA-GRID 1\n2 2 2\n0 0 0\n1 1 1\nabc").unwrap();
        assert!(Grid3D::read(&p).unwrap_err().1.contains("32"));
        let _ = std::fs::remove_dir_all(&dir);
    }
}
