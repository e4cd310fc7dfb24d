//! A uniform temperature offset: T += ΔT (e.g. a warmer or colder day than USA76's 15 °C).

/// A uniform temperature offset.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Offset {
    /// ΔT, K.
    pub dt_k: f64,
}
