//! Refractive-index fields n(λ, x) and their gradients, and the dispersion laws they use.
