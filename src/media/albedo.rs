//! The single-scattering albedo ω_c(λ) of an atmosphere's constituent ([`super::constituents`]):
//! one number for every wavelength, or a table of values at listed wavelengths.
//!
//! # Interpolation
//! A table (λ_j, ω_j), j = 0 … n − 1 with n ≥ 2 and λ_j strictly increasing, gives
//!
//! ω(λ) = ω_j + (ω_{j+1} − ω_j)(λ − λ_j)/(λ_{j+1} − λ_j) on [λ_j, λ_{j+1}],
//! ω(λ) = ω_0 below λ_0 and ω_{n−1} above λ_{n−1}
//!
//! (linear between the samples, constant beyond the ends). With every ω_j in [0, 1], ω(λ) lies in
//! [0, 1] everywhere, so the absorption (1 − ω(λ)) σ_c(λ) and the scattering ω(λ) σ_c(λ) are
//! never negative.
//!
//! # References
//! - Hess, Koepke & Schult, "Optical properties of aerosols and clouds: the software package
//!   OPAC", Bull. Amer. Meteor. Soc. 79 (1998), 831–844: tables ω(λ) of this kind for its aerosol
//!   types (a spectral albedo is how aerosol climatologies give absorption).

use crate::spectrum::Tabulated;

/// ω(λ) of one constituent (see the module docs).
#[derive(Clone, Debug, PartialEq)]
pub enum Albedo {
    /// The same ω at every wavelength.
    Constant(f64),
    /// Linear between samples, constant beyond the ends.
    Spectral(Tabulated),
}

impl Albedo {
    /// A table of ω at `wavelength_nm`: at least two samples, strictly increasing finite
    /// wavelengths, every value in [0, 1]. The error names what is wrong and how to fix it.
    pub fn spectral(wavelength_nm: Vec<f64>, value: Vec<f64>) -> Result<Albedo, String> {
        if let Some(i) = value.iter().position(|v| !(0.0..=1.0).contains(v)) {
            return Err(format!(
                "value #{i} is {}: a single-scattering albedo lies in [0, 1] at every wavelength",
                value[i]
            ));
        }
        if let Some(i) = wavelength_nm.iter().position(|x| !(x.is_finite() && *x > 0.0)) {
            return Err(format!("wavelength_nm #{i} is {}: give wavelengths in nm, above 0", wavelength_nm[i]));
        }
        Tabulated::new(wavelength_nm, value)
            .map(Albedo::Spectral)
            .map_err(|e| e.replace("tabulated spectrum", "albedo table").replace("values", "value"))
    }

    /// ω(λ).
    pub fn at(&self, wavelength_nm: f64) -> f64 {
        match self {
            Albedo::Constant(w) => *w,
            Albedo::Spectral(t) => {
                let (lo, hi) = t.domain_nm();
                t.eval(wavelength_nm.clamp(lo, hi))
            }
        }
    }

    /// The largest ω over all wavelengths (the largest sample of a table).
    pub fn max(&self) -> f64 {
        match self {
            Albedo::Constant(w) => *w,
            Albedo::Spectral(t) => t.samples().1.iter().copied().fold(0.0, f64::max),
        }
    }

    /// True when the constituent scatters at some wavelength (ω > 0 somewhere).
    pub fn scatters(&self) -> bool {
        self.max() > 0.0
    }

    /// True when every value lies in [0, 1].
    pub fn is_valid(&self) -> bool {
        match self {
            Albedo::Constant(w) => (0.0..=1.0).contains(w),
            Albedo::Spectral(t) => t.samples().1.iter().all(|v| (0.0..=1.0).contains(v)),
        }
    }
}

impl std::fmt::Display for Albedo {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Albedo::Constant(w) => write!(f, "{w}"),
            Albedo::Spectral(t) => {
                let (nm, v) = t.samples();
                write!(f, "{{ wavelength_nm = {nm:?}, value = {v:?} }}")
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interpolates_linearly_and_holds_the_ends() {
        let a = Albedo::spectral(vec![400.0, 500.0, 700.0], vec![0.9, 0.8, 0.6]).unwrap();
        assert_eq!(a.at(400.0), 0.9);
        assert!((a.at(450.0) - 0.85).abs() < 1e-15);
        assert!((a.at(600.0) - 0.7).abs() < 1e-15);
        assert_eq!(a.at(300.0), 0.9, "constant below the first wavelength");
        assert_eq!(a.at(900.0), 0.6, "constant above the last");
        assert_eq!(a.max(), 0.9);
        assert!(a.scatters() && a.is_valid());
        assert!(!Albedo::Constant(0.0).scatters());
    }

    #[test]
    fn rejects_bad_tables_with_the_fix() {
        let e = Albedo::spectral(vec![400.0, 500.0], vec![0.9, 1.2]).unwrap_err();
        assert!(e.contains("value #1") && e.contains("[0, 1]"), "{e}");
        let e = Albedo::spectral(vec![500.0, 400.0], vec![0.9, 0.8]).unwrap_err();
        assert!(e.contains("strictly increasing"), "{e}");
        let e = Albedo::spectral(vec![500.0], vec![0.9]).unwrap_err();
        assert!(e.contains("at least 2"), "{e}");
        let e = Albedo::spectral(vec![400.0, 500.0], vec![0.9]).unwrap_err();
        assert!(e.contains("one value per wavelength"), "{e}");
        let e = Albedo::spectral(vec![-1.0, 500.0], vec![0.9, 0.9]).unwrap_err();
        assert!(e.contains("wavelength_nm #0"), "{e}");
    }
}
