//! The effect plan: computed once from the validated scene, it says which machinery runs and
//! why. Integrators read it instead of re-deriving it; `morgana check` prints it and
//! `report.json` records it. "Simulate only what the scene calls for" starts here.

use super::settings::{DirectLighting, IntegratorSettings, Method, VolumeEstimate, WavelengthSampling};
use crate::material::Material;
use crate::media::Medium;
use serde::Serialize;

/// Whether one piece of machinery runs, and the reason in words a user can act on.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct Decision {
    /// Whether it runs.
    pub on: bool,
    /// Why, in words a user can act on (printed by `morgana check`, recorded in `report.json`).
    pub why: String,
}

impl Decision {
    fn on(why: impl Into<String>) -> Decision {
        Decision { on: true, why: why.into() }
    }
    fn off(why: impl Into<String>) -> Decision {
        Decision { on: false, why: why.into() }
    }
}

/// Which light-transport machinery a scene needs, one [`Decision`] per piece.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct EffectPlan {
    /// Photons stored on diffuse surfaces for indirect light (and for everything when direct
    /// light comes from the photon map).
    pub global_map: Decision,
    /// Photons that reached a diffuse surface through specular surfaces only (L S+ D).
    pub caustic_map: Decision,
    /// Direct light on diffuse surfaces and single scattering in media by shadow rays
    /// (next-event estimation).
    pub shadow_rays: Decision,
    /// Indirect light by gathering the global map from a set of rays at each shading point.
    pub final_gather: Decision,
    /// Eye paths carrying several wavelengths split at wavelength-dependent refraction.
    pub dispersion_splitting: Decision,
    /// Absorption and scattering in media along paths (off when every used medium is clear).
    pub participating_media: Decision,
    /// Photons stored in participating media for in-scattered light along eye rays.
    pub volume_map: Decision,
    /// Rays follow Fermat's ray equation where a medium's refractive index varies.
    pub curved_paths: Decision,
    /// Fluorescence and Raman re-emission at other wavelengths.
    pub inelastic_scattering: Decision,
    /// Repeated passes with fresh photon maps and shrinking radii, averaged (progressive photon
    /// mapping), and the rules that stop them.
    pub progressive_passes: Decision,
}

/// What the scene contains, as far as the plan cares.
pub struct SceneFacts<'a> {
    pub used_materials: Vec<(&'a str, &'a Material)>,
    pub used_media: Vec<&'a Medium>,
    pub sampling: WavelengthSampling,
    pub bands: usize,
    /// The short end of the simulated wavelengths, nm.
    pub min_nm: f64,
    /// The scene has sensors that count photons at every interaction (ocean profiles).
    pub photon_sensors: bool,
    /// The lowest elevation (degrees above the horizontal) of any direction the scene measures
    /// light along or receives it from (camera field, sky sensors, suns).
    pub lowest_sight_deg: f64,
    /// What the volume map's decision says of folding photons about the sun's axis (see
    /// [`super::symmetry::plan_words`]).
    pub axial_words: Option<String>,
}

impl EffectPlan {
    /// Decides the plan from what the scene contains and the integrator settings.
    pub fn decide(facts: &SceneFacts, s: &IntegratorSettings) -> EffectPlan {
        if s.method == Method::Path {
            return Self::path_tracing(facts, s);
        }
        let diffuse = facts.used_materials.iter().find(|(_, m)| m.is_diffuse()).map(|(n, _)| *n);
        let specular = facts.used_materials.iter().find(|(_, m)| m.is_specular()).map(|(n, _)| *n);
        let dispersive = facts.used_materials.iter().find(|(_, m)| m.is_dispersive()).map(|(n, _)| *n);
        let photon_direct = s.direct == DirectLighting::PhotonMap;
        let global_map = match (diffuse, s.photons) {
            (None, _) => Decision::off("no diffuse surface in the scene stores photons"),
            (Some(_), 0) => Decision::off("[integrator] photons = 0"),
            (Some(d), _) if photon_direct => Decision::on(format!(
                "direct = \"photon_map\": all light on diffuse surfaces (e.g. \"{d}\") comes from the global map"
            )),
            (Some(d), _) => Decision::on(format!("diffuse material \"{d}\" receives indirect light")),
        };
        let caustic_map = match (diffuse, specular) {
            _ if photon_direct => Decision::off("direct = \"photon_map\": caustics are part of the global map"),
            (None, _) => Decision::off("no diffuse surface to receive caustics"),
            (_, None) => Decision::off("no specular surface (mirror or glass) can focus light"),
            _ if s.caustic_photons == 0 => Decision::off("[integrator] caustic_photons = 0"),
            (Some(d), Some(sp)) => {
                Decision::on(format!("specular material \"{sp}\" can focus light onto diffuse \"{d}\""))
            }
        };
        let (global_map, caustic_map) = (with_edge_words(global_map, s), with_edge_words(caustic_map, s));
        let scattering = facts.used_media.iter().find(|m| m.scatters()).map(|m| m.name.as_str());
        let shadow_rays = match (diffuse, scattering) {
            _ if photon_direct => Decision::off("direct = \"photon_map\": direct light comes from the photon maps"),
            (None, None) => Decision::off("no diffuse surface or scattering medium receives direct light"),
            (d, m) => Decision::on(format!(
                "direct = \"shadow_rays\": {} by shadow rays",
                lit_by_shadow_rays(d, m, "direct light on diffuse", "single scattering in")
            )),
        };
        let final_gather = match (s.final_gather, global_map.on) {
            (true, true) => {
                Decision::on(format!("{} gather rays per shading point read the global map", s.gather_rays))
            }
            (true, false) => Decision::off("no global map to gather from"),
            (false, _) if photon_direct => {
                Decision::off("direct = \"photon_map\": the global map is visualised directly")
            }
            (false, _) => Decision::off("final_gather = false: indirect light read directly from the global map"),
        };
        let multi = facts.sampling == WavelengthSampling::Hero || facts.bands > 1;
        let bending_medium =
            facts.used_media.iter().find(|m| m.bends_light() && m.index.as_ref().is_some_and(|f| f.is_dispersive()));
        let bending = bending_medium.map(|m| m.name.as_str());
        let dispersion_splitting = match (dispersive, bending, multi) {
            (None, None, _) => Decision::off("no material's or medium's refractive index depends on wavelength"),
            (_, _, false) => Decision::off("a single band: every path carries one wavelength"),
            (Some(m), _, true) => Decision::on(format!("material \"{m}\" refracts each wavelength differently")),
            (None, Some(m), true) => Decision::on(format!(
                "medium \"{m}\" bends each wavelength differently: eye paths split into one path per wavelength there{}",
                bundles_words(bending_medium, facts, s)
            )),
        };
        EffectPlan {
            global_map,
            caustic_map,
            shadow_rays,
            final_gather,
            dispersion_splitting,
            participating_media: media_decision(&facts.used_media),
            volume_map: volume_map_decision(facts, s),
            curved_paths: curved_decision(facts, s),
            inelastic_scattering: inelastic_decision(&facts.used_media),
            progressive_passes: Self::progressive_decision(s),
        }
    }

    /// Whether a run makes several passes, and which rules stop them.
    pub fn progressive_decision(s: &IntegratorSettings) -> Decision {
        let p = &s.progressive;
        let mut rules = Vec::new();
        if let Some(n) = p.passes {
            rules.push(format!("at most {n} passes"));
        }
        if let Some(t) = p.time_s {
            rules.push(format!("while the next pass fits in {t} s of wall time"));
        }
        if let Some(e) = p.target_rel_error {
            let on = crate::scene::progressive::label(&p.target);
            rules.push(format!("until the relative standard error of the {on}'s mean is at most {e}"));
        }
        match p.pass_limit() {
            1 => Decision::off(
                "one pass: no passes > 1, time or target_rel_error (or --passes, --time, --target-rel-error)",
            ),
            _ => Decision::on(format!(
                "passes with fresh maps and radii shrinking by Knaus & Zwicker's rule (alpha = {:.3}), averaged {}{}",
                p.alpha,
                rules.join(", "),
                if p.adaptive {
                    format!(
                        "; adaptive sampling: from pass 2 on, each pass's {} eye samples per pixel on average go where the pixels' samples spread most (at least 1, at most {} per pixel)",
                        s.spp,
                        s.spp.saturating_mul(crate::scene::progressive::ADAPTIVE_MAX_FACTOR)
                    )
                } else {
                    String::new()
                }
            )),
        }
    }

    /// The plan of the reference path tracer: no photon maps; direct light by next-event
    /// estimation.
    fn path_tracing(facts: &SceneFacts, s: &IntegratorSettings) -> EffectPlan {
        let diffuse = facts.used_materials.iter().find(|(_, m)| m.is_diffuse()).map(|(n, _)| *n);
        let scattering = facts.used_media.iter().find(|m| m.scatters()).map(|m| m.name.as_str());
        let off = || Decision::off("method = \"path\": unbiased path tracing uses no photon maps");
        let multi = facts.sampling == WavelengthSampling::Hero || facts.bands > 1;
        EffectPlan {
            global_map: off(),
            caustic_map: off(),
            shadow_rays: match (diffuse, scattering) {
                (None, None) => Decision::off("no diffuse surface or scattering medium receives direct light"),
                (d, m) => Decision::on(format!(
                    "method = \"path\": next-event estimation ({})",
                    lit_by_shadow_rays(d, m, "at diffuse", "at collisions in")
                )),
            },
            final_gather: off(),
            dispersion_splitting: Decision::off(if multi {
                "method = \"path\": each path follows one randomly chosen wavelength"
            } else {
                "a single band: every path carries one wavelength"
            }),
            participating_media: media_decision(&facts.used_media),
            volume_map: off(),
            curved_paths: curved_decision(facts, s),
            inelastic_scattering: inelastic_decision(&facts.used_media),
            progressive_passes: Self::progressive_decision(s),
        }
    }

    /// (name, decision) in a fixed order, for printing.
    pub fn entries(&self) -> [(&'static str, &Decision); 10] {
        [
            ("global photon map", &self.global_map),
            ("caustic photon map", &self.caustic_map),
            ("shadow rays", &self.shadow_rays),
            ("final gathering", &self.final_gather),
            ("dispersion splitting", &self.dispersion_splitting),
            ("participating media", &self.participating_media),
            ("volume photon map", &self.volume_map),
            ("curved light paths", &self.curved_paths),
            ("inelastic scattering", &self.inelastic_scattering),
            ("progressive passes", &self.progressive_passes),
        ]
    }
}

impl std::fmt::Display for EffectPlan {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        for (name, d) in self.entries() {
            writeln!(f, "  {:<22} {:<3}  {}", name, if d.on { "on" } else { "off" }, d.why)?;
        }
        Ok(())
    }
}

/// A surface map's decision with how its estimates at a surface measure their disc
/// ([`IntegratorSettings::edge_correction`]).
fn with_edge_words(d: Decision, s: &IntegratorSettings) -> Decision {
    if !d.on {
        return d;
    }
    let words = match s.edge_correction {
        true => "estimates divide by the part of their disc on surfaces that hold photons (edge_correction = true)",
        false => "estimates divide by their whole disc, so edges read dark (edge_correction = false)",
    };
    Decision::on(format!("{}; {words}", d.why))
}

/// How camera paths through a bending, dispersive medium that only absorbs follow its
/// wavelengths: from four guides where dispersion bundles apply
/// (`dispersion_bundles`, [`IntegratorSettings::dispersion_bundles`]).
fn bundles_words(medium: Option<&&Medium>, facts: &SceneFacts, s: &IntegratorSettings) -> String {
    let lanes = if facts.sampling == WavelengthSampling::Bands { facts.bands } else { 0 };
    let absorbs_only = medium.is_some_and(|m| !m.scatters());
    if !absorbs_only || lanes < super::settings::BUNDLE_MIN_LANES {
        return String::new();
    }
    if !s.dispersion_bundles {
        return "; dispersion_bundles = false: every wavelength's camera path is traced".into();
    }
    format!(
        "; camera paths through it trace 4 guide wavelengths and interpolate the other {} from them where a check at one guide holds (dispersion_bundles = true)",
        lanes - 4
    )
}

/// What shadow rays light: "<surface_words> \"white\" and <medium_words> \"fog\"", naming an
/// example diffuse material and scattering medium where there are any.
fn lit_by_shadow_rays(diffuse: Option<&str>, medium: Option<&str>, surface_words: &str, medium_words: &str) -> String {
    match (diffuse, medium) {
        (Some(d), Some(m)) => {
            format!("{surface_words} surfaces (e.g. \"{d}\") and {medium_words} media (e.g. \"{m}\")")
        }
        (Some(d), None) => format!("{surface_words} surfaces (e.g. \"{d}\")"),
        (None, Some(m)) => format!("{medium_words} media (e.g. \"{m}\")"),
        (None, None) => "nothing".to_string(),
    }
}

/// Curved paths where a used medium's index field has a gradient; straight lines elsewhere.
fn curved_decision(facts: &SceneFacts, s: &IntegratorSettings) -> Decision {
    let media = &facts.used_media;
    let bending: Vec<&str> = media.iter().filter(|m| m.bends_light()).map(|m| m.name.as_str()).collect();
    if bending.is_empty() {
        let constant = media.iter().find(|m| m.index.is_some());
        return Decision::off(match constant {
            Some(m) => format!("the refractive index of \"{}\" is constant: every path is a straight line", m.name),
            None => "no refractive-index field: every path is a straight line".to_string(),
        });
    }
    let c = &s.curved;
    let method = match c.ode {
        "dopri5" => format!("Dormand–Prince RK5(4)7M, rtol {:e}, atol {:e}", c.rtol, c.atol),
        other => format!("{other} with a fixed step of {} m", c.step_m),
    };
    let atmospheres: String = media.iter().filter_map(|m| atmosphere_bending(m, facts)).collect();
    Decision::on(format!(
        "the refractive index of \"{}\" varies: light follows Fermat's ray equation there ({method}; chords within {} m of the arc), straight lines elsewhere{atmospheres}",
        bending.join("\", \""),
        c.arc_tolerance_m
    ))
}

/// For an atmosphere medium that bends light and scatters or absorbs it: how much switching its
/// bending off would turn and change the light along the scene's lowest line of sight,
/// R = (n₀ − 1) tan z and B = (n₀ − 1) tan² z τ sec z at the shortest wavelength
/// ([`crate::media::bending`]), and whether B is negligible.
fn atmosphere_bending(m: &Medium, facts: &SceneFacts) -> Option<String> {
    let e = facts.lowest_sight_deg;
    let nm = facts.min_nm;
    let z = (90.0 - e).to_radians();
    if !m.bends_light() || m.is_clear() {
        return None;
    }
    let ground = glam::DVec3::ZERO;
    let turn_deg = crate::media::bending::refraction_bound_rad(m, nm, ground, z).map_or(0.0, f64::to_degrees);
    let Some(bound) = crate::media::bending::radiance_bound(m, nm, ground, z) else {
        return matches!(m.index, Some(crate::media::refractive_index::IndexField::Atmosphere(_))).then(|| {
            format!("; in \"{}\" the scene looks or is lit {e:.1}° from the horizontal: bending matters", m.name)
        });
    };
    let verdict = if bound < crate::media::bending::NEGLIGIBLE { "negligible" } else { "not negligible" };
    Some(format!(
        "; in \"{}\" the lowest line of sight or sun is {e:.1}° up: bending turns it by at most {turn_deg:.3}° ((n₀ − 1) tan z) and changes the light along it by at most {:.2} % at {nm} nm ((n₀ − 1) tan² z τ sec z), {verdict} against {} %",
        m.name,
        100.0 * bound,
        100.0 * crate::media::bending::NEGLIGIBLE
    ))
}

fn media_decision(media: &[&Medium]) -> Decision {
    let media: Vec<&Medium> = media.iter().copied().filter(|m| !m.is_clear()).collect();
    match media.as_slice() {
        [] => Decision::off("the scene declares no medium that absorbs or scatters light"),
        _ => {
            let names: Vec<String> = media
                .iter()
                .map(|m| {
                    let kind = if m.is_homogeneous() { "homogeneous" } else { "heterogeneous" };
                    let what = if m.scatters() { "" } else { ", absorbing only" };
                    format!("\"{}\" ({kind}{what})", m.name)
                })
                .collect();
            Decision::on(format!("light is absorbed and scattered in {}", names.join(", ")))
        }
    }
}

/// On when a used medium has inelastic components, naming them.
fn inelastic_decision(media: &[&Medium]) -> Decision {
    let parts: Vec<String> = media
        .iter()
        .filter(|m| !m.inelastic.is_empty())
        .map(|m| {
            let names: Vec<&str> = m.inelastic.components.iter().map(|c| c.name.as_str()).collect();
            format!("\"{}\" ({})", m.name, names.join(", "))
        })
        .collect();
    if parts.is_empty() {
        Decision::off("no medium re-emits light at another wavelength")
    } else {
        Decision::on(format!(
            "light is re-emitted at other wavelengths (a second Russian roulette on the quantum yield after absorption; Raman scattering always re-emits) in {}",
            parts.join("; ")
        ))
    }
}

fn volume_map_decision(facts: &SceneFacts, s: &IntegratorSettings) -> Decision {
    let mut d = volume_map_storage(&facts.used_media, facts.photon_sensors, s);
    if d.on {
        d.why.push_str(match s.volume_estimate {
            VolumeEstimate::Point => {
                "; eye rays read it by the point estimate (the k nearest photons at every march step; volume_estimate = \"point\")"
            }
            VolumeEstimate::Beam => {
                "; eye rays read it by the beam estimate (every photon whose disc a chord crosses, one query per chord; volume_estimate = \"beam\")"
            }
            VolumeEstimate::PhotonBeams => {
                "; eye rays read it by photon beams (every photon's flight through a medium kept as a thin tube, every tube a chord passes through; volume_estimate = \"photon_beams\")"
            }
        });
        d.why.push_str(match s.edge_correction {
            true => ", estimates ending on the planes of the surfaces a chord starts and ends on (edge_correction = true)",
            false => ", estimates reaching past the surfaces a chord ends on, so fog before a wall reads dark (edge_correction = false)",
        });
        if let Some(words) = &facts.axial_words {
            d.why.push_str(words);
        }
    }
    d
}

/// Whether photons are stored in media, and why.
fn volume_map_storage(media: &[&Medium], photon_sensors: bool, s: &IntegratorSettings) -> Decision {
    if let Some(m) = media.iter().find(|m| !m.is_clear() && !m.scatters())
        && !media.iter().any(|m| m.scatters())
        && !photon_sensors
    {
        return Decision::off(format!(
            "\"{}\" only absorbs (σ_s = 0): nothing is scattered toward the eye, so no photon is stored in it",
            m.name
        ));
    }
    match (media.iter().find(|m| m.keeps_photons(photon_sensors)), s.direct, s.photons) {
        (None, _, _) => Decision::off("no participating medium to store photons in"),
        (Some(_), _, 0) => Decision::off("[integrator] photons = 0"),
        (Some(m), DirectLighting::PhotonMap, _) => Decision::on(format!(
            "photons interacting in \"{}\" are stored at every interaction, the first included: direct = \"photon_map\" takes direct light in media from the map",
            m.name
        )),
        (Some(m), DirectLighting::ShadowRays, _) => Decision::on(format!(
            "photons interacting in \"{}\" are stored at every interaction; camera paths read only those that arrived after a scattering or a surface (single scattering comes from shadow rays, multiple scattering from the map)",
            m.name
        )),
    }
}
