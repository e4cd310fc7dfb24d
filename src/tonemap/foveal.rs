//! The foveal image: luminance averaged over patches about 1° across, the area the fovea sees
//! at once and the unit of local adaptation in Ward Larson et al. (1997, §3.1).
//!
//! For a pinhole camera with vertical field of view φ, the image plane spans 2 tan(φ/2) (in units
//! of the focal length) vertically; the foveal image has n_y = round(2 tan(φ/2) / (π/180))
//! rows (1° ≈ π/180 of the focal length near the centre), at least 2 and at most the pixel rows,
//! and n_x = round(n_y · width/height) columns, likewise bounded. Each foveal sample is the mean
//! photopic luminance of the pixels whose centres fall in its block (a box filter). Values
//! between sample centres are interpolated bilinearly.
//!
//! # References
//! - G. Ward Larson, H. Rushmeier, C. Piatko (1997), IEEE TVCG 3(4), 291–306, §3.1.

use super::scene_image::SceneImage;

/// Mean luminance over ~1° blocks.
#[derive(Clone, Debug)]
pub struct FovealImage {
    /// Columns of blocks.
    pub nx: usize,
    /// Rows of blocks.
    pub ny: usize,
    /// Row-major mean luminance per block, cd m⁻².
    pub luminance: Vec<f64>,
}

impl FovealImage {
    /// The foveal image of `image` seen with vertical field of view `fov_deg`.
    pub fn new(image: &SceneImage, fov_deg: f64) -> FovealImage {
        let (w, h) = (image.width, image.height);
        let span = 2.0 * (0.5 * fov_deg.clamp(1e-3, 179.0)).to_radians().tan();
        let ny = ((span / 1f64.to_radians()).round() as usize).clamp(2.min(h), h);
        let nx = ((ny as f64 * w as f64 / h as f64).round() as usize).clamp(2.min(w), w);
        let mut sum = vec![0.0; nx * ny];
        let mut count = vec![0usize; nx * ny];
        for y in 0..h {
            for x in 0..w {
                let b = (y * ny / h) * nx + x * nx / w;
                sum[b] += image.luminance(y * w + x);
                count[b] += 1;
            }
        }
        let luminance = sum.iter().zip(&count).map(|(s, &c)| if c > 0 { s / c as f64 } else { 0.0 }).collect();
        FovealImage { nx, ny, luminance }
    }

    /// The local adaptation luminance at pixel (x, y) of a `w` × `h` image: bilinear between the
    /// foveal sample centres, clamped at the borders.
    pub fn at_pixel(&self, x: usize, y: usize, w: usize, h: usize) -> f64 {
        let fx = ((x as f64 + 0.5) * self.nx as f64 / w as f64 - 0.5).clamp(0.0, (self.nx - 1) as f64);
        let fy = ((y as f64 + 0.5) * self.ny as f64 / h as f64 - 0.5).clamp(0.0, (self.ny - 1) as f64);
        let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.nx - 1), (y0 + 1).min(self.ny - 1));
        let (tx, ty) = (fx - x0 as f64, fy - y0 as f64);
        let v = |i: usize, j: usize| self.luminance[j * self.nx + i];
        let top = (1.0 - tx) * v(x0, y0) + tx * v(x1, y0);
        let bottom = (1.0 - tx) * v(x0, y1) + tx * v(x1, y1);
        (1.0 - ty) * top + ty * bottom
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn split(w: usize, h: usize) -> SceneImage {
        let xyz = (0..w * h).map(|i| if i % w < w / 2 { [0.0; 3] } else { [0.0, 4.0, 0.0] }).collect();
        SceneImage::from_xyz(w, h, xyz).unwrap()
    }

    #[test]
    fn blocks_are_about_one_degree_and_hold_means() {
        // 40° vertical field: 2 tan 20° / (π/180) = 41.7 → 42 rows; a 2:1 image has 84 columns.
        let img = SceneImage::from_xyz(400, 200, vec![[0.0, 2.0, 0.0]; 80_000]).unwrap();
        let f = FovealImage::new(&img, 40.0);
        assert_eq!((f.nx, f.ny), (84, 42));
        assert!(f.luminance.iter().all(|&l| (l - 2.0).abs() < 1e-12));
    }

    #[test]
    fn small_images_and_narrow_fields_are_bounded_and_interpolated() {
        // A tiny image keeps at most one sample per pixel.
        let f = FovealImage::new(&split(4, 2), 90.0);
        assert_eq!((f.nx, f.ny), (4, 2));
        assert_eq!((f.at_pixel(0, 0, 4, 2), f.at_pixel(3, 1, 4, 2)), (0.0, 4.0));
        // A narrow field gives 2 × 2 blocks of 4 × 4 pixels; between centres it interpolates.
        let f = FovealImage::new(&split(8, 8), 1.0);
        assert_eq!((f.nx, f.ny), (2, 2));
        assert_eq!(f.luminance, vec![0.0, 4.0, 0.0, 4.0]);
        assert_eq!(f.at_pixel(3, 0, 8, 8), 1.5);
        assert_eq!(f.at_pixel(0, 0, 8, 8), 0.0);
    }
}
