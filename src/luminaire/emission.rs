//! An emission spectrum a photometric file carries (IES TM-33 `SpectralData/EmitterSpectral`,
//! a GLDF `Spectrum`): the relative spectral power distribution of the luminaire's light.
//!
//! Only its shape matters: the file's lumens fix the level, and one candela of light of shape
//! s(λ) is s(λ) / (K_m ∫ s ȳ dλ) W sr⁻¹ nm⁻¹ ([`super::per_candela`]). So the values (times a
//! TM-33 `Multiplier`) are normalised to a peak of 1, and sorted by wavelength; between samples
//! the spectrum is linear, outside them zero (a [`Tabulated`] spectrum).
//!
//! Checked: at least two samples, finite wavelengths in 100–10 000 nm with none repeated,
//! finite values ≥ 0, and some luminous content (360–830 nm), or the lumens could not be
//! carried.

use super::photometric::luminous_integral;
use crate::spectrum::{Spectrum, Tabulated};

/// A file's emission spectrum, normalised to peak 1 (see the module docs).
#[derive(Clone, Debug)]
pub struct EmissionSpectrum {
    table: Tabulated,
    /// Where in the file it came from, e.g. "TM-33 Emitter 1, EmitterSpectral 1".
    pub source: String,
}

impl EmissionSpectrum {
    /// From (wavelength nm, value) samples in any order; the error says what is wrong.
    pub fn new(mut samples: Vec<(f64, f64)>, source: impl Into<String>) -> Result<EmissionSpectrum, String> {
        if samples.len() < 2 {
            return Err(format!("{} sample(s); a spectrum needs at least 2", samples.len()));
        }
        if let Some((w, _)) = samples.iter().find(|(w, _)| !(w.is_finite() && (100.0..=10_000.0).contains(w))) {
            return Err(format!("wavelength {w} nm; wavelengths must be within 100–10000 nm"));
        }
        if let Some((w, v)) = samples.iter().find(|(_, v)| !(v.is_finite() && *v >= 0.0)) {
            return Err(format!("value {v} at {w} nm; values must be finite and ≥ 0"));
        }
        samples.sort_by(|a, b| a.0.total_cmp(&b.0));
        if let Some(w) = samples.windows(2).find(|p| p[0].0 == p[1].0) {
            return Err(format!("wavelength {} nm given twice", w[0].0));
        }
        let peak = samples.iter().map(|s| s.1).fold(0.0, f64::max);
        if peak <= 0.0 {
            return Err("every value is 0".to_string());
        }
        let (nm, values): (Vec<f64>, Vec<f64>) = samples.into_iter().map(|(w, v)| (w, v / peak)).unzip();
        let table = Tabulated::new(nm, values)?;
        if luminous_integral(&Spectrum::Tabulated(table.clone())) <= 0.0 {
            let (lo, hi) = table.domain_nm();
            return Err(format!("it spans {lo}–{hi} nm with nothing visible (360–830 nm) to carry lumens"));
        }
        Ok(EmissionSpectrum { table, source: source.into() })
    }

    /// The spectrum, peak 1.
    pub fn spectrum(&self) -> Spectrum {
        Spectrum::Tabulated(self.table.clone())
    }

    /// Wavelengths (nm, ascending) and values (peak 1).
    pub fn samples(&self) -> (&[f64], &[f64]) {
        self.table.samples()
    }

    /// The first and last wavelength, nm.
    pub fn domain_nm(&self) -> (f64, f64) {
        self.table.domain_nm()
    }

    /// The wavelength of the largest value, nm.
    pub fn peak_nm(&self) -> f64 {
        let (nm, v) = self.samples();
        nm.iter().zip(v).find(|(_, v)| **v == 1.0).map_or(nm[0], |(w, _)| *w)
    }

    /// "TM-33 Emitter 1, EmitterSpectral 1: 81 values, 380–780 nm, peak at 450 nm".
    pub fn describe(&self) -> String {
        let (lo, hi) = self.domain_nm();
        format!("{}: {} values, {lo}–{hi} nm, peak at {} nm", self.source, self.samples().0.len(), self.peak_nm())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn values_are_sorted_and_normalised_to_a_peak_of_one() {
        let s = EmissionSpectrum::new(vec![(500.0, 2.0), (400.0, 1.0), (600.0, 4.0)], "t").unwrap();
        assert_eq!(s.samples(), (&[400.0, 500.0, 600.0][..], &[0.25, 0.5, 1.0][..]));
        assert_eq!(s.peak_nm(), 600.0);
        assert_eq!(s.spectrum().eval(450.0), 0.375);
        assert_eq!(s.spectrum().eval(650.0), 0.0);
        assert_eq!(s.describe(), "t: 3 values, 400–600 nm, peak at 600 nm");
    }

    #[test]
    fn malformed_spectra_say_why() {
        let e = |s: Vec<(f64, f64)>| EmissionSpectrum::new(s, "t").unwrap_err();
        assert!(e(vec![(500.0, 1.0)]).contains("at least 2"));
        assert!(e(vec![(500.0, 1.0), (500.0, 2.0)]).contains("twice"));
        assert!(e(vec![(500.0, 1.0), (510.0, -2.0)]).contains("≥ 0"));
        assert!(e(vec![(500.0, 0.0), (510.0, 0.0)]).contains("every value"));
        assert!(e(vec![(900.0, 1.0), (1000.0, 1.0)]).contains("nothing visible"));
        assert!(e(vec![(f64::NAN, 1.0), (1000.0, 1.0)]).contains("100–10000"));
    }
}
