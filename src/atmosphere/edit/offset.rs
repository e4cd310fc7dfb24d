//! A uniform temperature offset: T += ΔT (e.g. a warmer or colder day than USA76's 15 °C).

#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Offset {
    pub dt_k: f64,
}
