//! Pattanaik, Tumblin, Yee & Greenberg (2000): time-dependent visual adaptation.
//!
//! **Receptors.** Cones and rods respond to luminance I as R(I) = Iⁿ / (Iⁿ + σⁿ), n = 0.73, with
//! the half-saturation σ set by the adaptation level A through Hunt's (1995) luminance-level
//! factors:
//! - cones: k = 1/(5A + 1), F_L = 0.2 k⁴ (5A) + 0.1 (1 − k⁴)² (5A)^(1/3), σ_c = 2^(1/n) · 5A / F_L;
//! - rods: j = 10⁻⁵ / (5A + 10⁻⁵), F_LS = 3800 j² (5A) + 0.2 (1 − j²)⁴ (5A)^(1/6),
//!   σ_r = 2^(1/n) · A / F_LS.
//!
//! Rods see the photopic-equivalent scotopic luminance L′/2.26 ([`super::scotopic`]), computed
//! from the spectrum. Each response is scaled by the fraction of unbleached pigment, at steady
//! state B_c = 2·10⁶/(2·10⁶ + A_c) and B_r = 0.04/(0.04 + A_r); the scene response is
//! R_s = B_c R_c(L) + B_r R_r(L′/2.26).
//!
//! **Time.** Adaptation follows the luminance the eye looks at, G, in two ways (§3.3 of the
//! paper): neural gain control, dA/dt = (G − A)/t₀ with t₀ = 0.08 s (cones) and 0.15 s (rods), and
//! pigment bleaching and regeneration, dB/dt = (1 − B)/τ − B G/(τ I_½) with τ = 110 s, I_½ = 2·10⁶
//! cd m⁻² (cones) and τ = 400 s, I_½ = 0.04 cd m⁻² (rods), whose steady state is the B above. For
//! a constant G both have closed forms, used here for any step:
//! A(t) = G + (A₀ − G) e^(−t/t₀), B(t) = B_∞ + (B₀ − B_∞) e^(−t (1 + G/I_½)/τ). Going into the
//! light is fast (bleaching runs at rate G/(τ I_½)) and into the dark slow (regeneration at 1/τ),
//! the asymmetry the paper models. [`AdaptationState`] carries this state from frame to frame.
//!
//! **One image.** G is the log-average luminance of the image (cones: L, rods: L′/2.26). By
//! default the eye is fully adapted to it (t = ∞). With `adaptation_time_s = t` and
//! `adapt_from_cd_m2 = L₀`, the eye was at steady state for L₀ (rods at L₀ too) and has looked at
//! this image for t seconds. Neural gain settles within a fraction of a second, pigment over
//! minutes: 50 ms after stepping from 5000 cd m⁻² into a dusk scene it is nearly black; 1 s after,
//! the cones have adapted but the rods are still bleached, so the scene is seen by cones alone,
//! in colour; after about 10 minutes the rods have recovered and colour fades into rod vision.
//!
//! **Display.** A scene reference white of 5A and black of 5A/32 are compared with the display's,
//! adapted to G_d = 25 cd m⁻² (white 125, black 3.9 cd m⁻², cones only): if the scene's response
//! range W_s − K_s exceeds the display's, responses are compressed by g = (W_d − K_d)/(W_s − K_s)
//! about the white (when W_s > W_d) or the black (when K_s < K_d); otherwise they are only shifted
//! to the same anchor. The display luminance is the inverse display response,
//! L_d = σ_d (R_d / (1 − R_d))^(1/n), shown as L_d / 125. With the scene adapted like the display,
//! L_d = L (identity). The rod share B_r R_r / R_s of a pixel's response is shown achromatic.
//!
//! These constants follow the paper as implemented in pfstools' `pfstmo_pattanaik00`
//! (Krawczyk); the paper itself is not available here.
//!
//! # References
//! - S. N. Pattanaik, J. Tumblin, H. Yee, D. P. Greenberg (2000), "Time-Dependent Visual
//!   Adaptation for Fast Realistic Image Display", SIGGRAPH 2000, 47–54.
//! - R. W. G. Hunt (1995), *The Reproduction of Colour*, 5th ed., Fountain Press, §31.

use super::{Display, ToneCurve};

/// The exponent n of the receptor response.
pub const N: f64 = 0.73;
/// Luminance the display viewer is adapted to, cd m⁻².
pub const DISPLAY_ADAPTATION_CD_M2: f64 = 25.0;
/// Reference white as a multiple of the adaptation level.
pub const WHITE_FACTOR: f64 = 5.0;
/// Reference white over reference black.
pub const WHITE_OVER_BLACK: f64 = 32.0;

const CONE_T0_S: f64 = 0.08;
const ROD_T0_S: f64 = 0.15;
const CONE_TAU_S: f64 = 110.0;
const ROD_TAU_S: f64 = 400.0;
const CONE_HALF_BLEACH_CD_M2: f64 = 2e6;
const ROD_HALF_BLEACH_CD_M2: f64 = 0.04;

/// Adaptation levels (cd m⁻²; rods in photopic-equivalent units) and unbleached pigment.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AdaptationState {
    /// Cone adaptation level A_c, cd m⁻².
    pub cone_cd_m2: f64,
    /// Rod adaptation level A_r, cd m⁻² (photopic-equivalent, L′/2.26).
    pub rod_cd_m2: f64,
    /// Fraction of unbleached cone pigment B_c, 0 to 1.
    pub cone_pigment: f64,
    /// Fraction of unbleached rod pigment B_r, 0 to 1.
    pub rod_pigment: f64,
}

impl AdaptationState {
    /// Steady state after looking at `cone_cd_m2` (and `rod_cd_m2`) for a long time.
    pub fn steady(cone_cd_m2: f64, rod_cd_m2: f64) -> AdaptationState {
        AdaptationState {
            cone_cd_m2,
            rod_cd_m2,
            cone_pigment: CONE_HALF_BLEACH_CD_M2 / (CONE_HALF_BLEACH_CD_M2 + cone_cd_m2),
            rod_pigment: ROD_HALF_BLEACH_CD_M2 / (ROD_HALF_BLEACH_CD_M2 + rod_cd_m2),
        }
    }

    /// The state after looking at `cone_cd_m2` / `rod_cd_m2` for `dt_s` seconds (exact for a
    /// constant stimulus; apply per frame for an animation).
    pub fn advance(&self, cone_cd_m2: f64, rod_cd_m2: f64, dt_s: f64) -> AdaptationState {
        let target = AdaptationState::steady(cone_cd_m2, rod_cd_m2);
        let relax = |from: f64, to: f64, rate: f64| to + (from - to) * (-dt_s * rate).exp();
        AdaptationState {
            cone_cd_m2: relax(self.cone_cd_m2, cone_cd_m2, 1.0 / CONE_T0_S),
            rod_cd_m2: relax(self.rod_cd_m2, rod_cd_m2, 1.0 / ROD_T0_S),
            cone_pigment: relax(
                self.cone_pigment,
                target.cone_pigment,
                (1.0 + cone_cd_m2 / CONE_HALF_BLEACH_CD_M2) / CONE_TAU_S,
            ),
            rod_pigment: relax(
                self.rod_pigment,
                target.rod_pigment,
                (1.0 + rod_cd_m2 / ROD_HALF_BLEACH_CD_M2) / ROD_TAU_S,
            ),
        }
    }
}

/// Cone half-saturation σ_c(A), cd m⁻².
pub fn sigma_cone(a: f64) -> f64 {
    let a5 = 5.0 * a.max(1e-12);
    let k4 = (1.0 / (a5 + 1.0)).powi(4);
    let f_l = 0.2 * k4 * a5 + 0.1 * (1.0 - k4).powi(2) * a5.cbrt();
    2f64.powf(1.0 / N) * a5 / f_l
}

/// Rod half-saturation σ_r(A), photopic-equivalent cd m⁻².
pub fn sigma_rod(a: f64) -> f64 {
    let a = a.max(1e-12);
    let j = 1e-5 / (5.0 * a + 1e-5);
    let f_ls = 3800.0 * j * j * 5.0 * a + 0.2 * (1.0 - j * j).powi(4) * (5.0 * a).powf(1.0 / 6.0);
    2f64.powf(1.0 / N) * a / f_ls
}

/// The receptor response Iⁿ / (Iⁿ + σⁿ).
pub fn response(i: f64, sigma: f64) -> f64 {
    let i_n = i.max(0.0).powf(N);
    i_n / (i_n + sigma.powf(N))
}

/// Which receptors take part.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Receptors {
    /// Cones respond.
    pub cones: bool,
    /// Rods respond.
    pub rods: bool,
}

/// The prepared operator for one adaptation state.
#[derive(Clone, Copy, Debug)]
pub struct PattanaikCurve {
    sigma_c: f64,
    sigma_r: f64,
    b_c: f64,
    b_r: f64,
    sigma_d: f64,
    /// Response map R_d = anchor_d + (R_s − anchor_s) · gain.
    anchor_s: f64,
    anchor_d: f64,
    gain: f64,
}

impl PattanaikCurve {
    /// The operator for an eye in `state`, with the given receptors.
    pub fn new(state: &AdaptationState, receptors: Receptors) -> PattanaikCurve {
        let b_c = if receptors.cones { state.cone_pigment } else { 0.0 };
        let b_r = if receptors.rods { state.rod_pigment } else { 0.0 };
        let (sigma_c, sigma_r) = (sigma_cone(state.cone_cd_m2), sigma_rod(state.rod_cd_m2));
        let scene =
            |f: f64| b_c * response(f * state.cone_cd_m2, sigma_c) + b_r * response(f * state.rod_cd_m2, sigma_r);
        let (w_s, k_s) = (scene(WHITE_FACTOR), scene(WHITE_FACTOR / WHITE_OVER_BLACK));
        let sigma_d = sigma_cone(DISPLAY_ADAPTATION_CD_M2);
        let display = |f: f64| response(f * DISPLAY_ADAPTATION_CD_M2, sigma_d);
        let (w_d, k_d) = (display(WHITE_FACTOR), display(WHITE_FACTOR / WHITE_OVER_BLACK));
        let gain = ((w_d - k_d) / (w_s - k_s)).min(1.0);
        let gain = if gain.is_finite() && gain > 0.0 { gain } else { 1.0 };
        let (anchor_s, anchor_d) = if w_s > w_d {
            (w_s, w_d)
        } else if k_s < k_d {
            (k_s, k_d)
        } else {
            (0.0, 0.0)
        };
        PattanaikCurve { sigma_c, sigma_r, b_c, b_r, sigma_d, anchor_s, anchor_d, gain }
    }
}

impl ToneCurve for PattanaikCurve {
    fn display(&self, luminance: f64, rod: f64) -> Display {
        let r_c = self.b_c * response(luminance, self.sigma_c);
        let r_r = self.b_r * response(rod, self.sigma_r);
        let r_s = r_c + r_r;
        let r_d = (self.anchor_d + (r_s - self.anchor_s) * self.gain).clamp(0.0, 1.0 - 1e-9);
        let l_d = self.sigma_d * (r_d / (1.0 - r_d)).powf(1.0 / N);
        let rod_fraction = if r_s > 0.0 { r_r / r_s } else { 0.0 };
        Display { y: l_d / (WHITE_FACTOR * DISPLAY_ADAPTATION_CD_M2), rod_fraction }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const BOTH: Receptors = Receptors { cones: true, rods: true };

    #[test]
    fn half_saturation_follows_hunts_factors() {
        // σ_c = 2^(1/n) 5A / F_L; at A = 100 cd m⁻², F_L ≈ 0.1 · 500^(1/3) = 0.7937.
        let want = 2f64.powf(1.0 / N) * 500.0 / (0.1 * 500f64.cbrt());
        assert!((sigma_cone(100.0) / want - 1.0).abs() < 1e-6);
        // Half the maximum response at I = σ.
        assert!((response(sigma_cone(3.0), sigma_cone(3.0)) - 0.5).abs() < 1e-12);
        assert!(sigma_rod(0.01) > 0.0 && sigma_rod(0.01).is_finite());
    }

    #[test]
    fn monotone_in_luminance() {
        for a in [1e-3, 0.1, 25.0, 1e4] {
            let c = PattanaikCurve::new(&AdaptationState::steady(a, a), BOTH);
            let mut last = -1.0;
            for i in 0..=1000 {
                let l = 10f64.powf(-5.0 + f64::from(i) / 100.0);
                let y = c.display(l, l).y;
                assert!(y >= last, "A = {a}: not monotone at L = {l}");
                last = y;
            }
        }
    }

    #[test]
    fn a_scene_adapted_like_the_display_is_shown_unchanged() {
        let c = PattanaikCurve::new(&AdaptationState::steady(25.0, 25.0), Receptors { cones: true, rods: false });
        for l in [25.0 * 5.0 / 32.0, 10.0, 25.0, 60.0, 125.0] {
            let l_d = c.display(l, 0.0).y * 125.0;
            assert!((l_d / l - 1.0).abs() < 1e-3, "{l} → {l_d}");
        }
    }

    #[test]
    fn adaptation_is_fast_into_light_and_slow_into_dark() {
        let (bright, dark) = (5000.0, 0.01);
        // Neural adaptation: e^(−1) of the way after t₀.
        let s = AdaptationState::steady(bright, bright).advance(dark, dark, CONE_T0_S);
        assert!(((s.cone_cd_m2 - dark) / (bright - dark) - (-1f64).exp()).abs() < 1e-12);
        // Pigment after 60 s: rods bleach (into light) far faster than they regenerate.
        let into_light = AdaptationState::steady(dark, dark).advance(bright, bright, 60.0);
        let into_dark = AdaptationState::steady(bright, bright).advance(dark, dark, 60.0);
        let left = |s: AdaptationState, target: f64| {
            let t = AdaptationState::steady(target, target);
            (s.rod_pigment - t.rod_pigment).abs()
        };
        assert!(left(into_light, bright) < 1e-6 && left(into_dark, dark) > 0.5, "{into_light:?} {into_dark:?}");
        // Long after, the steady state.
        let late = AdaptationState::steady(bright, bright).advance(dark, dark, 1e5);
        let steady = AdaptationState::steady(dark, dark);
        assert!((late.rod_pigment - steady.rod_pigment).abs() < 1e-12);
        // Just after entering the dark the scene looks darker than when adapted.
        let scene = 0.05;
        let early = PattanaikCurve::new(&AdaptationState::steady(bright, bright).advance(dark, dark, 0.05), BOTH);
        let adapted = PattanaikCurve::new(&steady, BOTH);
        assert!(early.display(scene, scene).y < 0.5 * adapted.display(scene, scene).y);
    }
}
