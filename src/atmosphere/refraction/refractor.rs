//! Astronomical refraction through an atmosphere file by the method asked: Bouguer's
//! quadrature of the refraction integral ([`super::terrestrial::true_altitude`]) where the air
//! allows it, or the ray trace ([`Tracer`]), its oracle.
//!
//! In air whose index depends on height alone over a round Earth, n·r·cos e is constant along a
//! ray, so the true altitude of a star seen at apparent altitude e₀ is a one-dimensional
//! integral over height: e_v − Φ, with Φ the central angle the ray sweeps to the top and e_v its
//! elevation there (Smart 1977, ch. III; Auer & Standish 2000). The quadrature samples n only
//! where its error estimate needs it, and agrees with the trace to the trace's own tolerance
//! (tests/terrestrial.rs, `the_quadrature_is_the_trace_by_default`). A ray it does not follow —
//! one that meets the ground, is turned back by a duct, or points at the zenith — is traced, so
//! every row has the trace's answer where the quadrature has none.
//!
//! # References
//! - W. M. Smart, *Textbook on Spherical Astronomy*, 6th ed., Cambridge 1977, ch. III.
//! - L. H. Auer, E. M. Standish, "Astronomical refraction: computational method for all zenith
//!   angles", Astron. J. 119 (2000) 2472–2474.

use super::model_table::QUADRATURE_TOL_RAD;
use super::terrestrial::{AtmosphereIndex, RadialAir, radial_air, true_altitude};
use super::{Outcome, Trace, Tracer};
use crate::error::Result;

/// How a [`Refractor`] answers.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Bouguer's quadrature, rays it does not follow traced.
    Quadrature,
    /// The ray trace for every ray.
    Trace,
}

/// One observer, one atmosphere, one wavelength, one method.
#[derive(Clone, Debug)]
pub struct Refractor<'a> {
    tracer: Tracer<'a>,
    /// The tracer's air for the quadrature; `None`: every ray is traced.
    air: Option<RadialAir<AtmosphereIndex<'a>>>,
}

/// One answer: the ray's outcome (from the quadrature: no path length and no steps) and the
/// quadrature's evaluations of n when it answered.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Answer {
    /// The ray's outcome.
    pub trace: Trace,
    /// `Some(evaluations)` when Bouguer's quadrature gave it, `None` when it was traced.
    pub quadrature_evaluations: Option<u64>,
}

impl<'a> Refractor<'a> {
    /// Every ray traced.
    pub fn trace(tracer: Tracer<'a>) -> Refractor<'a> {
        Refractor { tracer, air: None }
    }

    /// By Bouguer's quadrature; an error naming why when the tracer's atmosphere is not
    /// spherically symmetric (a flat Earth, edits that vary along the ground).
    pub fn quadrature(tracer: Tracer<'a>) -> std::result::Result<Refractor<'a>, String> {
        let air = radial_air(tracer.atmosphere(), tracer.wavelength_nm())?;
        Ok(Refractor { tracer, air: Some(air) })
    }

    /// By `method`, or when `None` by the quadrature where the atmosphere allows it and by the
    /// trace elsewhere.
    pub fn new(tracer: Tracer<'a>, method: Option<Method>) -> std::result::Result<Refractor<'a>, String> {
        match method {
            Some(Method::Trace) => Ok(Refractor::trace(tracer)),
            Some(Method::Quadrature) => Refractor::quadrature(tracer),
            None => Ok(Refractor::quadrature(tracer.clone()).unwrap_or_else(|_| Refractor::trace(tracer))),
        }
    }

    /// The method the rays are answered by.
    pub fn method(&self) -> Method {
        if self.air.is_some() { Method::Quadrature } else { Method::Trace }
    }

    /// The tracer (the observer, the atmosphere, the wavelength).
    pub fn tracer(&self) -> &Tracer<'a> {
        &self.tracer
    }

    /// The same observer and method at another wavelength.
    pub fn at_wavelength(&self, wavelength_nm: f64) -> Result<Refractor<'a>> {
        let tracer = self.tracer.at_wavelength(wavelength_nm)?;
        match self.air {
            None => Ok(Refractor::trace(tracer)),
            Some(_) => Refractor::quadrature(tracer).map_err(|e| crate::error::Error::input(None, e)),
        }
    }

    /// The ray leaving the observer at `apparent_altitude_rad`.
    pub fn answer(&self, apparent_altitude_rad: f64) -> Result<Answer> {
        let h0 = self.tracer.atmosphere().earth.height(self.tracer.observer());
        let by_quadrature = self
            .air
            .as_ref()
            .and_then(|air| true_altitude(air, h0, apparent_altitude_rad, QUADRATURE_TOL_RAD).ok().flatten());
        Ok(match by_quadrature {
            Some((true_altitude_rad, evaluations)) => Answer {
                trace: Trace {
                    apparent_altitude_rad,
                    outcome: Outcome::Escaped { true_altitude_rad },
                    path_length_m: f64::NAN,
                    ode_steps: 0,
                    ode_rejected: 0,
                },
                quadrature_evaluations: Some(evaluations),
            },
            None => Answer { trace: self.tracer.trace(apparent_altitude_rad)?, quadrature_evaluations: None },
        })
    }

    /// The true altitude of the star seen at `apparent_altitude_rad`, rad (`None` when the ray
    /// does not escape).
    pub fn true_altitude_rad(&self, apparent_altitude_rad: f64) -> Result<Option<f64>> {
        Ok(self.answer(apparent_altitude_rad)?.trace.true_altitude_rad())
    }

    /// The refraction at `apparent_altitude_rad`, rad (`None` when the ray does not escape).
    pub fn refraction_rad(&self, apparent_altitude_rad: f64) -> Result<Option<f64>> {
        Ok(self.answer(apparent_altitude_rad)?.trace.refraction_rad())
    }
}
