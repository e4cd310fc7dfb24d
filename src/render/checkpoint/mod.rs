//! Checkpoints of a progressive run (`--resume DIR`): after each pass, rank 0 writes what the
//! passes so far add up to — the running means and spreads of every output
//! ([`super::progressive::Outputs`]), the target's, the history, the passes done and the
//! elapsed time — with the [`Fingerprint`] of the scene and options, to `DIR/`[`FILE_NAME`],
//! atomically (a temporary file renamed into place: a run killed while writing leaves the
//! previous checkpoint). The radii and seeds of pass i are functions of i, the scene's first
//! radii, k, seed and α ([`crate::scene::IntegratorSettings::for_pass`]), all in the
//! fingerprint, so the pass count is their whole state.
//!
//! A run resumed from a checkpoint of pass i continues with pass i + 1 and adds its values to
//! the stored sums in the same order and precision as an uninterrupted run, so its outputs are
//! the same bytes. The checkpoint is kept when the run ends, so a finished run can be extended
//! with more passes.

pub mod codec;
pub mod fingerprint;

use super::adaptive::Spread;
use super::progressive::{Outputs, PassRecord, Scalar};
use crate::error::{Error, Location, Result};
pub use fingerprint::Fingerprint;
use std::path::{Path, PathBuf};

/// The checkpoint's file name in the output directory.
pub const FILE_NAME: &str = "progressive.checkpoint";

/// The first bytes of a checkpoint file (with the layout's version).
const MAGIC: &[u8] = b"morgana progressive checkpoint v2\n";

/// The state of a progressive run after some passes.
#[derive(Clone, Debug)]
pub struct Checkpoint {
    /// What the passes were rendered from.
    pub fingerprint: Fingerprint,
    /// Passes done.
    pub passes: u32,
    /// Every output's running mean and spread.
    pub outputs: Outputs,
    /// The target's running mean and spread.
    pub target: Scalar,
    /// The record of each pass.
    pub history: Vec<PassRecord>,
    /// The spread of the pixels' samples, under adaptive sampling.
    pub spread: Option<Spread>,
}

/// Where a run writes its checkpoints, and the one it resumes from.
#[derive(Clone, Debug)]
pub struct Plan {
    /// The output directory.
    pub dir: PathBuf,
    /// The fingerprint of this run's scene and options.
    pub fingerprint: Fingerprint,
    /// The checkpoint to resume from.
    pub resume: Option<Checkpoint>,
}

impl Checkpoint {
    /// The checkpoint as bytes.
    pub fn encode(&self) -> Vec<u8> {
        encode(&self.fingerprint, (self.passes, &self.target, &self.history), (&self.outputs, self.spread.as_ref()))
    }

    /// The checkpoint from bytes; `Err` says what is wrong with them.
    pub fn decode(bytes: &[u8]) -> codec::Result<Checkpoint> {
        let body = bytes.strip_prefix(MAGIC).ok_or("it is not a morgana checkpoint of this version")?;
        let mut r = codec::Reader::new(body);
        let n = r.len(16)?;
        let parts = (0..n).map(|_| Ok((r.str()?, r.str()?))).collect::<codec::Result<Vec<_>>>()?;
        let passes = r.u32()?;
        let target = Scalar::load(&mut r)?;
        let n = r.len(8)?;
        let history = (0..n).map(|_| PassRecord::load(&mut r)).collect::<codec::Result<Vec<_>>>()?;
        let outputs = Outputs::load(&mut r)?;
        let spread = if r.at_end() { None } else { Some(Spread::load(&mut r)?) };
        if !r.at_end() {
            return Err("it has bytes after its end".into());
        }
        if history.len() != passes as usize || outputs.passes() != passes {
            return Err(format!("it says {passes} passes but holds {} records", history.len()));
        }
        Ok(Checkpoint { fingerprint: Fingerprint(parts), passes, outputs, target, history, spread })
    }

    /// Reads the checkpoint in `dir` (`--resume DIR`) and checks it was made from `now`:
    /// an input error (exit code 2) names what is missing, unreadable or different.
    pub fn read(dir: &Path, now: &Fingerprint) -> Result<Checkpoint> {
        let path = dir.join(FILE_NAME);
        let at = |m: String| Error::input(Some(Location::file(&path)), format!("--resume {}: {m}", dir.display()));
        let bytes = std::fs::read(&path).map_err(|e| {
            at(format!("cannot read the checkpoint ({e}); a progressive run (--passes, --time or --target-rel-error) writes {FILE_NAME} into its --out directory after each pass"))
        })?;
        let c = Checkpoint::decode(&bytes)
            .map_err(|e| at(format!("the checkpoint is damaged ({e}); start afresh without --resume")))?;
        let differs = c.fingerprint.differences(now);
        if !differs.is_empty() {
            return Err(at(format!(
                "the checkpoint was rendered from a different scene or options: {}; resume with the same scene file, files, --photons and --seed, or start afresh without --resume",
                differs.join("; ")
            )));
        }
        Ok(c)
    }
}

/// The bytes of a checkpoint of `passes` passes with these parts (what
/// [`Checkpoint::decode`] reads back), without copying them into a [`Checkpoint`]; the
/// spread of adaptive sampling, when there is one, comes last.
pub fn encode(
    fingerprint: &Fingerprint,
    (passes, target, history): (u32, &Scalar, &[PassRecord]),
    (outputs, spread): (&Outputs, Option<&Spread>),
) -> Vec<u8> {
    let mut w = codec::Writer::default();
    w.bytes.extend_from_slice(MAGIC);
    w.usize(fingerprint.0.len());
    for (name, value) in &fingerprint.0 {
        w.str(name);
        w.str(value);
    }
    w.u32(passes);
    target.save(&mut w);
    w.usize(history.len());
    history.iter().for_each(|r| r.save(&mut w));
    outputs.save(&mut w);
    if let Some(s) = spread {
        s.save(&mut w);
    }
    w.bytes
}

/// Writes checkpoint `bytes` into `dir` atomically (a temporary file renamed into place).
pub fn write(dir: &Path, bytes: &[u8]) -> Result<()> {
    let path = dir.join(FILE_NAME);
    let fail = |e: std::io::Error| Error::internal(format!("cannot write the checkpoint {}: {e}", path.display()));
    let staged = crate::atomic::Staged::new(&path).map_err(fail)?;
    std::fs::write(&staged.temp, bytes).map_err(fail)?;
    staged.commit().map_err(fail)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::sensor::{ProfileReading, ProfileRow, Reading};

    /// Pass `i`'s made-up outputs: 3 image values, a 2-point reading, a 2-row profile.
    fn pass(i: u32) -> (Vec<f32>, Vec<Reading>, Vec<ProfileReading>) {
        let x = f64::from(i);
        let reading = Reading {
            name: "desk".into(),
            quantity: "illuminance".into(),
            unit: "lx".into(),
            nx: 2,
            ny: 1,
            points: vec![glam::DVec3::ZERO, glam::DVec3::X],
            columns: vec![("E_lx".into(), vec![x.sin(), 1.0 / (x + 1.0)])],
        };
        let row = |d: f64| ProfileRow {
            depth_m: d,
            wavelength_nm: 500.0,
            ed: x.cos() + d,
            eu: 0.1 * x,
            eod: 1.0,
            eou: x,
            lu: x * x,
        };
        let profile = ProfileReading {
            name: "profile".into(),
            rows: vec![row(1.0), row(5.0)],
            surface: vec![[500.0, 0.5, 0.01 * x, 0.02, x.sqrt()]],
            std_error: None,
        };
        (vec![0.1 * i as f32, 1.0 / (i as f32 + 3.0), 7.0], vec![reading], vec![profile])
    }

    #[test]
    fn a_checkpoint_read_back_continues_exactly_as_the_run_it_holds() {
        for stored in [1, 3] {
            let mut run = Outputs::default();
            let mut target = Scalar::default();
            // The three-pass run also tracks its pixels' band means (`target = "pixels"`).
            let pixels = |run: &mut Outputs, d: &[f32]| {
                if stored == 3 {
                    run.add_pixels(crate::render::progressive::band_means(d, 1));
                }
            };
            for i in 0..stored {
                let (d, s, p) = pass(i);
                pixels(&mut run, &d);
                run.add(d, s, p);
                target.add(f64::from(i).exp());
            }
            let fingerprint = Fingerprint(vec![("seed".into(), "3".into())]);
            let history = (0..stored)
                .map(|i| PassRecord {
                    pass: i + 1,
                    elapsed_s: f64::from(i) / 3.0,
                    seconds: 0.1,
                    k: 50,
                    max_radius_m: 0.5,
                    target_mean: 1.0,
                    rel_error: (i > 0).then_some(0.25),
                })
                .collect();
            let mut spread = Spread::default();
            spread.add(&[1.5, 0.0, 2.0], &[4, 1, 9]);
            let c = Checkpoint {
                fingerprint: fingerprint.clone(),
                passes: stored,
                outputs: run.clone(),
                target,
                history,
                spread: (stored == 3).then_some(spread),
            };
            let back = Checkpoint::decode(&c.encode()).expect("a checkpoint it wrote");
            assert_eq!(back.fingerprint, fingerprint);
            assert_eq!(back.spread, c.spread);
            assert_eq!(
                (back.passes, back.target.mean(), back.target.rel_error()),
                (stored, target.mean(), target.rel_error())
            );
            let (mut a, mut b) = (run, back.outputs);
            for i in stored..stored + 2 {
                let (d, s, p) = pass(i);
                pixels(&mut a, &d);
                pixels(&mut b, &d);
                a.add(d.clone(), s.clone(), p.clone());
                b.add(d, s, p);
            }
            assert_eq!(a.pixel_rel_error().map(f64::to_bits), b.pixel_rel_error().map(f64::to_bits));
            assert_eq!(a.pixel_rel_error().is_some(), stored == 3);
            let (a, b) = (a.finish(), b.finish());
            assert_eq!(
                a.image.iter().map(|v| v.to_bits()).collect::<Vec<_>>(),
                b.image.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            );
            assert_eq!(a.image_se, b.image_se);
            assert_eq!(a.sensors, b.sensors);
            assert_eq!(a.profiles, b.profiles);
            assert!(a.profiles[0].std_error.is_some());
            let mut damaged = c.encode();
            damaged.pop();
            assert!(Checkpoint::decode(&damaged).is_err());
        }
    }
}
