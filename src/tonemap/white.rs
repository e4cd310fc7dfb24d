//! The scene white that chromatic adaptation starts from: given, or estimated from the image.
//!
//! - [`AdaptTo::None`]: no chromatic adaptation.
//! - [`AdaptTo::Chromaticity`]: a given (x, y), e.g. the water colour a diver adapts to; `d65`
//!   is (0.3127, 0.3290), the display white, so it adapts nothing.
//! - [`AdaptTo::Illuminant`]: a CIE illuminant by name (`A`, `E`), its white from the CIE
//!   tables (relative XYZ of the perfect reflector, as `colour.sd_to_XYZ` computes it).
//! - [`AdaptTo::SceneAverage`]: "grey world" (Buchsbaum 1980): the white is the mean XYZ of all
//!   pixels, i.e. the scene is assumed to average to grey. Suits scenes bathed in one coloured
//!   light, such as underwater views.
//! - [`AdaptTo::WhitePatch`]: "white patch" / max-RGB retinex (Land & McCann 1971): the white is
//!   the mean XYZ of the brightest 1 % of pixels (by luminance; at least one pixel), i.e. the
//!   brightest things are assumed white or the light itself.
//!
//! Every white is returned with Y = 1.
//!
//! # References
//! - G. Buchsbaum (1980), "A spatial processor model for object colour perception", Journal of
//!   the Franklin Institute 310(1), 1–26.
//! - E. H. Land, J. J. McCann (1971), "Lightness and Retinex Theory", JOSA 61(1), 1–11.

use super::matrix::xy_to_xyz;
use super::scene_image::SceneImage;
use crate::spectrum::colour::relative_xyz;
use crate::spectrum::{Spectrum, named_illuminant};

/// The display white: sRGB's D65, (x, y) = (0.3127, 0.3290) (IEC 61966-2-1).
pub const DISPLAY_WHITE_XY: [f64; 2] = [0.3127, 0.3290];

/// Fraction of the brightest pixels that [`AdaptTo::WhitePatch`] averages.
pub const WHITE_PATCH_FRACTION: f64 = 0.01;

/// What the eye is adapted to in the scene.
#[derive(Clone, Debug, PartialEq)]
pub enum AdaptTo {
    /// No chromatic adaptation.
    None,
    /// A given chromaticity (x, y).
    Chromaticity([f64; 2]),
    /// A CIE illuminant by name, `A` or `E` (`d65` is taken as its chromaticity).
    Illuminant(String),
    /// Grey world: the mean XYZ of all pixels.
    SceneAverage,
    /// White patch: the mean XYZ of the brightest 1 % of pixels.
    WhitePatch,
}

impl AdaptTo {
    /// Parses `none`, `d65`, `a`, `e`, `scene_average` (or `scene-average`), `white`, or `x,y`.
    pub fn parse(s: &str) -> Result<AdaptTo, String> {
        let lower = s.trim().to_ascii_lowercase().replace('-', "_");
        match lower.as_str() {
            "none" => return Ok(AdaptTo::None),
            "d65" => return Ok(AdaptTo::Chromaticity(DISPLAY_WHITE_XY)),
            "scene_average" => return Ok(AdaptTo::SceneAverage),
            "white" => return Ok(AdaptTo::WhitePatch),
            "a" | "e" => return Ok(AdaptTo::Illuminant(lower.to_ascii_uppercase())),
            _ => {}
        }
        let parts: Vec<&str> = lower.split(',').map(str::trim).collect();
        let xy = match parts.as_slice() {
            [x, y] => x.parse::<f64>().ok().zip(y.parse::<f64>().ok()),
            _ => None,
        };
        match xy {
            Some((x, y)) => AdaptTo::chromaticity([x, y]),
            None => Err(format!(
                "\"{s}\" is not a white: allowed are none, d65, a, e, white (brightest 1 % of pixels), \
                 scene_average (grey world) or a chromaticity x,y such as 0.25,0.35"
            )),
        }
    }

    /// A given chromaticity, which must lie in the open triangle x > 0, y > 0, x + y < 1.
    pub fn chromaticity(xy: [f64; 2]) -> Result<AdaptTo, String> {
        let [x, y] = xy;
        if x.is_finite() && y.is_finite() && x > 0.0 && y > 0.0 && x + y < 1.0 {
            Ok(AdaptTo::Chromaticity(xy))
        } else {
            Err(format!("chromaticity ({x}, {y}) is not valid: need x > 0, y > 0 and x + y < 1"))
        }
    }

    /// The scene white (Y = 1), or `None` for no adaptation or an image without light.
    pub fn white(&self, image: &SceneImage) -> Option<[f64; 3]> {
        let w = match self {
            AdaptTo::None => return None,
            AdaptTo::Chromaticity(xy) => xy_to_xyz(*xy),
            AdaptTo::Illuminant(name) => relative_xyz(&Spectrum::Constant(1.0), &named_illuminant(name)?),
            AdaptTo::SceneAverage => mean_xyz(image),
            AdaptTo::WhitePatch => brightest_mean(image),
        };
        (w[1].is_finite() && w[1] > 0.0).then(|| w.map(|c| c / w[1]))
    }

    /// How the white is chosen, for reports.
    pub fn describe(&self) -> String {
        match self {
            AdaptTo::None => "none".into(),
            AdaptTo::Chromaticity(xy) => format!("x,y = {},{}", xy[0], xy[1]),
            AdaptTo::Illuminant(n) => format!("CIE illuminant {n}"),
            AdaptTo::SceneAverage => "scene average (grey world)".into(),
            AdaptTo::WhitePatch => "brightest 1 % of pixels (white patch)".into(),
        }
    }
}

fn mean_xyz(image: &SceneImage) -> [f64; 3] {
    let mut sum = [0.0; 3];
    for c in &image.xyz {
        for k in 0..3 {
            sum[k] += c[k];
        }
    }
    sum
}

/// Mean XYZ of the k = max(1, round(0.01 N)) brightest of the N pixels.
fn brightest_mean(image: &SceneImage) -> [f64; 3] {
    let mut order: Vec<(f64, usize)> = image.luminances().into_iter().zip(0..).collect();
    let n = order.len();
    if n == 0 {
        return [0.0; 3];
    }
    let k = ((WHITE_PATCH_FRACTION * n as f64).round() as usize).max(1);
    order.select_nth_unstable_by(n - k, |a, b| a.0.total_cmp(&b.0));
    let mut sum = [0.0; 3];
    for &(_, i) in &order[n - k..] {
        for (s, c) in sum.iter_mut().zip(image.xyz[i]) {
            *s += c;
        }
    }
    sum
}

#[cfg(test)]
mod tests {
    use super::*;

    fn image(xyz: Vec<[f64; 3]>) -> SceneImage {
        let n = xyz.len();
        SceneImage::from_xyz(n, 1, xyz).unwrap()
    }

    #[test]
    fn parses_every_documented_form() {
        assert_eq!(AdaptTo::parse("none").unwrap(), AdaptTo::None);
        assert_eq!(AdaptTo::parse("D65").unwrap(), AdaptTo::Chromaticity(DISPLAY_WHITE_XY));
        assert_eq!(AdaptTo::parse("scene-average").unwrap(), AdaptTo::SceneAverage);
        assert_eq!(AdaptTo::parse("white").unwrap(), AdaptTo::WhitePatch);
        assert_eq!(AdaptTo::parse("A").unwrap(), AdaptTo::Illuminant("A".into()));
        assert_eq!(AdaptTo::parse(" 0.25, 0.35 ").unwrap(), AdaptTo::Chromaticity([0.25, 0.35]));
        assert!(AdaptTo::parse("0.7,0.4").unwrap_err().contains("x + y < 1"));
        assert!(AdaptTo::parse("blue").unwrap_err().contains("scene_average"));
    }

    #[test]
    fn estimates_the_white_as_documented() {
        // Grey world: the mean of a blue and a yellow pixel.
        let img = image(vec![[1.0, 2.0, 5.0], [3.0, 2.0, 1.0]]);
        assert_eq!(AdaptTo::SceneAverage.white(&img), Some([1.0, 1.0, 1.5]));
        // White patch: 100 dim reddish pixels and one bright bluish one; the brightest 1 % is
        // that one pixel.
        let mut px = vec![[2.0, 1.0, 0.5]; 100];
        px.push([8.0, 10.0, 12.0]);
        assert_eq!(AdaptTo::WhitePatch.white(&image(px)), Some([0.8, 1.0, 1.2]));
        // A black image has no white; the display white is (0.3127, 0.3290).
        assert_eq!(AdaptTo::SceneAverage.white(&image(vec![[0.0; 3]; 4])), None);
        let d65 = AdaptTo::parse("d65").unwrap().white(&img).unwrap();
        assert!((d65[0] - 0.950_455).abs() < 1e-6);
        // Illuminant A from the CIE tables: (x, y) = (0.44758, 0.40745) (CIE 015:2018 Table 5).
        let a = AdaptTo::Illuminant("A".into()).white(&img).unwrap();
        let s = a[0] + a[1] + a[2];
        assert!((a[0] / s - 0.44758).abs() < 1e-4 && (a[1] / s - 0.40745).abs() < 1e-4, "{a:?}");
    }
}
