//! The fuzz targets: for each reader of outside input, its seed documents, how a case is made
//! from a seed (reproducibly, from the run's seed and the case's index), and how a case runs
//! and is judged.

use crate::formats;
use crate::outcome::{Class, Outcome, has_non_finite_word, locates, non_finite_words};
use crate::text_mut::{mutate_bytes, mutate_lines};
use crate::toml_mut::{self, Pool};
use crate::workspace::Workspace;
use morgana::error::Error;
use rand::{Rng, SeedableRng};
use rand_pcg::Pcg64;
use std::ffi::OsString;
use std::path::{Path, PathBuf};
use std::time::Duration;

/// A reader of outside input under test.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Target {
    /// Scene TOML, validated as `morgana check` does (unclamped values).
    Scene,
    /// Scene TOML, clamped to a tiny render (≤ 4×4 pixels, ≤ 500 photons) and rendered; the
    /// outputs are checked.
    Render,
    /// OBJ meshes, read through a scene's `type = "mesh"` shape.
    Obj,
    /// Luminaire files: IES LM-63, EULUMDAT, IES TM-33 XML, GLDF zip (as `morgana luminaire`
    /// and through a scene's luminaire light).
    Luminaire,
    /// Atmosphere TOML files and their CSV profiles (loaded, and through a scene's index).
    Atmosphere,
    /// Density grids (`.mgrid`) and lattice files (`.mfield`), through scenes and atmospheres.
    Grid,
    /// EXR input to `morgana tonemap`.
    Tonemap,
    /// The command line of the real `morgana` binary.
    Cli,
}

/// Every target.
pub const TARGETS: [Target; 8] = [
    Target::Scene,
    Target::Render,
    Target::Obj,
    Target::Luminaire,
    Target::Atmosphere,
    Target::Grid,
    Target::Tonemap,
    Target::Cli,
];

impl Target {
    /// The name on the command line and in `tests/fuzz_corpus/`.
    pub fn name(self) -> &'static str {
        match self {
            Target::Scene => "scene",
            Target::Render => "render",
            Target::Obj => "obj",
            Target::Luminaire => "luminaire",
            Target::Atmosphere => "atmosphere",
            Target::Grid => "grid",
            Target::Tonemap => "tonemap",
            Target::Cli => "cli",
        }
    }

    /// The target of a name.
    pub fn parse(s: &str) -> Option<Target> {
        TARGETS.iter().copied().find(|t| t.name() == s)
    }
}

/// One case: the files to write into the case directory (the first is the mutated input; its
/// name decides how it is read) and, for the command line, the arguments.
#[derive(Clone, Debug)]
pub struct Case {
    /// (name in the case directory, bytes).
    pub files: Vec<(String, Vec<u8>)>,
    /// Arguments of `morgana` (the command-line target).
    pub args: Vec<OsString>,
    /// The seed document and the mutations, for the report.
    pub what: String,
    /// Which way the input is read, for targets with more than one (see [`modes`]).
    pub mode: u32,
}

/// How many ways a target reads its input: a luminaire by `morgana luminaire` (0) or through
/// a scene's light (1); an atmosphere loaded (0) or through a scene's index (1).
pub fn modes(target: Target) -> u32 {
    match target {
        Target::Luminaire | Target::Atmosphere => 2,
        _ => 1,
    }
}

/// The files that read the input named `main` (scenes and atmospheres written beside it).
pub fn context(target: Target, main: &str, mode: u32) -> Vec<(String, Vec<u8>)> {
    let ctx = context_files();
    let get = |n: &str| ctx.iter().find(|(m, _)| *m == n).map(|(_, t)| t.clone()).unwrap_or_default();
    let mut out: Vec<(String, String)> = Vec::new();
    match target {
        Target::Obj => out.push(("mesh_scene.toml".into(), get("mesh_scene.toml"))),
        Target::Luminaire if mode == 1 => {
            out.push(("lum_scene.toml".into(), get("lum_scene.toml").replace("LUMFILE", main)))
        }
        Target::Atmosphere => {
            if main == "profile.csv" {
                out.push((
                    "atm.toml".into(),
                    "name = \"t\"\nprofile = \"profile.csv\"\ndispersion = \"ciddor\"\n".into(),
                ));
            }
            if mode == 1 {
                out.push(("atm_scene.toml".into(), get("atm_scene.toml")));
            }
        }
        Target::Grid => match main {
            "density.mgrid" => out.push(("density_scene.toml".into(), get("density_scene.toml"))),
            "temperature.mfield" => out.push(("field_scene.toml".into(), get("field_scene.toml"))),
            _ => out.push(("delta_atm.toml".into(), get("delta_atm.toml"))),
        },
        _ => {}
    }
    out.into_iter().map(|(n, t)| (n, t.into_bytes())).collect()
}

/// A tiny scene: 4×4 pixels, 2000 photons, one quad and one point light. Contexts for the
/// mesh, grid, luminaire and atmosphere targets add to it.
pub const TINY_SCENE: &str = r#"[camera]
position = [0.0, 1.0, 3.0]
look_at = [0.0, 0.5, 0.0]
fov_deg = 40.0
width = 4
height = 4

[integrator]
photons = 2000
caustic_photons = 2000
spp = 1
gather_rays = 2

[[material]]
name = "white"
type = "lambertian"
reflectance = 0.7

[[shape]]
type = "quad"
origin = [-1.0, 0.0, -1.0]
u = [0.0, 0.0, 2.0]
v = [2.0, 0.0, 0.0]
material = "white"

[[light]]
type = "point"
position = [0.0, 2.0, 0.0]
spectrum = { blackbody_k = 4000 }
power_w = 10.0
"#;

/// Scenes that read the file under test (written into every case directory).
fn context_files() -> Vec<(&'static str, String)> {
    vec![
        (
            "mesh_scene.toml",
            format!(
                "{TINY_SCENE}\n[[shape]]\ntype = \"mesh\"\nfile = \"mesh.obj\"\nmaterial = \"white\"\nscale = 0.5\n"
            ),
        ),
        (
            "lum_scene.toml",
            format!(
                "{TINY_SCENE}\n[[light]]\nname = \"lum\"\ntype = \"luminaire\"\nfile = \"LUMFILE\"\nposition = [0.0, 2.0, 0.0]\ndirection = [0.0, -1.0, 0.0]\n"
            ),
        ),
        (
            "atm_scene.toml",
            format!(
                "{TINY_SCENE}\n[world]\nmedium = \"air\"\n\n[[medium]]\nname = \"air\"\nsigma_a = 0.0\nsigma_s = 0.0\nindex = {{ type = \"atmosphere\", file = \"atm.toml\" }}\n"
            ),
        ),
        (
            "density_scene.toml",
            format!(
                "{TINY_SCENE}\n[[medium]]\nname = \"smoke\"\nsigma_t = 0.5\nalbedo = 0.9\ndensity = {{ type = \"grid\", file = \"density.mgrid\" }}\n\n[[shape]]\ntype = \"box\"\nmin = [-1.0, 0.0, -1.0]\nmax = [1.0, 1.0, 1.0]\ninterior = \"smoke\"\nexterior = \"vacuum\"\n"
            ),
        ),
        (
            "field_scene.toml",
            format!(
                "{TINY_SCENE}\n[world]\nmedium = \"air\"\n\n[[medium]]\nname = \"air\"\nsigma_a = 0.0\nsigma_s = 0.0\nindex = {{ type = \"temperature_grid\", file = \"temperature.mfield\", pressure_pa = 101325.0 }}\n"
            ),
        ),
        ("delta_atm.toml", "base = \"usa76\"\n\n[[edit]]\ntype = \"grid\"\nfile = \"delta.mfield\"\n".to_string()),
    ]
}

/// A scratch folder of this process: its pid and start time (a pid alone repeats across pid
/// namespaces, and two processes writing one seed file would make cases irreproducible).
fn private_dir(what: &str) -> PathBuf {
    static STARTED: std::sync::OnceLock<u32> = std::sync::OnceLock::new();
    let nanos = *STARTED.get_or_init(|| {
        std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.subsec_nanos())
    });
    std::env::temp_dir().join(format!("morgana-fuzz-{what}-{}-{nanos}", std::process::id()))
}

/// Fixture files of the command-line target (written into every case directory).
pub fn cli_fixtures() -> Result<Vec<(String, Vec<u8>)>, String> {
    let mut v: Vec<(String, Vec<u8>)> = vec![("s.toml".into(), TINY_SCENE.as_bytes().to_vec())];
    let dir = private_dir("fixture");
    std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
    let p = dir.join("a.exr");
    formats::spectral_exr(&p, 4, 3, 4, (400.0, 700.0), None)?;
    v.push(("a.exr".into(), std::fs::read(&p).map_err(|e| e.to_string())?));
    std::fs::remove_dir_all(&dir).ok();
    Ok(v)
}

/// Everything a worker needs to make cases: the seed documents of its target.
pub struct Seeds {
    /// (name, bytes) of each seed document.
    pub docs: Vec<(String, Vec<u8>)>,
    /// How often each document is drawn, relative to the others.
    pub weights: Vec<u32>,
    /// For TOML targets: what the mutator splices.
    pub pool: Pool,
}

/// Example scenes that `morgana check` alone takes over a second to read (they trace curved
/// rays through an atmosphere for their sun and horizon; measured 2026-12-02 on the 2-vCPU
/// machine: mirage_hot_road 1.2 s, sunset_sea 2.0 s, sunset_fog 2.1 s, mirage_superior 3.1 s,
/// against 20–250 ms for the other examples). The scene target draws them
/// [`HEAVY_WEIGHT`] times less often than the others; the render target leaves them out (their
/// schema is the other scenes', and a render of them takes seconds however small).
pub const HEAVY_SCENES: [&str; 4] =
    ["mirage_hot_road.toml", "sunset_sea.toml", "sunset_fog.toml", "mirage_superior.toml"];

/// How many times more often a light seed is drawn than a heavy one.
pub const HEAVY_WEIGHT: u32 = 25;

impl Seeds {
    /// The index of a document, drawn by weight.
    pub fn pick(&self, rng: &mut Pcg64) -> usize {
        let total: u32 = self.weights.iter().sum();
        let mut r = rng.random_range(0..total.max(1));
        for (i, w) in self.weights.iter().enumerate() {
            if r < *w {
                return i;
            }
            r -= w;
        }
        0
    }
}

fn read_dir_sorted(dir: &Path, ext: &[&str]) -> Vec<(String, Vec<u8>)> {
    let mut out: Vec<(String, Vec<u8>)> = std::fs::read_dir(dir)
        .map(|r| {
            r.filter_map(|e| e.ok())
                .map(|e| e.path())
                .filter(|p| p.extension().is_some_and(|x| ext.iter().any(|e| x.eq_ignore_ascii_case(e))))
                .filter_map(|p| Some((p.file_name()?.to_string_lossy().into_owned(), std::fs::read(&p).ok()?)))
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
}

impl Seeds {
    /// The seeds of `target`, read from the repository at `repo`.
    pub fn load(target: Target, repo: &Path) -> Result<Seeds, String> {
        let mut docs: Vec<(String, Vec<u8>)> = match target {
            Target::Scene | Target::Render => {
                let mut d = read_dir_sorted(&repo.join("examples"), &["toml"]);
                d.push(("default.toml".into(), morgana::scene::DEFAULT_SCENE.as_bytes().to_vec()));
                d
            }
            Target::Obj => {
                let mut d = formats::obj_seeds();
                d.extend(read_dir_sorted(&repo.join("examples/meshes"), &["obj"]));
                d
            }
            Target::Luminaire => {
                let mut d = read_dir_sorted(&repo.join("luminaires"), &["ies", "ldt"]);
                let data = repo.join("tests/data/luminaires");
                d.extend(read_dir_sorted(&data, &["ies", "ldt"]));
                for f in ["quad_downlight_tm33_18.xml", "quad_downlight_tm33_23.xml"] {
                    d.push((f.into(), std::fs::read(data.join(f)).map_err(|e| format!("{f}: {e}"))?));
                }
                let r = |f: &str| std::fs::read(data.join(f)).map_err(|e| format!("{f}: {e}"));
                let entries = formats::gldf_entries(
                    &r("quad_downlight_gldf_product.xml")?,
                    &r("quad_downlight.ldt")?,
                    &r("quad_downlight.ies")?,
                    &r("quad_downlight_spectrum.txt")?,
                );
                d.push(("quad_downlight.gldf".into(), formats::zip_of(&entries)));
                d
            }
            Target::Atmosphere => {
                let mut d = read_dir_sorted(&repo.join("atmospheres"), &["toml"]);
                d.extend(read_dir_sorted(&repo.join("atmospheres"), &["csv"]));
                d
            }
            Target::Grid => formats::grid_seeds(),
            Target::Tonemap | Target::Cli => Vec::new(),
        };
        if target == Target::Render {
            docs.retain(|(n, _)| !HEAVY_SCENES.contains(&n.as_str()));
        }
        let weights =
            docs.iter().map(|(n, _)| if HEAVY_SCENES.contains(&n.as_str()) { 1 } else { HEAVY_WEIGHT }).collect();
        let texts: Vec<String> = docs
            .iter()
            .filter(|(n, _)| n.ends_with(".toml"))
            .map(|(_, b)| String::from_utf8_lossy(b).into_owned())
            .collect();
        let refs: Vec<&str> = texts.iter().map(String::as_str).collect();
        if docs.is_empty() && !matches!(target, Target::Tonemap | Target::Cli) {
            return Err(format!("no seed documents for {} under {}", target.name(), repo.display()));
        }
        Ok(Seeds { docs, weights, pool: Pool::of(&refs) })
    }
}

/// The random stream of case `index` of a run with `seed`.
pub fn case_rng(target: Target, seed: u64, index: u64) -> Pcg64 {
    let t = TARGETS.iter().position(|x| *x == target).unwrap_or(0) as u64;
    let mut h: u64 = 0x9E37_79B9_7F4A_7C15 ^ seed.wrapping_mul(0xBF58_476D_1CE4_E5B9);
    for x in [t, index] {
        h ^= x.wrapping_add(0x9E37_79B9_7F4A_7C15).wrapping_add(h << 6).wrapping_add(h >> 2);
        h = h.wrapping_mul(0x94D0_49BB_1331_11EB);
    }
    Pcg64::seed_from_u64(h)
}

/// How many mutations a case gets: one most often, up to four.
fn mutation_count(rng: &mut Pcg64) -> usize {
    match rng.random_range(0..100) {
        0..=59 => 1,
        60..=84 => 2,
        85..=94 => 3,
        _ => 4,
    }
}

/// Makes case `index`: picks a seed document and mutates it.
pub fn generate(target: Target, seeds: &Seeds, seed: u64, index: u64) -> Case {
    let mut rng = case_rng(target, seed, index);
    match target {
        Target::Tonemap => return tonemap_case(&mut rng),
        Target::Cli => return crate::cli_mut::case(&mut rng),
        _ => {}
    }
    let (name, doc) = seeds.docs[seeds.pick(&mut rng)].clone();
    let mut what = vec![name.clone()];
    let mut bytes = doc;
    let n = mutation_count(&mut rng);
    if name.ends_with(".gldf") {
        let data = bytes_of_gldf(&bytes);
        let mut entries = data;
        let mut byte_level = false;
        for _ in 0..n {
            match formats::mutate_gldf(&mut rng, &mut entries) {
                Some(w) => what.push(w),
                None => byte_level = true,
            }
        }
        bytes = formats::zip_of(&entries);
        if byte_level {
            let (b, w) = mutate_bytes(&mut rng, &bytes);
            bytes = b;
            what.push(format!("zip bytes: {w}"));
        }
        let mode = rng.random_range(0..modes(target));
        return finish(target, name, bytes, what, mode);
    }
    for _ in 0..n {
        // morgana refuses a TOML file past its size limit unread: mutating it further only
        // costs the worker time and memory (a 160 MB scene's slots took past the deadline).
        if name.ends_with(".toml") && bytes.len() as u64 > morgana::error::MAX_TEXT_FILE_BYTES {
            break;
        }
        let (b, w) = mutate_one(&mut rng, &name, &bytes, seeds);
        bytes = b;
        what.push(w);
    }
    let mode = rng.random_range(0..modes(target));
    finish(target, name, bytes, what, mode)
}

fn mutate_one(rng: &mut Pcg64, name: &str, bytes: &[u8], seeds: &Seeds) -> (Vec<u8>, String) {
    let ext = name.rsplit('.').next().unwrap_or("").to_ascii_lowercase();
    match ext.as_str() {
        "toml" => match std::str::from_utf8(bytes) {
            Ok(s) => toml_mut::mutate(rng, s, &seeds.pool),
            Err(_) => mutate_bytes(rng, bytes),
        },
        "obj" => formats::mutate_obj(rng, bytes),
        "xml" => formats::mutate_xml(rng, bytes),
        "mgrid" => formats::mutate_grid(rng, bytes, 4),
        "mfield" => formats::mutate_grid(rng, bytes, 6),
        "ies" | "ldt" => {
            if rng.random_bool(0.8) {
                mutate_lines(rng, bytes, 40)
            } else {
                mutate_bytes(rng, bytes)
            }
        }
        _ => {
            if rng.random_bool(0.8) {
                mutate_lines(rng, bytes, 0)
            } else {
                mutate_bytes(rng, bytes)
            }
        }
    }
}

fn bytes_of_gldf(zip_bytes: &[u8]) -> Vec<(String, Vec<u8>)> {
    use std::io::Read;
    let mut out = Vec::new();
    if let Ok(mut z) = zip::ZipArchive::new(std::io::Cursor::new(zip_bytes)) {
        for i in 0..z.len() {
            if let Ok(mut f) = z.by_index(i) {
                let mut b = Vec::new();
                if f.read_to_end(&mut b).is_ok() {
                    out.push((f.name().map(|n| n.to_string()).unwrap_or_default(), b));
                }
            }
        }
    }
    out
}

/// The case's file name in the case directory, from the seed's name and target.
fn finish(target: Target, seed_name: String, mut bytes: Vec<u8>, what: Vec<String>, mode: u32) -> Case {
    let ext = seed_name.rsplit('.').next().unwrap_or("").to_ascii_lowercase();
    let file = match (target, ext.as_str()) {
        (Target::Scene | Target::Render, _) => "scene.toml".to_string(),
        (Target::Obj, _) => "mesh.obj".to_string(),
        (Target::Atmosphere, "csv") => "profile.csv".to_string(),
        (Target::Atmosphere, _) => "atm.toml".to_string(),
        (Target::Grid, _) => seed_name.clone(),
        (Target::Luminaire, e) => format!("lum.{e}"),
        _ => seed_name.clone(),
    };
    if target == Target::Render {
        bytes = clamp_scene(&bytes);
    }
    let mut files = vec![(file.clone(), bytes)];
    files.extend(context(target, &file, mode));
    Case { files, args: Vec::new(), what: what.join("; "), mode }
}

/// The case that reads `bytes` as the input file `name` (a corpus file) in `mode`.
pub fn case_of_file(target: Target, name: &str, bytes: Vec<u8>, mode: u32) -> Case {
    if target == Target::Cli {
        return crate::cli_mut::case_of_args_file(&bytes);
    }
    let seed_name = match (target, name.rsplit('.').next().unwrap_or("")) {
        (Target::Grid, "mgrid") => "density.mgrid".to_string(),
        (Target::Grid, _) if name.contains("delta") => "delta.mfield".to_string(),
        (Target::Grid, _) => "temperature.mfield".to_string(),
        (Target::Tonemap, _) => "in.exr".to_string(),
        _ => name.to_string(),
    };
    if target == Target::Tonemap {
        return Case {
            files: vec![(seed_name, bytes)],
            args: vec!["--operator".into(), "exposure".into()],
            what: name.into(),
            mode,
        };
    }
    finish(target, seed_name, bytes, vec![name.to_string()], mode)
}

/// Caps what makes a render slow (pixels, photons, samples, bands) in a mutated scene, where
/// those fields are still numbers: the render target stays fast while `scene` checks the
/// unclamped values.
pub fn clamp_scene(bytes: &[u8]) -> Vec<u8> {
    // A scene past morgana's size limit is refused unread, so there is nothing to clamp; its
    // slots (a 100 MB mutant holds tens of millions) would exhaust the worker's memory.
    if bytes.len() as u64 > morgana::error::MAX_TEXT_FILE_BYTES {
        return bytes.to_vec();
    }
    let Ok(src) = std::str::from_utf8(bytes) else { return bytes.to_vec() };
    let caps: &[(&str, f64)] = &[
        ("camera.width", 4.0),
        ("camera.height", 4.0),
        ("integrator.photons", 500.0),
        ("integrator.caustic_photons", 500.0),
        ("integrator.volume_photons", 500.0),
        ("integrator.spp", 1.0),
        ("integrator.gather_rays", 2.0),
        ("integrator.k", 50.0),
        ("integrator.caustic_k", 50.0),
        ("integrator.volume_k", 50.0),
        ("output.bands", 8.0),
    ];
    let mut edits: Vec<(std::ops::Range<usize>, String)> = Vec::new();
    for s in toml_mut::slots(src) {
        let cap = caps.iter().find(|(p, _)| *p == s.path).map(|(_, c)| *c).or_else(|| {
            // Sensor grids and resolutions.
            (s.path.starts_with("sensor[") && (s.path.ends_with(".resolution") || s.path.contains(".resolution[")))
                .then_some(8.0)
        });
        if let Some(cap) = cap
            && let Ok(x) = s.text.replace('_', "").parse::<f64>()
            && x > cap
        {
            edits.push((s.value.clone(), if s.kind == "float" { format!("{cap:?}") } else { format!("{cap}") }));
        }
    }
    // Photon counts the scene does not give default to large ones: add small ones.
    let mut out = src.to_string();
    edits.sort_by_key(|e| std::cmp::Reverse(e.0.start));
    for (r, v) in edits {
        out.replace_range(r, &v);
    }
    // Counts the scene does not give default to large ones (a deleted [integrator] or [camera]
    // renders for minutes): small ones are added where the table is, or with it.
    let given: Vec<String> = toml_mut::slots(&out).into_iter().map(|s| s.path).collect();
    for (table, keys) in [
        ("integrator", &["photons = 500", "caustic_photons = 500", "spp = 1", "gather_rays = 2"][..]),
        ("camera", &["width = 4", "height = 4"][..]),
    ] {
        let missing: Vec<&str> = keys
            .iter()
            .copied()
            .filter(|k| !given.iter().any(|g| *g == format!("{table}.{}", k.split(' ').next().unwrap_or(""))))
            .collect();
        if missing.is_empty() {
            continue;
        }
        let header = format!("[{table}]");
        let lines = missing.join("\n");
        if out.contains(&header) {
            out = out.replacen(&header, &format!("{header}\n{lines}"), 1);
        } else if table == "integrator" {
            out = format!("{out}\n{header}\n{lines}\n");
        }
    }
    out.into_bytes()
}

fn tonemap_case(rng: &mut Pcg64) -> Case {
    let dir = private_dir("exr");
    std::fs::create_dir_all(&dir).ok();
    let p = dir.join("seed.exr");
    let (w, h) = (rng.random_range(1..9), rng.random_range(1..9));
    let poison: Option<f32> = rng.random_bool(0.2).then(|| {
        [f32::NAN, f32::INFINITY, f32::NEG_INFINITY, -1.0, f32::MAX, 1e-45, 65504.0, 0.0][rng.random_range(0..8)]
    });
    let mut what = vec![];
    let made = if rng.random_bool(0.7) {
        let bands = [1, 2, 3, 4, 16, 40, 81][rng.random_range(0..7)];
        let range =
            [(400.0, 700.0), (380.0, 780.0), (300.0, 1100.0), (550.0, 551.0), (1.0, 100_000.0)][rng.random_range(0..5)];
        what.push(format!("spectral {w}x{h}, {bands} bands {:?} nm, poison {poison:?}", range));
        formats::spectral_exr(&p, w, h, bands, range, poison.map(|v| (rng.random_range(0..10_000), v)))
    } else {
        let y = rng.random_bool(0.3);
        what.push(format!("{} {w}x{h}, poison {poison:?}", if y { "luminance" } else { "rgb" }));
        formats::rgb_exr(&p, w, h, poison, y)
    };
    let mut bytes = match made.and_then(|()| std::fs::read(&p).map_err(|e| e.to_string())) {
        Ok(b) => b,
        Err(e) => {
            what.push(format!("seed not written: {e}"));
            Vec::new()
        }
    };
    let n = if rng.random_bool(0.25) { 0 } else { mutation_count(rng) };
    for _ in 0..n {
        let (b, w) = formats::mutate_exr(rng, &bytes);
        bytes = b;
        what.push(w);
    }
    // Options: a valid set, sometimes with a region and CSV.
    let ops = ["exposure", "reinhard", "ward-histogram", "pattanaik"];
    let mut args: Vec<OsString> = vec!["--operator".into(), ops[rng.random_range(0..4)].into()];
    if rng.random_bool(0.3) {
        args.extend(["--region".into(), "0,0,1,1".into(), "--csv".into(), "r.csv".into()]);
    }
    if rng.random_bool(0.2) {
        args.extend(["--adapt-to".into(), ["white", "scene-average", "a", "0.3,0.3"][rng.random_range(0..4)].into()]);
    }
    if rng.random_bool(0.1) {
        args.push("--false-colour".into());
    }
    what.push(format!("{args:?}"));
    Case { files: vec![("in.exr".into(), bytes)], args, what: what.join("; "), mode: 0 }
}

/// Runs a case in this process (the command-line target spawns `morgana`) and judges it.
pub fn run(target: Target, ws: &Workspace, case: &Case, deadline: Duration) -> Outcome {
    let mut written = Vec::new();
    for (name, bytes) in &case.files {
        let p = ws.case.join(name);
        if let Err(e) = std::fs::write(&p, bytes) {
            return Outcome::new(Class::Internal, format!("harness: cannot write {}: {e}", p.display()));
        }
        written.push(name.clone());
    }
    let read: Vec<String> = case.files.iter().map(|(n, _)| n.clone()).collect();
    let result = crate::worker::catching(|| {
        // A self-test of the harness (tests/fuzz_corpus.rs): the case panics or hangs.
        match std::env::var("MORGANA_FUZZ_SELFTEST").as_deref() {
            Ok("panic") => panic!("self-test panic"),
            Ok("hang") => std::thread::sleep(deadline * 20),
            _ => {}
        }
        execute(target, ws, case, &read, deadline)
    });
    let outcome = match result {
        Err(panic) => Outcome::new(Class::Panic, panic),
        Ok(Exec::Done(o)) => o,
        // The tonemap target passes options as a command line: a flag locates its problem.
        Ok(Exec::Lib(r, outputs)) => judge(r, &read, target == Target::Tonemap, &outputs, &case.files),
    };
    ws.settle(outcome, &written, target)
}

/// What a case's execution gave, before judging.
enum Exec {
    /// Judged already (the command line, or a harness problem).
    Done(Outcome),
    /// A library result and the output files to check when it is `Ok`.
    Lib(Result<String, Error>, Vec<PathBuf>),
}

fn judge(
    r: Result<String, Error>,
    read: &[String],
    flags: bool,
    outputs: &[PathBuf],
    inputs: &[(String, Vec<u8>)],
) -> Outcome {
    match r {
        Ok(text) => {
            // A word of the input echoed (a maker named "+inf") is not a number the code made.
            // A GLDF is a zip: its words are in its entries, not in its compressed bytes.
            let texts: Vec<String> = inputs
                .iter()
                .flat_map(|(name, b)| {
                    let entries = if name.ends_with(".gldf") { bytes_of_gldf(b) } else { Vec::new() };
                    std::iter::once(b.clone()).chain(entries.into_iter().map(|(_, e)| e))
                })
                .map(|b| String::from_utf8_lossy(&b).into_owned())
                .collect();
            let echoed = |w: &str| texts.iter().any(|t| t.contains(w));
            let made = |l: &&str| has_non_finite_word(l) && !echoed(&non_finite_words(l));
            if let Some(l) = text.lines().find(made) {
                return Outcome::new(Class::NonFinite, format!("printed: {l}"));
            }
            for o in outputs {
                if let Some(m) = crate::workspace::non_finite_in(o).filter(|m| !echoed(&non_finite_words(m))) {
                    return Outcome::new(Class::NonFinite, m);
                }
            }
            Outcome::ok()
        }
        Err(Error::Internal(m)) => Outcome::new(Class::Internal, m),
        Err(e @ Error::Input(_)) => {
            let msg = e.to_string();
            let class = if locates(&msg, read, flags) { Class::InputLocated } else { Class::InputUnlocated };
            Outcome::new(class, msg)
        }
    }
}

fn check(path: &Path, out: &Path) -> Result<String, Error> {
    morgana::cli::check::run(&morgana::cli::check::CheckArgs {
        scene: Some(path.to_path_buf()),
        out: out.to_path_buf(),
    })
}

fn execute(target: Target, ws: &Workspace, case: &Case, read: &[String], deadline: Duration) -> Exec {
    let c = &ws.case;
    let main = case.files.first().map(|(n, _)| n.clone()).unwrap_or_default();
    let out = c.join("out");
    match target {
        Target::Scene => Exec::Lib(check(&c.join(&main), &out), vec![]),
        Target::Render => {
            let args = morgana::cli::render::RenderArgs {
                scene: Some(c.join(&main)),
                out: Some(out.clone()),
                photons: None,
                seed: None,
                threads: Some(1),
                quiet: true,
                max_map_memory: None,
                max_memory: None,
                max_seconds: None,
                schedule: morgana::distributed::Schedule::Dynamic,
                sun_zenith_deg: Vec::new(),
                stop: Default::default(),
            };
            let r = morgana::cli::render::run(&args);
            let outputs = std::fs::read_dir(&out)
                .map(|d| d.filter_map(|e| e.ok()).map(|e| e.path()).collect())
                .unwrap_or_default();
            Exec::Lib(r, outputs)
        }
        Target::Obj => Exec::Lib(check(&c.join("mesh_scene.toml"), &out), vec![]),
        Target::Luminaire if case.mode == 1 => Exec::Lib(check(&c.join("lum_scene.toml"), &out), vec![]),
        Target::Luminaire => {
            Exec::Lib(morgana::luminaire::inspect_variant(&c.join(&main), Some(&c.join("polar.png")), None), vec![])
        }
        Target::Atmosphere if case.mode == 1 => Exec::Lib(check(&c.join("atm_scene.toml"), &out), vec![]),
        Target::Atmosphere => Exec::Lib(load_atmosphere(&c.join("atm.toml")), vec![]),
        Target::Grid => match main.as_str() {
            "density.mgrid" => Exec::Lib(check(&c.join("density_scene.toml"), &out), vec![]),
            "temperature.mfield" => Exec::Lib(check(&c.join("field_scene.toml"), &out), vec![]),
            _ => Exec::Lib(load_atmosphere(&c.join("delta_atm.toml")), vec![]),
        },
        Target::Tonemap => {
            let mut argv: Vec<OsString> =
                vec!["morgana".into(), "tonemap".into(), c.join(&main).into(), "--out".into(), c.join("o.png").into()];
            for a in &case.args {
                if a == "r.csv" {
                    argv.push(c.join("r.csv").into());
                } else {
                    argv.push(a.clone());
                }
            }
            use clap::Parser;
            #[derive(clap::Parser)]
            struct T {
                #[command(flatten)]
                a: morgana::cli::tonemap::TonemapArgs,
            }
            let args = match T::try_parse_from(argv.iter().skip(1)) {
                Ok(t) => t.a,
                Err(e) => return Exec::Done(Outcome::new(Class::Internal, format!("harness: tonemap arguments: {e}"))),
            };
            Exec::Lib(morgana::cli::tonemap::run_args(&args), vec![c.join("r.csv")])
        }
        Target::Cli => Exec::Done(crate::cli_mut::run(ws, case, read, deadline)),
    }
}

/// Loads an atmosphere and evaluates it at a few heights: every value must be finite.
fn load_atmosphere(path: &Path) -> Result<String, Error> {
    let a = morgana::atmosphere::load(path)?;
    let mut text = String::new();
    for h in [0.0, 1.0, 100.0, 1000.0, 11_000.0, 50_000.0, a.top_m() * 0.999] {
        let p = glam::DVec3::new(0.0, h, 0.0);
        let air = a.air(p);
        let (n, g) = a.n_grad(550.0, p);
        text.push_str(&format!("{h} m: T {} K, p {} Pa, n {n}, grad n {g}\n", air.temperature_k, air.pressure_pa));
    }
    Ok(text)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scene_past_the_size_limit_is_left_unclamped() {
        // Case 1208 of the render target (seed 2) was such a mutant, 106 MB: clamping it listed
        // tens of millions of slots and the worker aborted for memory before morgana saw it.
        let row = "photons = 9999999\n";
        let n = (morgana::error::MAX_TEXT_FILE_BYTES as usize) / row.len() + 1;
        let doc = format!("[integrator]\n{}", row.repeat(n));
        assert!(doc.len() as u64 > morgana::error::MAX_TEXT_FILE_BYTES);
        assert_eq!(clamp_scene(doc.as_bytes()), doc.as_bytes());
        // Below the limit the same field is clamped.
        let small = "[integrator]\nphotons = 9999999\n";
        let clamped = String::from_utf8(clamp_scene(small.as_bytes())).unwrap();
        assert!(clamped.contains("photons = 500") && !clamped.contains("9999999"), "{clamped}");
    }
}
