//! Loss of visual acuity in dim light.
//!
//! The highest spatial frequency the eye resolves at adaptation luminance L_a (cd m⁻²) is
//! ω(L_a) = 17.25 arctan(1.4 log₁₀ L_a + 0.35) + 25.72 cycles per degree, Ward Larson et al.'s
//! (1997, Eq. 11) fit to Shlaer's (1937) acuity data, which Ferwerda et al. (1996, §6) also use:
//! about 50 c/deg in daylight, 11 c/deg at 0.1 cd m⁻², 3 c/deg at 10⁻³·¹ cd m⁻², the dimmest
//! level measured. Below it the fit is held at that value (it would fall to zero near
//! 10⁻⁹ cd m⁻², far beyond the data), so a black patch in a lit scene is not smeared over the
//! whole image.
//!
//! The image is blurred so that detail beyond ω is lost: each pixel is blurred with a Gaussian
//! whose modulation transfer exp(−2π²σ²f²) falls to ½ at f = ω, i.e. σ = √(ln 2 / 2) / (π ω)
//! degrees, with ω from the pixel's local adaptation luminance (the 1° foveal image,
//! [`super::foveal`]). A pixel already averages over its own width (a box of variance 1/12
//! pixel²), so the blur added has variance σ²/p² − 1/12 (p the pixel size in degrees), and none
//! when that is negative. As in Ward Larson et al.'s pyramid, the image is filtered at a few fixed
//! widths ([`super::blur`]) and each pixel interpolates linearly, in variance, between the two
//! levels that bracket its own.
//!
//! # References
//! - G. Ward Larson, H. Rushmeier, C. Piatko (1997), IEEE TVCG 3(4), 291–306, §5.2.
//! - S. Shlaer (1937), "The relation between visual acuity and illumination", Journal of General
//!   Physiology 21(2), 165–188.
//! - J. A. Ferwerda, S. N. Pattanaik, P. Shirley, D. P. Greenberg (1996), SIGGRAPH '96, 249–258.

use super::blur::{BLUR_LEVELS, blur_level, level_sigma_px};
use super::foveal::FovealImage;
use super::scene_image::SceneImage;

/// The dimmest adaptation luminance of Shlaer's data, log₁₀ cd m⁻².
pub const DIMMEST_MEASURED_LOG10_CD_M2: f64 = -3.1;

/// Resolvable spatial frequency, cycles per degree, at adaptation luminance `la_cd_m2`.
pub fn acuity_cycles_per_degree(la_cd_m2: f64) -> f64 {
    let l = if la_cd_m2 > 0.0 { la_cd_m2.log10() } else { f64::NEG_INFINITY };
    let l = l.max(DIMMEST_MEASURED_LOG10_CD_M2);
    17.25 * (1.4 * l + 0.35).atan() + 25.72
}

/// The blur σ in degrees for adaptation luminance `la_cd_m2` (see the module documentation).
pub fn blur_sigma_deg(la_cd_m2: f64) -> f64 {
    (std::f64::consts::LN_2 / 2.0).sqrt() / (std::f64::consts::PI * acuity_cycles_per_degree(la_cd_m2))
}

/// Blurs `image` (XYZ and scotopic luminance) for the acuity at each pixel's local adaptation;
/// `deg_per_pixel` is the angular size of a pixel. Returns the largest σ added, in pixels.
pub fn apply_acuity(image: &mut SceneImage, foveal: &FovealImage, deg_per_pixel: f64) -> f64 {
    let (w, h) = (image.width, image.height);
    let max_var = level_sigma_px(BLUR_LEVELS - 1).powi(2);
    let variance: Vec<f64> = (0..w * h)
        .map(|i| (blur_sigma_deg(foveal.at_pixel(i % w, i / w, w, h)) / deg_per_pixel).powi(2) - 1.0 / 12.0)
        .map(|v| v.clamp(0.0, max_var))
        .collect();
    let max_variance = variance.iter().copied().fold(0.0, f64::max);
    let channels = channels_of(image);
    let mut result = channels.clone();
    let mut lower = channels.clone();
    for level in 1..BLUR_LEVELS {
        let (v0, v1) = (level_sigma_px(level - 1).powi(2), level_sigma_px(level).powi(2));
        if v0 >= max_variance {
            break;
        }
        let upper: Vec<Vec<f64>> = channels.iter().map(|c| blur_level(c, w, h, level)).collect();
        for (i, &v) in variance.iter().enumerate() {
            if v > v0 && v <= v1 {
                let t = (v - v0) / (v1 - v0);
                for (r, (lo, hi)) in result.iter_mut().zip(lower.iter().zip(&upper)) {
                    r[i] = (1.0 - t) * lo[i] + t * hi[i];
                }
            }
        }
        lower = upper;
    }
    store_channels(image, &result);
    max_variance.sqrt()
}

fn channels_of(image: &SceneImage) -> Vec<Vec<f64>> {
    let mut c: Vec<Vec<f64>> = (0..3).map(|k| image.xyz.iter().map(|p| p[k]).collect()).collect();
    c.push(image.scotopic.clone());
    c
}

fn store_channels(image: &mut SceneImage, c: &[Vec<f64>]) {
    for (i, p) in image.xyz.iter_mut().enumerate() {
        *p = [c[0][i], c[1][i], c[2][i]];
    }
    image.scotopic.clone_from(&c[3]);
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn follows_shlaers_data() {
        // Shlaer (1937) as tabulated for Ward Larson et al.: (log₁₀ L_a, c/deg).
        for (l, want) in [(-3.105, 2.09), (-1.074, 10.94), (0.294, 37.42), (1.828, 47.0), (3.249, 51.09)] {
            let got = acuity_cycles_per_degree(10f64.powf(l));
            assert!((got - want).abs() < 0.06 * want + 0.8, "1e{l}: {got} vs {want}");
        }
        assert_eq!(acuity_cycles_per_degree(0.0), acuity_cycles_per_degree(10f64.powf(-3.1)));
        // σ at 50 c/deg is 0.0037°; at 1 c/deg 0.187°.
        assert!((blur_sigma_deg(10f64.powf(1.2)) - 0.1874 / acuity_cycles_per_degree(10f64.powf(1.2))).abs() < 1e-4);
    }

    #[test]
    fn dim_scenes_lose_detail_and_bright_ones_keep_it() {
        // A 64×64 checkerboard of 1-pixel squares, 0.04°/pixel (12.5 c/deg).
        let checker = |scale: f64| {
            let xyz = (0..64 * 64).map(|i| if (i % 64 + i / 64) % 2 == 0 { [scale; 3] } else { [0.0; 3] }).collect();
            SceneImage::from_xyz(64, 64, xyz).unwrap()
        };
        let contrast = |img: &SceneImage| {
            let y = img.luminances();
            let (lo, hi) = y.iter().fold((f64::INFINITY, 0.0f64), |(a, b), &v| (a.min(v), b.max(v)));
            (hi - lo) / (hi + lo)
        };
        for (scale, keeps) in [(1000.0, true), (0.001, false)] {
            let mut img = checker(scale);
            let fov = FovealImage::new(&img, 3.2);
            apply_acuity(&mut img, &fov, 0.04);
            let c = contrast(&img);
            assert!(if keeps { c > 0.99 } else { c < 0.2 }, "scale {scale}: contrast {c}");
            // Blurring keeps the mean away from the clamped borders.
            let y = img.luminances();
            let mean: f64 =
                (16..48).flat_map(|r| (16..48).map(move |c| (r, c))).map(|(r, c)| y[r * 64 + c]).sum::<f64>();
            assert!((mean / 1024.0 / (0.5 * scale) - 1.0).abs() < 1e-9, "{mean}");
        }
    }
}
