//! What a checkpoint was rendered from, part by part, so that a resume with anything different
//! is refused naming the part: the morgana version, every key of the scene file (per table key,
//! per array-of-tables entry), the bytes of every file the scene names, and the effective
//! photons, seed, α, volume estimate and target, and adaptive sampling when it is on. The
//! stopping rules (`passes`, `time`, `target_rel_error`) are left out: a resume exists to change
//! them. The thread and rank counts are left out: the output does not depend on them.

use crate::distributed::fingerprint::Fnv64;
use crate::scene::Scene;
use std::path::Path;

/// `[integrator]` keys left out: the stopping rules, and what the effective values cover.
const NOT_COMPARED: &[&str] =
    &["passes", "time", "target_rel_error", "target", "photons", "caustic_photons", "seed", "adaptive"];

/// Values longer than this are compared by their FNV-1a hash.
const SHOWN_CHARS: usize = 48;

/// (part, value) pairs in a fixed order.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Fingerprint(pub Vec<(String, String)>);

impl Fingerprint {
    /// The fingerprint of `scene` loaded from `text` (the scene file's text), with the files it
    /// names resolved against `dir` (`None`: the embedded default scene, which names none).
    pub fn of(scene: &Scene, text: &str, dir: Option<&Path>) -> Fingerprint {
        let mut parts = vec![("morgana version".to_string(), env!("CARGO_PKG_VERSION").to_string())];
        parts.extend(scene_parts(text));
        let named = dir.map(|d| crate::distributed::scene::referenced_files(text, d)).unwrap_or_default();
        let mut files: Vec<(String, String)> = named
            .into_iter()
            .map(|(name, path)| {
                let hash = std::fs::read(&path).map_or(0, |b| Fnv64::of(&b));
                (format!("file \"{name}\""), format!("{hash:016x}"))
            })
            .collect();
        files.sort();
        parts.extend(files);
        let s = &scene.integrator;
        parts.push(("photons".into(), s.photons.to_string()));
        parts.push(("caustic photons".into(), s.caustic_photons.to_string()));
        parts.push(("seed".into(), s.seed.to_string()));
        parts.push(("alpha".into(), s.progressive.alpha.to_string()));
        // The effective estimate: unset, it depends on the scene, and its rule changed on 2026-12-05.
        let estimate = match s.volume_estimate {
            crate::scene::VolumeEstimate::Point => "point",
            crate::scene::VolumeEstimate::Beam => "beam",
            crate::scene::VolumeEstimate::PhotonBeams => "photon_beams",
        };
        parts.push(("volume estimate".into(), estimate.into()));
        parts.push(("target".into(), crate::scene::progressive::label(&s.progressive.target)));
        if s.progressive.adaptive {
            // Only when on: a checkpoint without adaptive sampling keeps its bytes.
            parts.push(("adaptive sampling".into(), "on".into()));
        }
        Fingerprint(parts)
    }

    /// What differs between the fingerprint a checkpoint holds (`self`) and `now`, in words,
    /// one entry per part (empty when they agree).
    pub fn differences(&self, now: &Fingerprint) -> Vec<String> {
        let find = |f: &Fingerprint, name: &str| f.0.iter().find(|(n, _)| n == name).map(|(_, v)| v.clone());
        let mut names: Vec<&String> = self.0.iter().chain(&now.0).map(|(n, _)| n).collect();
        names.dedup();
        let mut seen = Vec::new();
        let mut out = Vec::new();
        for name in names {
            if seen.contains(&name) {
                continue;
            }
            seen.push(name);
            match (find(self, name), find(now, name)) {
                (Some(a), Some(b)) if a == b => {}
                (Some(a), Some(b)) => out.push(format!("{name} (checkpoint: {a}, now: {b})")),
                (Some(_), None) => out.push(format!("{name} (in the checkpoint's scene, not in this one)")),
                (None, _) => out.push(format!("{name} (in this scene, not in the checkpoint's)")),
            }
        }
        out
    }
}

/// One part per key of each table of the scene file (`[camera] width`), one per entry of an
/// array of tables (`[[light]] 2`), one per other top-level key, sorted by name; integrator
/// keys of [`NOT_COMPARED`] are left out. Text that does not parse is one part.
fn scene_parts(text: &str) -> Vec<(String, String)> {
    let Ok(toml::Value::Table(top)) = toml::from_str::<toml::Value>(text) else {
        return vec![("scene file".into(), shown(text))];
    };
    let mut parts = Vec::new();
    for (key, value) in &top {
        match value {
            toml::Value::Table(t) => {
                for (k, v) in t {
                    if !(key == "integrator" && NOT_COMPARED.contains(&k.as_str())) {
                        parts.push((format!("the scene's [{key}] {k}"), shown(&v.to_string())));
                    }
                }
            }
            toml::Value::Array(a) if a.iter().all(|v| v.is_table()) => {
                for (i, v) in a.iter().enumerate() {
                    parts.push((format!("the scene's [[{key}]] number {}", i + 1), shown(&v.to_string())));
                }
            }
            v => parts.push((format!("the scene's {key}"), shown(&v.to_string()))),
        }
    }
    parts.sort();
    parts
}

/// `v` itself when short, else its hash.
fn shown(v: &str) -> String {
    if v.chars().count() <= SHOWN_CHARS { v.to_string() } else { format!("hash {:016x}", Fnv64::of(v.as_bytes())) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_changed_key_is_named_and_stopping_rules_are_not_compared() {
        let a = "[camera]\nwidth = 16\n[integrator]\npasses = 2\nk = 50\n[[light]]\nscale = 1.0\n";
        let b = "[camera]\nwidth = 32\n[integrator]\npasses = 9\ntime = 5\nk = 50\n[[light]]\nscale = 2.0\n";
        let (pa, pb) = (Fingerprint(scene_parts(a)), Fingerprint(scene_parts(b)));
        let d = pa.differences(&pb);
        assert_eq!(d.len(), 2, "{d:?}");
        assert!(d.iter().any(|x| x.contains("[camera] width (checkpoint: 16, now: 32)")), "{d:?}");
        assert!(d.iter().any(|x| x.contains("[[light]] number 1")), "{d:?}");
        let c = "[camera]\nwidth = 16\nfov_deg = 40.0\n[integrator]\nk = 50\n[[light]]\nscale = 1.0\n";
        let d = pa.differences(&Fingerprint(scene_parts(c)));
        assert_eq!(d, vec!["the scene's [camera] fov_deg (in this scene, not in the checkpoint's)".to_string()]);
        assert!(pa.differences(&pa).is_empty());
    }

    /// The effective volume estimate is a part of its own, so that a checkpoint written under
    /// another default is refused even where the scene file names none.
    #[test]
    fn the_effective_volume_estimate_is_a_part() {
        let text = crate::scene::DEFAULT_SCENE;
        let scene = crate::scene::load_scene_str(text, Path::new("default.toml"), Path::new("."), "default")
            .expect("the default scene loads");
        let f = Fingerprint::of(&scene, text, None);
        let mut other = f.clone();
        for (name, value) in &mut other.0 {
            if name == "volume estimate" {
                *value = if value == "point" { "beam".into() } else { "point".into() };
            }
        }
        assert_eq!(f.differences(&other).len(), 1, "{:?}", f.differences(&other));
        assert!(f.differences(&other)[0].starts_with("volume estimate"), "{:?}", f.differences(&other));
    }
}
