//! Luminance and illuminance of a rectangle of pixels, for lighting studies, as CSV.
//!
//! A region x0,y0,x1,y1 holds the pixels x0 ≤ x < x1, y0 ≤ y < y1 (origin top left). The CSV
//! has one row per pixel: `x, y, luminance_cd_m2, scotopic_luminance_cd_m2,
//! illuminance_white_diffuser_lx`, the last being E = π L, the illuminance on a perfectly white
//! Lambertian surface that would show luminance L (for a surface of reflectance ρ it is π L / ρ).
//! Values are those of the input image, before any adaptation or tone mapping.
//!
//! [`RegionSummary`] adds the mean, minimum and maximum luminance and the illuminance the region
//! casts on the camera's pupil: a pinhole with vertical field of view φ on an image of height h
//! has focal length f = (h/2)/tan(φ/2) pixels; a pixel at (u, v) from the image centre subtends
//! dΩ = cos³θ / f² with cos θ = f/√(f² + u² + v²), so E_v = Σ L cos θ dΩ = Σ L cos⁴θ / f² (lx).

use super::scene_image::SceneImage;
use std::io::{self, Write};
use std::path::Path;

/// A pixel rectangle, end-exclusive.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Region {
    /// First column, pixels from the left.
    pub x0: usize,
    /// First row, pixels from the top.
    pub y0: usize,
    /// Column after the last.
    pub x1: usize,
    /// Row after the last.
    pub y1: usize,
}

/// Statistics of a region.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct RegionSummary {
    /// Number of pixels in the region.
    pub pixels: usize,
    /// Mean luminance, cd m⁻².
    pub mean_cd_m2: f64,
    /// Smallest luminance, cd m⁻².
    pub min_cd_m2: f64,
    /// Largest luminance, cd m⁻².
    pub max_cd_m2: f64,
    /// Illuminance on the camera from the region, lx.
    pub camera_illuminance_lx: f64,
}

impl Region {
    /// Parses "x0,y0,x1,y1" (non-negative integers with x0 < x1 and y0 < y1).
    pub fn parse(s: &str) -> Result<Region, String> {
        let v: Vec<Option<usize>> = s.split(',').map(|p| p.trim().parse().ok()).collect();
        match v.as_slice() {
            [Some(x0), Some(y0), Some(x1), Some(y1)] => Region::new(*x0, *y0, *x1, *y1),
            _ => Err(format!("\"{s}\" is not a region: give four pixel coordinates x0,y0,x1,y1 such as 10,20,50,40")),
        }
    }

    /// The rectangle x0 ≤ x < x1, y0 ≤ y < y1; empty rectangles are rejected.
    pub fn new(x0: usize, y0: usize, x1: usize, y1: usize) -> Result<Region, String> {
        if x0 < x1 && y0 < y1 {
            Ok(Region { x0, y0, x1, y1 })
        } else {
            Err(format!("region {x0},{y0},{x1},{y1} is empty: need x0 < x1 and y0 < y1 (x1, y1 exclusive)"))
        }
    }

    /// Checks the region lies inside a `width` × `height` image.
    pub fn check_inside(&self, width: usize, height: usize) -> Result<(), String> {
        if self.x1 <= width && self.y1 <= height {
            Ok(())
        } else {
            Err(format!(
                "region {},{},{},{} reaches outside the {width}×{height} image: x1 ≤ {width} and y1 ≤ {height} are needed",
                self.x0, self.y0, self.x1, self.y1
            ))
        }
    }

    fn pixels(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (self.y0..self.y1).flat_map(move |y| (self.x0..self.x1).map(move |x| (x, y)))
    }

    /// The region's statistics in `image` seen with vertical field of view `fov_deg`.
    pub fn summary(&self, image: &SceneImage, fov_deg: f64) -> RegionSummary {
        let (w, h) = (image.width as f64, image.height as f64);
        // The image plane at unit distance: a pixel is t wide (t = 1/f for a focal length of f
        // pixels), so tiny fields of view underflow to no illuminance instead of ∞/∞.
        let t = (0.5 * fov_deg.to_radians()).tan() / (0.5 * h);
        let mut s = RegionSummary {
            pixels: 0,
            mean_cd_m2: 0.0,
            min_cd_m2: f64::INFINITY,
            max_cd_m2: 0.0,
            camera_illuminance_lx: 0.0,
        };
        for (x, y) in self.pixels() {
            let l = image.luminance(y * image.width + x);
            let (u, v) = (x as f64 + 0.5 - 0.5 * w, y as f64 + 0.5 - 0.5 * h);
            let cos2 = 1.0 / (1.0 + t * t * (u * u + v * v));
            s.pixels += 1;
            s.mean_cd_m2 += l;
            s.min_cd_m2 = s.min_cd_m2.min(l);
            s.max_cd_m2 = s.max_cd_m2.max(l);
            // E = Σ L cos θ dω with dω = cos³θ t² (Nicodemus 1963).
            s.camera_illuminance_lx += l * cos2 * cos2 * t * t;
        }
        s.mean_cd_m2 /= s.pixels.max(1) as f64;
        s
    }

    /// Writes the per-pixel CSV of `image` to `path` (not atomically: callers stage the file).
    pub fn write_csv(&self, image: &SceneImage, path: &Path) -> io::Result<()> {
        let mut f = io::BufWriter::new(std::fs::File::create(path)?);
        writeln!(f, "x,y,luminance_cd_m2,scotopic_luminance_cd_m2,illuminance_white_diffuser_lx")?;
        for (x, y) in self.pixels() {
            let i = y * image.width + x;
            let l = image.luminance(i);
            writeln!(f, "{x},{y},{l:e},{:e},{:e}", image.scotopic[i], std::f64::consts::PI * l)?;
        }
        f.flush()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn uniform(w: usize, h: usize, l: f64) -> SceneImage {
        SceneImage::from_xyz(w, h, vec![[l, l, l]; w * h]).unwrap()
    }

    #[test]
    fn parses_and_checks_regions() {
        assert_eq!(Region::parse("1, 2,3,4").unwrap(), Region { x0: 1, y0: 2, x1: 3, y1: 4 });
        assert!(Region::parse("1,2,3").unwrap_err().contains("x0,y0,x1,y1"));
        assert!(Region::parse("3,2,3,4").unwrap_err().contains("empty"));
        assert!(Region::parse("-1,0,2,2").is_err());
        let r = Region::parse("0,0,10,5").unwrap();
        assert!(r.check_inside(10, 5).is_ok());
        assert!(r.check_inside(9, 5).unwrap_err().contains("9×5"));
    }

    #[test]
    fn camera_illuminance_is_the_integral_of_l_cos_theta() {
        // The centre pixel of an odd image: E = L / f² (θ = 0 at its centre).
        let img = uniform(101, 101, 7.0);
        let fov = 30.0;
        let f = 50.5 / (15f64).to_radians().tan();
        let centre = Region::new(50, 50, 51, 51).unwrap().summary(&img, fov);
        assert!((centre.camera_illuminance_lx - 7.0 / (f * f)).abs() < 1e-15);
        // The whole image against the solid-angle integral of L cos θ over the image rectangle,
        // ∫∫ L f² / (f² + u² + v²)² du dv, by fine quadrature.
        let whole = Region::new(0, 0, 101, 101).unwrap().summary(&img, fov);
        let n = 2020;
        let d = 101.0 / n as f64;
        let mut want = 0.0;
        for i in 0..n {
            for j in 0..n {
                let (u, v) = (-50.5 + (i as f64 + 0.5) * d, -50.5 + (j as f64 + 0.5) * d);
                want += 7.0 * f * f / (f * f + u * u + v * v).powi(2) * d * d;
            }
        }
        assert!((whole.camera_illuminance_lx / want - 1.0).abs() < 1e-4, "{} vs {want}", whole.camera_illuminance_lx);
        assert_eq!((whole.pixels, whole.mean_cd_m2, whole.min_cd_m2, whole.max_cd_m2), (10201, 7.0, 7.0, 7.0));
    }

    #[test]
    fn extreme_fields_of_view_give_finite_illuminance() {
        // The fuzzer's `tonemap --fov-deg 1e-300` printed NaN lx (f² overflowed, ∞/∞). The
        // illuminance of a uniform L over a tiny field is L times its solid angle, ≈ L·(w·h)·t².
        let img = uniform(4, 4, 3.0);
        let whole = Region::new(0, 0, 4, 4).unwrap();
        assert_eq!(whole.summary(&img, 1e-300).camera_illuminance_lx, 0.0);
        let fov = 1e-6f64;
        let t = (0.5 * fov).to_radians().tan() / 2.0;
        let e = whole.summary(&img, fov).camera_illuminance_lx;
        assert!((e / (3.0 * 16.0 * t * t) - 1.0).abs() < 1e-9, "{e}");
        let wide = whole.summary(&img, 179.999_999).camera_illuminance_lx;
        assert!(wide.is_finite() && wide > 0.0 && wide < std::f64::consts::PI * 3.0, "{wide}");
    }

    #[test]
    fn writes_one_row_per_pixel() {
        let img = uniform(4, 3, 2.0);
        let path = std::env::temp_dir().join(format!("morgana-region-{}.csv", std::process::id()));
        Region::new(1, 1, 3, 2).unwrap().write_csv(&img, &path).unwrap();
        let text = std::fs::read_to_string(&path).unwrap();
        std::fs::remove_file(&path).unwrap();
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 3);
        assert!(lines[0].starts_with("x,y,luminance_cd_m2"));
        let cols: Vec<f64> = lines[1].split(',').map(|c| c.parse().unwrap()).collect();
        assert_eq!(&cols[..3], &[1.0, 1.0, 2.0]);
        assert!((cols[4] - 2.0 * std::f64::consts::PI).abs() < 1e-12);
    }
}
