//! The wavelengths an eye path carries.
//!
//! With `sampling = "bands"` a path carries one wavelength per band, jittered within it; with
//! `sampling = "hero"` it carries 4 wavelengths spread evenly over the whole range from a random
//! hero wavelength (Wilkie, Nawaz, Droske, Weidlich & Hanika 2014, "Hero Wavelength Spectral
//! Sampling", EGSR). Both estimate the band average L̄_b = (1/Δλ)∫_b L dλ: a bands lane
//! deposits L(λ) into its band; a hero lane deposits L(λ)·(W/Δλ)/4 into the band holding λ,
//! where W is the range width.

use crate::scene::{HERO_WAVELENGTHS, WavelengthSampling};
use crate::spectrum::{Bands, MAX_BANDS};

/// The wavelengths one eye path carries (see the module docs).
#[derive(Clone, Copy, Debug)]
pub struct Lanes {
    /// Number of lanes in use.
    pub len: usize,
    /// Wavelength of each lane, nm (the first `len` are in use).
    pub nm: [f64; MAX_BANDS],
    /// Band holding each lane's wavelength.
    pub band: [u8; MAX_BANDS],
    /// Number of lanes the camera sample started with; a path split at a dispersive surface
    /// carries `len` of them.
    pub camera_len: usize,
}

impl Lanes {
    /// Wavelengths for one eye sample from uniform `u`.
    pub fn new(bands: &Bands, sampling: WavelengthSampling, u: f64) -> Lanes {
        let mut l = Lanes { len: 0, nm: [0.0; MAX_BANDS], band: [0; MAX_BANDS], camera_len: 0 };
        match sampling {
            WavelengthSampling::Bands => {
                l.len = bands.count;
                l.camera_len = bands.count;
                for b in 0..bands.count {
                    let (lo, hi) = bands.edges_nm(b);
                    l.nm[b] = lo + u * (hi - lo);
                    l.band[b] = b as u8;
                }
            }
            WavelengthSampling::Hero => {
                l.len = HERO_WAVELENGTHS;
                l.camera_len = HERO_WAVELENGTHS;
                let w = bands.max_nm - bands.min_nm;
                for j in 0..HERO_WAVELENGTHS {
                    let t = (u + j as f64 / HERO_WAVELENGTHS as f64).fract();
                    l.nm[j] = bands.min_nm + t * w;
                    l.band[j] = bands.index_of(l.nm[j]).unwrap_or(bands.count - 1) as u8;
                }
            }
        }
        l
    }

    /// Just lane `i`.
    pub fn single(&self, i: usize) -> Lanes {
        let mut l = Lanes { len: 1, nm: [0.0; MAX_BANDS], band: [0; MAX_BANDS], camera_len: self.camera_len };
        l.nm[0] = self.nm[i];
        l.band[0] = self.band[i];
        l
    }

    /// `n` scaled by the share of the camera sample's lanes this path carries (at least 1): a
    /// path split into single wavelengths spends per lane what the unsplit path spends for all.
    pub fn share_of(&self, n: usize) -> usize {
        (n * self.len).div_ceil(self.camera_len.max(1)).max(1)
    }

    /// Weight with which a lane's radiance enters its band's average.
    pub fn film_weight(bands: &Bands, sampling: WavelengthSampling) -> f64 {
        match sampling {
            WavelengthSampling::Bands => 1.0,
            WavelengthSampling::Hero => bands.count as f64 / HERO_WAVELENGTHS as f64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn band_lanes_stay_in_their_bands_and_hero_lanes_cover_the_range() {
        let bands = Bands::new(400.0, 700.0, 10).unwrap();
        let l = Lanes::new(&bands, WavelengthSampling::Bands, 0.999);
        for i in 0..l.len {
            assert_eq!(bands.index_of(l.nm[i]), Some(l.band[i] as usize));
        }
        // Uniform u gives hero lanes uniform over the range: every band is hit equally often.
        let mut hits = [0usize; 10];
        for k in 0..1000 {
            let h = Lanes::new(&bands, WavelengthSampling::Hero, (k as f64 + 0.5) / 1000.0);
            for j in 0..h.len {
                hits[h.band[j] as usize] += 1;
            }
        }
        assert!(hits.iter().all(|&n| n == 400), "{hits:?}");
    }
}
