//! report.json: what ran, how long each phase took, how many photons and rays.
