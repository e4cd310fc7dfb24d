//! Rendering: the photon pass ([`photon_pass`]), then the eye pass ([`eye`]) over the pixels.
//!
//! Pixels are independent tasks with their own random streams derived from (seed, pixel), and
//! each pixel's samples are summed in a fixed order, so the image is identical for any number
//! of threads — and of ranks: [`render_on`] runs the same passes split across the processes of
//! a [`Comm`] ([`crate::distributed`]); [`render`] is that with one process.

pub mod adaptive;
pub mod checkpoint;
mod direct;
pub mod eye;
mod lanes;
pub mod memory;
mod path;
pub mod photon_pass;
pub mod progress;
pub mod progressive;
pub mod sensors;
pub mod stats;

pub use lanes::Lanes;
pub use memory::{MemoryEstimate, MemoryLimit};
pub use stats::{MapReport, PhaseTime, Phases, RayCounts, RenderStats};

use crate::distributed::{self, Comm, DistributedReport, Rank};
use crate::error::Result;
use crate::raypath::RayState;
use crate::rng::{Rng, Stream};
use crate::sampling::ScrambledSobol2;
use crate::scene::progressive::Target;
use crate::scene::{Method, Scene};
use crate::spectrum::SpectralImage;
use crate::spectrum::colour::BandsToColour;
use crate::timing::Span;
use eye::{EyeTracer, Scratch};
use rayon::prelude::*;

/// How to run a render.
#[derive(Clone, Debug, Default)]
pub struct RenderOptions {
    /// Hide progress bars.
    pub quiet: bool,
    /// The memory the run may use, checked before the photon maps are allocated.
    pub max_memory: MemoryLimit,
    /// When the run must stop (`--max-seconds`): a render still running then stops cleanly
    /// with an error saying how far it got, and writes nothing.
    pub deadline: Option<std::time::Instant>,
    /// A flag another thread may raise to stop the run as the deadline would (Ctrl-C in the
    /// Python package); the error then says the run was cancelled.
    pub cancel: Option<std::sync::Arc<std::sync::atomic::AtomicBool>>,
    /// Where the progress of the current phase can be read from another thread (the Python
    /// package's progress bar); with it, no progress bar is drawn on stderr.
    pub observer: Option<std::sync::Arc<progress::Observer>>,
    /// When the run started, for the `time` budget of progressive passes (default: when
    /// [`render_on`] is called).
    pub started: Option<std::time::Instant>,
    /// Where rank 0 writes a checkpoint after each pass, and the checkpoint to resume from
    /// (`None`: no checkpoints; on ranks other than 0 only its presence matters).
    pub checkpoint: Option<checkpoint::Plan>,
}

impl RenderOptions {
    /// When the run must stop: its deadline or its cancel flag.
    pub fn stop(&self) -> crate::timing::Stop<'_> {
        crate::timing::Stop { deadline: self.deadline, cancel: self.cancel.as_deref() }
    }
}

/// A finished render.
pub struct Rendered {
    /// The spectral radiance image, W m⁻² sr⁻¹ nm⁻¹ per band.
    pub image: SpectralImage,
    /// The standard error of each band value of the image, from the spread of the progressive
    /// passes (row-major, the bands of a pixel together; `None` after one pass).
    pub std_error: Option<Vec<f32>>,
    /// Timings, photon and ray counts, for `report.json`.
    pub stats: RenderStats,
    /// What the scene's sensors measured.
    pub sensors: Vec<crate::sensor::Reading>,
    /// What the scene's ocean profile sensors measured.
    pub profiles: Vec<crate::sensor::ProfileReading>,
}

/// Renders `scene` on the current rayon thread pool.
pub fn render(scene: &Scene, opts: &RenderOptions) -> Rendered {
    match render_on(&Comm::local(), scene, opts, &distributed::Options::default()) {
        Ok(Some(r)) => r,
        // One rank is rank 0, and without a map-memory budget nothing can fail.
        Ok(None) | Err(_) => unreachable!("a local render without a memory budget always returns its image"),
    }
}

/// Renders `scene` on every rank of `comm` (each on its current rayon pool): the progressive
/// passes the scene asks for ([`progressive`]), each with its photon passes and eye pass split
/// across ranks (see [`crate::distributed`]); the image, the same for any number of ranks, is
/// returned on rank 0 (`None` on the others). Collective. Fails, on every rank, if the photon
/// maps would not fit in `dist.map_memory`.
pub fn render_on(
    comm: &Comm,
    scene: &Scene,
    opts: &RenderOptions,
    dist: &distributed::Options,
) -> Result<Option<Rendered>> {
    let started = opts.started.unwrap_or_else(std::time::Instant::now);
    let mut rank = Rank::new(comm, *dist);
    let quiet = opts.quiet || !comm.is_root();
    let mut stats = RenderStats::default();
    stats.warnings.extend(crate::scene::twilight::warning(scene));
    let settings = crate::photon::PassSettings::of(scene);
    let mut est = memory::estimate(scene, &settings, comm.size());
    distributed::fault::agree(comm, memory::check(&mut est, opts.max_memory))?;
    let p = &scene.integrator.progressive;
    let mut run = Run::start(p, opts.checkpoint.as_ref().and_then(|c| c.resume.clone()));
    // Rank 0 alone holds the checkpoint: it tells the others which pass comes first.
    let done = (run.report.history.len() as u32).to_le_bytes().to_vec();
    let first = u32::from_le_bytes(comm.broadcast(done).try_into().unwrap_or([0; 4]));
    let mut stop = progressive::decide(p, first, 0.0, 0.0, run.rel_error()).filter(|_| first > 0);
    let mut ranks = Vec::new();
    let mut pass = first;
    while comm.broadcast(vec![u8::from(stop.is_none())]).first() == Some(&1) {
        let s = scene.integrator.for_pass(pass);
        let t = std::time::Instant::now();
        let counts = sample_counts(comm, scene, &run.spread);
        let (pass_stats, out, pass_ranks) = match one_pass(&mut rank, scene, (&s, counts.as_deref()), opts)? {
            Pass::Done(stats, out, ranks) => (*stats, out, ranks),
            Pass::Cut(progress) => {
                stop = Some(cut(opts, pass, progress)?);
                break;
            }
        };
        rank.budget.release_all();
        stats.merge(pass_stats);
        ranks = pass_ranks;
        if let Some(out) = out {
            let seconds = t.elapsed().as_secs_f64();
            stop = run.add(scene, (pass, &s), (out, counts.as_deref()), (started.elapsed().as_secs_f64(), seconds));
        }
        if let Some(plan) = &opts.checkpoint {
            distributed::fault::agree(comm, run.write_checkpoint(plan, pass + 1))?;
        }
        if let Some(r) = run.report.history.last().filter(|_| !quiet && stop.is_none()) {
            let e = r.rel_error.map_or(String::new(), |e| format!(", relative standard error {e:.2e}"));
            eprintln!("morgana: pass {} done at {:.1} s{e}", r.pass, r.elapsed_s);
        }
        pass += 1;
    }
    if let Some(cut) = stop.as_ref().filter(|s| s.rule == progressive::Rule::MaxSeconds) {
        stats.warnings.push(cut.why.clone());
    }
    let rel_error = run.rel_error();
    let mut report = run.report;
    report.passes = report.history.len() as u32;
    report.stopped = stop;
    report.checkpoint = opts.checkpoint.as_ref().map(|_| checkpoint::FILE_NAME.to_string());
    let outputs = run.outputs;
    stats.memory = est;
    stats.memory.measured_peak_bytes = crate::memory::peak_rss_bytes();
    if !comm.is_root() {
        return Ok(None);
    }
    stats.distributed = Some(DistributedReport::new(comm.kind(), dist.schedule, ranks));
    report.rel_error = rel_error;
    report.convergence_fit = progressive::fit(&report.history);
    let done = outputs.finish();
    report.image_mean_rel_error = done.image_se.as_ref().and_then(|se| progressive::mean_rel_error(&done.image, se));
    stats.progressive = report;
    let t = Span::start();
    let image = to_image(scene, done.image);
    stats.phases.add("colour conversion", t);
    Ok(Some(Rendered { image, std_error: done.image_se, stats, sensors: done.sensors, profiles: done.profiles }))
}

/// A progressive run's state on rank 0: every output's running sums, the target's, the
/// spread of the pixels' samples (under adaptive sampling), the report with the history, and
/// the elapsed time of the passes taken from a checkpoint.
struct Run<'a> {
    p: &'a crate::scene::progressive::Progressive,
    outputs: progressive::Outputs,
    target: progressive::Scalar,
    spread: Option<adaptive::Spread>,
    report: progressive::ProgressiveReport,
    resumed_s: f64,
}

impl<'a> Run<'a> {
    /// A fresh run, or the run a checkpoint holds.
    fn start(p: &'a crate::scene::progressive::Progressive, resume: Option<checkpoint::Checkpoint>) -> Run<'a> {
        let mut report = progressive::ProgressiveReport {
            alpha: p.alpha,
            target: progressive::target_label(&p.target),
            ..Default::default()
        };
        let fresh = p.adaptive.then(adaptive::Spread::default);
        let Some(c) = resume else {
            let (outputs, target) = Default::default();
            return Run { p, outputs, target, spread: fresh, report, resumed_s: 0.0 };
        };
        report.resumed_after_pass = Some(c.passes);
        let resumed_s = c.history.last().map_or(0.0, |r| r.elapsed_s);
        report.history = c.history;
        let spread = c.spread.or(fresh).filter(|_| p.adaptive);
        Run { p, outputs: c.outputs, target: c.target, spread, report, resumed_s }
    }

    /// Adds pass `pass`'s outputs, run with settings `s` and the pixels' sample `counts`
    /// (under adaptive sampling), at `elapsed` s into this run after `seconds` of work; says
    /// whether the run stops (`elapsed` counts this run for the `time` budget, and the
    /// checkpoint's time too in the history).
    fn add(
        &mut self,
        scene: &Scene,
        (pass, s): (u32, &crate::scene::IntegratorSettings),
        (out, counts): (PassOutput, Option<&[u32]>),
        (elapsed, seconds): (f64, f64),
    ) -> Option<progressive::Stop> {
        if let (Some(spread), Some(ss), Some(counts)) = (&mut self.spread, &out.spread, counts) {
            spread.add(ss, counts);
            self.report.adaptive = Some(adaptive::AdaptiveReport::of(counts, scene.integrator.spp));
        }
        let image = (&out.data[..], scene.camera.width, scene.bands.count);
        let v = progressive::target_value(&self.p.target, image, &out.sensors, &out.profiles);
        self.target.add(v);
        let pixels = (self.p.target == Target::Pixels).then(|| progressive::band_means(&out.data, scene.bands.count));
        self.outputs.add(out.data, out.sensors, out.profiles);
        if let Some(means) = pixels {
            self.outputs.add_pixels(means);
        }
        let total = self.resumed_s + elapsed;
        let rel = self.rel_error();
        self.report.history.push(progressive::record(pass, s, (total, seconds), (&self.target, rel)));
        progressive::decide(self.p, pass + 1, elapsed, seconds, rel)
    }

    /// The relative standard error the stopping rule sees: of the target's mean, or under
    /// `target = "pixels"` the pixels' ([`progressive::pixel_rel_error`]).
    fn rel_error(&self) -> Option<f64> {
        match self.p.target {
            Target::Pixels => self.outputs.pixel_rel_error(),
            _ => self.target.rel_error(),
        }
    }

    /// Writes the checkpoint of the `passes` done into the plan's directory (rank 0; the
    /// other ranks hold no outputs and write nothing).
    fn write_checkpoint(&self, plan: &checkpoint::Plan, passes: u32) -> Result<()> {
        if self.outputs.passes() != passes {
            return Ok(());
        }
        let state = (passes, &self.target, &self.report.history[..]);
        let bytes = checkpoint::encode(&plan.fingerprint, state, (&self.outputs, self.spread.as_ref()));
        checkpoint::write(&plan.dir, &bytes)
    }
}

/// The stop of a run whose deadline (`--max-seconds`) cut pass `pass` (0-based) short, saying
/// how far it got: the passes before it are kept. With no pass finished, or when the run was
/// cancelled, the error of [`out_of_time`].
fn cut(opts: &RenderOptions, pass: u32, progress: String) -> Result<progressive::Stop> {
    if pass == 0 || opts.stop().cancelled() {
        return Err(out_of_time(opts, progress));
    }
    Ok(progressive::Stop {
        rule: progressive::Rule::MaxSeconds,
        why: format!(
            "the time budget (--max-seconds) ran out in pass {} {progress}; the {pass} passes finished before it are kept",
            pass + 1
        ),
    })
}

/// What one pass produced: its statistics, its outputs on rank 0 and every rank's report, or,
/// when the deadline or a cancel cut it short, how far it got.
enum Pass {
    Done(Box<RenderStats>, Option<PassOutput>, Vec<distributed::RankReport>),
    Cut(String),
}

/// What one pass produced on rank 0: the image's band values, the spread of each pixel's
/// samples (under adaptive sampling: see [`adaptive::PixelSpread`]) and the readings.
struct PassOutput {
    data: Vec<f32>,
    spread: Option<Vec<f32>>,
    sensors: Vec<crate::sensor::Reading>,
    profiles: Vec<crate::sensor::ProfileReading>,
}

/// One progressive pass with settings `s` and the pixels' sample `counts` (`None`: `spp`
/// each): photon maps, eye pass and sensors (`opts`: progress, deadline and cancel flag).
/// Returns the pass's statistics, its outputs on rank 0, and every rank's report. Collective.
fn one_pass(
    rank: &mut Rank,
    scene: &Scene,
    (s, counts): (&crate::scene::IntegratorSettings, Option<&[u32]>),
    opts: &RenderOptions,
) -> Result<Pass> {
    let quiet = opts.quiet || !rank.comm.is_root();
    let (bars, stop) = (progress::Bars { quiet, observer: opts.observer.as_deref() }, opts.stop());
    let mut stats = RenderStats::default();
    rank.report.photons.clear();
    let t = Span::start();
    if scene.world.media.iter().fold(false, |any, m| m.build_column_tables() | any) {
        stats.phases.add("column tables", t);
    }
    let maps = photon_pass::build(rank, scene, s, bars, stop, &mut stats.phases, &mut stats.maps)?;
    let stopped: u64 = stats.maps.iter().map(|m| m.stats.stopped_batches).sum();
    if stopped > 0 {
        let left: Vec<String> = stats.maps.iter().map(|m| format!("{} map {} photons", m.map, m.emitted)).collect();
        return Ok(Pass::Cut(format!(
            "during the photon pass ({stopped} batches of {} photons not shot; passes: {})",
            crate::photon::BATCH,
            left.join(", ")
        )));
    }
    for m in stats.maps.iter().filter(|m| m.emitted > 0 && m.stored == 0) {
        stats.warnings.push(format!(
            "the {} photon map stored none of its {} photons: they all escaped or were absorbed before reaching what stores them, so the image lacks that light (check the lights' positions, directions and targets)",
            m.map, m.emitted
        ));
    }
    if let Some(c) = &maps.irradiance {
        stats.irradiance_points = c.len() as u64;
        stats.irradiance_memory_bytes = c.memory_bytes() as u64;
    }
    let t = Span::start();
    let (data, work, curved) = eye_pass(rank, scene, (s, counts), &maps, bars, stop);
    stats.phases.add("eye pass", t);
    rank.report.eye = work;
    rank.report.eye_curved = curved;
    let ranks = rank.gather_reports(&stats.phases);
    let stopped_rows: u64 = ranks.iter().map(|r| r.eye.rays.stopped_rows).sum();
    if stopped_rows > 0 {
        let h = scene.camera.height;
        return Ok(Pass::Cut(format!(
            "during the eye pass ({} of {h} rows rendered; the photon maps were complete)",
            h as u64 - stopped_rows.min(h as u64)
        )));
    }
    let Some(data) = data else { return Ok(Pass::Done(Box::new(stats), None, ranks)) };
    let (data, spread) = match counts {
        Some(_) => {
            let (image, spread) = split_rows(data, scene.camera.width * scene.bands.count, scene.camera.width);
            (image, Some(spread))
        }
        None => (data, None),
    };
    for r in &ranks {
        stats.rays.add(&r.eye.rays);
        stats.eye_curved.add(&r.eye_curved);
    }
    let t = Span::start();
    let sensors = sensors::evaluate_all(scene, s, &maps);
    let profiles = sensors::evaluate_profiles(scene, s.seed, &maps);
    if !sensors.is_empty() || !profiles.is_empty() {
        stats.phases.add("sensors", t);
    }
    Ok(Pass::Done(Box::new(stats), Some(PassOutput { data, spread, sensors, profiles }), ranks))
}

/// The error of a run whose time budget ran out or that was cancelled: exit code 1, nothing
/// written.
fn out_of_time(opts: &RenderOptions, progress: String) -> crate::error::Error {
    let why = if opts.stop().cancelled() { "the run was cancelled" } else { "the time budget (--max-seconds) ran out" };
    crate::error::Error::internal(format!("{why} {progress}; no output was written"))
}

/// The eye samples of each pixel in the next pass under adaptive sampling (`None`: `spp`
/// each, and no spread measured): rank 0 decides from its sums ([`adaptive::counts`]) and
/// sends them to every rank. Collective when the scene asks for adaptive sampling.
fn sample_counts(comm: &Comm, scene: &Scene, spread: &Option<adaptive::Spread>) -> Option<Vec<u32>> {
    let spread = spread.as_ref()?;
    let (w, h) = (scene.camera.width, scene.camera.height);
    let mine: Vec<u8> = if comm.is_root() {
        adaptive::counts(spread, (w, h), scene.integrator.spp).iter().flat_map(|n| n.to_le_bytes()).collect()
    } else {
        Vec::new()
    };
    let bytes = comm.broadcast(mine);
    Some(bytes.chunks_exact(4).map(|c| u32::from_le_bytes([c[0], c[1], c[2], c[3]])).collect())
}

/// Rows of `image` values followed by `extra` values, split into the two images.
fn split_rows(data: Vec<f32>, image: usize, extra: usize) -> (Vec<f32>, Vec<f32>) {
    let rows = data.len() / (image + extra).max(1);
    let (mut a, mut b) = (Vec::with_capacity(rows * image), Vec::with_capacity(rows * extra));
    for row in data.chunks_exact(image + extra) {
        a.extend_from_slice(&row[..image]);
        b.extend_from_slice(&row[image..]);
    }
    (a, b)
}

/// This rank's part of the eye pass with the pixels' sample `counts` (`None`: `spp` each):
/// the image's band averages (row-major, `bands.count` per pixel; with `counts`, each row
/// followed by its pixels' spreads, [`adaptive::PixelSpread::sum_sq`]) on rank 0, this rank's
/// work, and the integrator work along its curved eye paths.
fn eye_pass(
    rank: &Rank,
    scene: &Scene,
    (s, counts): (&crate::scene::IntegratorSettings, Option<&[u32]>),
    maps: &photon_pass::Maps,
    bars: progress::Bars,
    stop: crate::timing::Stop,
) -> (Option<Vec<f32>>, distributed::eye::EyeWork, crate::raypath::CurvedWorkTotals) {
    let (w, h) = (scene.camera.width, scene.camera.height);
    let nb = scene.bands.count;
    let tracer = Tracer::new(scene, s, maps);
    let ranks = rank.comm.size();
    progress::note(
        bars.quiet,
        ranks,
        &format!("eye pass: {h} rows over {ranks} ranks, {:?} leases", rank.options.schedule),
    );
    let pb = bars.bar(h as u64, "eye pass");
    let row_values = if counts.is_some() { w * (nb + 1) } else { w * nb };
    let render_rows = |rows: std::ops::Range<usize>| -> (Vec<f32>, RayCounts) {
        let done: Vec<(Vec<f32>, RayCounts)> = rows
            .into_par_iter()
            .map_init(Scratch::default, |sc, y| {
                let before = sc.rays;
                let mut row = vec![0f32; row_values];
                if stop.reached() {
                    pb.inc(1);
                    return (row, RayCounts { stopped_rows: 1, ..RayCounts::default() });
                }
                for x in 0..w {
                    let n = counts.map_or(scene.integrator.spp, |c| c[y * w + x] as usize);
                    let (px, spread) = pixel((scene, s.seed), &tracer, (x, y), (n, counts.is_some()), sc);
                    for b in 0..nb {
                        row[x * nb + b] = px[b] as f32;
                    }
                    if let Some(ss) = spread {
                        row[w * nb + x] = ss as f32;
                    }
                }
                pb.inc(1);
                (row, sc.rays.since(&before))
            })
            .collect();
        let mut data = Vec::with_capacity(done.len() * w * nb);
        let mut rays = RayCounts::default();
        for (row, r) in done {
            data.extend(row);
            rays.add(&r);
        }
        (data, rays)
    };
    let out = distributed::eye::run(rank.comm, rank.options.schedule, h, row_values, &render_rows, &|n| pb.inc(n));
    pb.finish_and_clear();
    let curved = match &tracer {
        Tracer::PhotonMap(t) => t.curved_work(),
        Tracer::Path(t) => t.curved_work(),
    };
    (out.data, out.work, curved)
}

/// The eye-pass algorithm the scene asks for.
enum Tracer<'a> {
    PhotonMap(Box<EyeTracer<'a>>),
    Path(Box<path::PathTracer<'a>>),
}

impl<'a> Tracer<'a> {
    fn new(scene: &'a Scene, s: &crate::scene::IntegratorSettings, maps: &'a photon_pass::Maps) -> Tracer<'a> {
        match scene.integrator.method {
            Method::PhotonMap => Tracer::PhotonMap(Box::new(EyeTracer::new(scene, s, maps))),
            Method::Path => Tracer::Path(Box::new(path::PathTracer::new(scene))),
        }
    }
}

/// The band averages of pixel (`x`, `y`): the mean over `n` samples, drawn from the pass's
/// `seed`; with `spread`, also the spread of the samples ([`adaptive::PixelSpread`]).
/// The samples' positions in the pixel are the first `n` points of an Owen-scrambled Sobol'
/// sequence, scrambled afresh for each pixel and pass ([`ScrambledSobol2`]): each is uniform in
/// the pixel, so the mean stays unbiased and the passes independent, but an edge across the
/// pixel (a glint, a silhouette) no longer adds noise falling only as 1/√n. So are the points
/// sample i's first shadow rays sample on the lights (where the photon-map eye pass meets a
/// diffuse surface, or the path tracer first estimates next events; a second scrambled
/// sequence, point i): a penumbra's noise falls faster too. The
/// wavelength
/// jitter is stratified over the `n` samples (sample i draws u in [i/n, (i + 1)/n)) for the same
/// reason: a band's smooth spectral slope (Rayleigh's λ⁻⁴ across a 40 nm band: ±14 %).
fn pixel(
    (scene, seed): (&Scene, u64),
    tracer: &Tracer,
    (x, y): (usize, usize),
    (n, spread): (usize, bool),
    sc: &mut Scratch,
) -> ([f64; crate::spectrum::MAX_BANDS], Option<f64>) {
    let mut rng = Rng::for_task(seed, Stream::Eye, (y * scene.camera.width + x) as u64);
    let film = Lanes::film_weight(&scene.bands, scene.sampling);
    let weight = film / n as f64;
    let mut acc = [0.0; crate::spectrum::MAX_BANDS];
    let mut spread = spread.then(|| adaptive::PixelSpread::new(scene.bands.count));
    let positions = ScrambledSobol2::new(&mut rng);
    let on_lights = ScrambledSobol2::new(&mut rng);
    for i in 0..n {
        let [jx, jy] = positions.point(i as u32);
        let Some(ray) = scene.camera.ray(x as f64 + jx, y as f64 + jy) else {
            if let Some(sp) = &mut spread {
                sp.add(&[0.0; crate::spectrum::MAX_BANDS]);
            }
            continue;
        };
        let lanes = Lanes::new(&scene.bands, scene.sampling, (i as f64 + rng.uniform()) / n as f64);
        let state = RayState { position: ray.origin, dir: ray.dir, wavelength_nm: None, medium: scene.camera_medium };
        let l = match tracer {
            Tracer::PhotonMap(t) => t.camera_radiance(&state, &lanes, Some(on_lights.point(i as u32)), &mut rng, sc),
            Tracer::Path(t) => {
                t.camera_radiance(&state, &lanes, Some(on_lights.point(i as u32)), &mut rng, &mut sc.rays)
            }
        };
        for i in 0..lanes.len {
            acc[lanes.band[i] as usize] += weight * l[i];
        }
        if let Some(sp) = &mut spread {
            let mut one = [0.0; crate::spectrum::MAX_BANDS];
            for i in 0..lanes.len {
                one[lanes.band[i] as usize] += film * l[i];
            }
            sp.add(&one);
        }
    }
    (acc, spread.map(|sp| sp.sum_sq()))
}

fn to_image(scene: &Scene, data: Vec<f32>) -> SpectralImage {
    let nb = scene.bands.count;
    let conv = BandsToColour::new(&scene.bands);
    let rgb: Vec<f32> = data
        .par_chunks(nb)
        .flat_map_iter(|px| {
            let v: Vec<f64> = px.iter().map(|x| *x as f64).collect();
            conv.linear_srgb(&v).map(|c| c as f32)
        })
        .collect();
    SpectralImage { width: scene.camera.width, height: scene.camera.height, bands: scene.bands, data, rgb }
}
