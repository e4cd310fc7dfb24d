//! Loss of colour vision in dim light (mesopic and scotopic vision).
//!
//! Below about 5.6 cd m⁻² rods take over from cones and colour fades; below about 0.0056 cd m⁻²
//! vision is rod-only and colourless (Ferwerda et al. 1996, §5; Ward Larson et al. 1997, §5.3).
//! A pixel of photopic luminance L, scotopic luminance L′ and colour XYZ is shown as
//!
//! XYZ_m = k XYZ + (1 − k) (L′ / 2.26) W, k = clamp((L − L_bot) / (L_top − L_bot), 0, 1),
//!
//! L_bot = 5.62·10⁻³ and L_top = 5.62 cd m⁻², with W the display white (Y = 1): the rod signal,
//! L′/2.26 in photopic-equivalent units ([`super::scotopic`]), is seen as a grey, and the
//! weight is linear in luminance across the mesopic range, as in Ward Larson et al.'s
//! implementation. The scotopic luminance comes from the spectrum itself (V′(λ)), so a blue-green
//! underwater scene keeps more brightness in rod vision than a red one of equal luminance — the
//! Purkinje shift an RGB renderer cannot show. Kirk & O'Brien (2011) show that rod signals also
//! shift perceived hue towards blue in mesopic vision; that shift is not simulated here.
//!
//! `scotopic = "on"` forces k = 0 (rod vision only), `"off"` keeps k = 1.
//!
//! # References
//! - J. A. Ferwerda, S. N. Pattanaik, P. Shirley, D. P. Greenberg (1996), "A Model of Visual
//!   Adaptation for Realistic Image Synthesis", SIGGRAPH '96, 249–258, §5.
//! - G. Ward Larson, H. Rushmeier, C. Piatko (1997), IEEE TVCG 3(4), 291–306, §5.3.
//! - A. G. Kirk, J. F. O'Brien (2011), "Perceptually Based Tone Mapping for Low-Light
//!   Conditions", ACM Transactions on Graphics 30(4) (SIGGRAPH 2011), 42:1–10.

use super::matrix::xy_to_xyz;
use super::scene_image::SceneImage;
use super::scotopic::SCOTOPIC_PER_PHOTOPIC_WHITE;
use super::white::DISPLAY_WHITE_XY;

/// Bottom of the mesopic range (top of the scotopic), cd m⁻².
pub const MESOPIC_BOTTOM_CD_M2: f64 = 5.62e-3;
/// Top of the mesopic range (bottom of the photopic), cd m⁻².
pub const MESOPIC_TOP_CD_M2: f64 = 5.62;

/// How rod vision is simulated.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ScotopicMode {
    /// Photopic vision only.
    Off,
    /// Mesopic blending by luminance, with acuity loss.
    Auto,
    /// Rod vision only, with acuity loss.
    On,
}

impl ScotopicMode {
    /// Parses `off`, `auto` or `on` (any case).
    pub fn parse(s: &str) -> Option<ScotopicMode> {
        match s.to_ascii_lowercase().as_str() {
            "off" => Some(ScotopicMode::Off),
            "auto" => Some(ScotopicMode::Auto),
            "on" => Some(ScotopicMode::On),
            _ => None,
        }
    }

    /// The name [`ScotopicMode::parse`] accepts.
    pub fn name(self) -> &'static str {
        match self {
            ScotopicMode::Off => "off",
            ScotopicMode::Auto => "auto",
            ScotopicMode::On => "on",
        }
    }
}

/// The cone weight k at photopic luminance `l` (cd m⁻²).
pub fn cone_weight(l: f64) -> f64 {
    ((l - MESOPIC_BOTTOM_CD_M2) / (MESOPIC_TOP_CD_M2 - MESOPIC_BOTTOM_CD_M2)).clamp(0.0, 1.0)
}

/// Replaces each pixel's colour with its mesopic appearance (see the module documentation).
pub fn apply_mesopic(image: &mut SceneImage, mode: ScotopicMode) {
    if mode == ScotopicMode::Off {
        return;
    }
    let white = xy_to_xyz(DISPLAY_WHITE_XY);
    for (c, &s) in image.xyz.iter_mut().zip(&image.scotopic) {
        let k = if mode == ScotopicMode::On { 0.0 } else { cone_weight(c[1]) };
        let grey = s / SCOTOPIC_PER_PHOTOPIC_WHITE;
        *c = [0, 1, 2].map(|i| k * c[i] + (1.0 - k) * grey * white[i]);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn colour_fades_through_the_mesopic_range() {
        assert_eq!(cone_weight(10.0), 1.0);
        assert_eq!(cone_weight(1e-3), 0.0);
        assert!((cone_weight(2.8135) - 0.5).abs() < 1e-3);
        // A saturated blue pixel at three levels: photopic keeps it, scotopic makes it grey.
        let blue = |y: f64| [0.5 * y, y, 4.0 * y];
        let xyz = vec![blue(100.0), blue(1.0), blue(1e-3)];
        let scot = vec![300.0, 3.0, 3e-3];
        let mut img = SceneImage::from_xyz(3, 1, xyz.clone()).unwrap();
        img.scotopic = scot.clone();
        apply_mesopic(&mut img, ScotopicMode::Auto);
        assert_eq!(img.xyz[0], xyz[0]);
        let grey = xy_to_xyz(DISPLAY_WHITE_XY).map(|w| w * 3e-3 / 2.26);
        assert!((0..3).all(|k| (img.xyz[2][k] - grey[k]).abs() < 1e-15), "{:?}", img.xyz[2]);
        let mid = img.xyz[1];
        assert!(mid[2] / mid[1] < 4.0 && mid[2] / mid[1] > grey[2] / grey[1], "{mid:?}");
        let mut on = SceneImage::from_xyz(3, 1, xyz).unwrap();
        on.scotopic = scot;
        apply_mesopic(&mut on, ScotopicMode::On);
        assert!((on.xyz[0][1] - 300.0 / 2.26).abs() < 1e-9);
        assert_eq!(ScotopicMode::parse("AUTO"), Some(ScotopicMode::Auto));
    }
}
