//! Statistical test harnesses shared by unit and integration tests (and by later issues'
//! samplers: phase functions, luminaire webs, redistribution functions).

pub mod chi2;
