//! Kinks as step ends: the spheres where a radial field's gradient jumps, where curved paths'
//! steps end. They live in [`crate::ode::kink`], below the atmosphere, so that `morgana
//! refraction`'s tracer cuts its steps at them too (issue 18).

pub use crate::ode::kink::{Cut, Kink, KinkSpheres, Side, Tolerance};
