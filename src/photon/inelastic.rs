//! The second Russian roulette in photon tracing (Gutierrez et al. 2005, §3, Eq. 14) and its
//! bookkeeping: what each inelastic component took from the photons and gave back.
//!
//! Balance of a global pass (tested): emitted + Σ_i (emitted_w − excited_w) = absorbed at
//! surfaces + absorbed in media + escaped + truncated, where a photon re-emitted outside the
//! scene's wavelength range is absorbed there (its energy is counted in `out_of_range_w` and in
//! the medium's absorption: no band could record it).

use crate::media::Medium;
use crate::media::inelastic::{Outcome, Process};
use crate::rng::Rng;
use crate::world::World;
use glam::DVec3;
use serde::{Deserialize, Serialize};

/// One component's tally over a pass. Powers in W.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
pub struct InelasticTally {
    /// Name of the medium the component belongs to.
    pub medium: String,
    /// Name of the component.
    pub component: String,
    /// Re-emissions (fluorescence) or Raman scatterings.
    pub events: u64,
    /// Power of every photon the component absorbed or Raman-scattered (re-emitted or not).
    pub absorbed_w: f64,
    /// Power of the photons it re-emitted, before re-emission (energy in).
    pub excited_w: f64,
    /// Their power after re-emission (energy out).
    pub emitted_w: f64,
    /// Of `emitted_w`, what was re-emitted outside the scene's wavelength range (then absorbed).
    pub out_of_range_w: f64,
}

impl InelasticTally {
    /// Adds another tally of the same component.
    pub fn add(&mut self, o: &InelasticTally) {
        self.events += o.events;
        self.absorbed_w += o.absorbed_w;
        self.excited_w += o.excited_w;
        self.emitted_w += o.emitted_w;
        self.out_of_range_w += o.out_of_range_w;
    }
}

/// Empty tallies, one per component of every medium, named.
pub fn tallies(world: &World) -> Vec<InelasticTally> {
    world
        .media
        .iter()
        .flat_map(|m| {
            m.inelastic.components.iter().map(|c| InelasticTally {
                medium: m.name.clone(),
                component: c.name.clone(),
                ..InelasticTally::default()
            })
        })
        .collect()
}

/// Index of the first tally of medium `medium`.
fn offset(world: &World, medium: u32) -> usize {
    world.media[..medium as usize].iter().map(|m| m.inelastic.components.len()).sum()
}

/// A photon re-emitted by an inelastic event.
pub struct Reemission {
    /// Fluorescence or Raman.
    pub process: Process,
    /// Emission wavelength, nm.
    pub wavelength_nm: f64,
    /// Unit direction of travel after re-emission.
    pub dir: DVec3,
    /// Power after re-emission (times the energy factor), W.
    pub power_w: f64,
}

/// What follows an interaction that the first roulette did not make an elastic scattering, for a
/// photon of `power_w` at `wavelength_nm` travelling along `dir` in medium `medium`: the
/// re-emitted photon, or `Err(power absorbed)` (the re-emitted power when the new wavelength is
/// outside `range_nm`, the wavelengths simulated). Tallies go to `tally` (indexed by [`tallies`]).
#[allow(clippy::too_many_arguments)]
pub fn after_absorption(
    world: &World,
    range_nm: (f64, f64),
    m: &Medium,
    medium: u32,
    wavelength_nm: f64,
    dir: DVec3,
    power_w: f64,
    rng: &mut Rng,
    tally: &mut Vec<InelasticTally>,
) -> Result<Reemission, f64> {
    let non_elastic = m.sigma_t(wavelength_nm) - m.sigma_s(wavelength_nm);
    let outcome = m.inelastic.interact(wavelength_nm, non_elastic, dir, rng);
    let slot = |i: usize, tally: &mut Vec<InelasticTally>| {
        let k = offset(world, medium) + i;
        if tally.len() <= k {
            tally.resize(k + 1, InelasticTally::default());
        }
        k
    };
    match outcome {
        Outcome::Absorbed { component: None } => Err(power_w),
        Outcome::Absorbed { component: Some(i) } => {
            let k = slot(i, tally);
            tally[k].absorbed_w += power_w;
            Err(power_w)
        }
        Outcome::Emitted { component, wavelength_nm: l, dir, energy_factor } => {
            let k = slot(component, tally);
            let out = power_w * energy_factor;
            let t = &mut tally[k];
            t.events += 1;
            t.absorbed_w += power_w;
            t.excited_w += power_w;
            t.emitted_w += out;
            if !(range_nm.0..=range_nm.1).contains(&l) {
                t.out_of_range_w += out;
                return Err(out);
            }
            let process = m.inelastic.components[component].process;
            Ok(Reemission { process, wavelength_nm: l, dir, power_w: out })
        }
    }
}
