//! What can go wrong while integrating a ray, each with a message that says what was found and
//! what was expected.

use glam::DVec3;
use std::fmt;

/// A failure of the ray integrator. Nothing here is ever silently turned into NaN.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum OdeError {
    /// The field gave n ≤ 0, a non-finite n or a non-finite ∇n at a point the step needed.
    BadIndex {
        /// Where the field was sampled, m.
        at: DVec3,
        /// The index found.
        n: f64,
        /// The gradient found, m⁻¹.
        grad_n: DVec3,
    },
    /// A state with non-finite components (or a zero direction) was handed in.
    BadState {
        /// Position, m.
        r: DVec3,
        /// Ray vector n dr/ds.
        v: DVec3,
    },
    /// An integrator setting out of range: which, the value found, what is expected.
    InvalidSettings {
        /// Name of the setting.
        parameter: &'static str,
        /// The value found.
        value: f64,
        /// What is expected, in words.
        expected: &'static str,
    },
    /// A step limit that is negative or NaN.
    InvalidStepLimit {
        /// The limit given, m.
        h_limit: f64,
    },
    /// The controller asked for a step below h_min (or below what s can resolve).
    StepSizeUnderflow {
        /// Arc length where the step started, m.
        s: f64,
        /// The step asked for, m.
        h: f64,
        /// The smallest step allowed, m.
        h_min: f64,
    },
    /// Too many consecutive rejections inside one step.
    TooManyRejections {
        /// Arc length where the step started, m.
        s: f64,
        /// Consecutive rejections counted.
        rejections: u32,
    },
    /// The integrator reached its budget of steps (accepted + rejected).
    MaxSteps {
        /// Arc length reached, m.
        s: f64,
        /// The budget of steps.
        max_steps: u64,
    },
}

impl fmt::Display for OdeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            OdeError::BadIndex { at, n, grad_n } => write!(
                f,
                "refractive-index field at ({}, {}, {}) m gives n = {n}, grad n = ({}, {}, {}) m^-1; \
                 expected a finite n > 0 and a finite gradient",
                at.x, at.y, at.z, grad_n.x, grad_n.y, grad_n.z
            ),
            OdeError::BadState { r, v } => write!(
                f,
                "ray state r = ({}, {}, {}) m, v = ({}, {}, {}) is not usable; expected finite \
                 components and a nonzero direction",
                r.x, r.y, r.z, v.x, v.y, v.z
            ),
            OdeError::InvalidSettings { parameter, value, expected } => {
                write!(f, "ray integrator settings: {parameter} = {value}; expected {expected}")
            }
            OdeError::InvalidStepLimit { h_limit } => {
                write!(f, "step limit h_limit = {h_limit} m; expected a number >= 0")
            }
            OdeError::StepSizeUnderflow { s, h, h_min } => write!(
                f,
                "ray integrator step size underflow at s = {s} m: the error control asks for \
                 h = {h:e} m, below h_min = {h_min:e} m (the field varies too fast for the tolerance)"
            ),
            OdeError::TooManyRejections { s, rejections } => write!(
                f,
                "ray integrator rejected {rejections} consecutive steps at s = {s} m without \
                 meeting the tolerance"
            ),
            OdeError::MaxSteps { s, max_steps } => write!(
                f,
                "ray integrator reached its budget of {max_steps} steps at s = {s} m; raise \
                 max_steps or loosen the tolerance"
            ),
        }
    }
}

impl std::error::Error for OdeError {}

impl From<OdeError> for crate::error::Error {
    /// Bad fields and settings come from the user's scene (exit code 2); the others are the
    /// integrator failing (exit code 1).
    fn from(e: OdeError) -> Self {
        match e {
            OdeError::BadIndex { .. } | OdeError::InvalidSettings { .. } => {
                crate::error::Error::input(None, e.to_string())
            }
            _ => crate::error::Error::internal(e.to_string()),
        }
    }
}
