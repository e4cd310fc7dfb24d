//! Measures the sun's disc in a rendered spectral EXR: its vertical and horizontal extent (the
//! flattening of a setting sun) in luminance and in every band, where each band's upper and
//! lower limb lie (the dispersion), and the colours of the rim pixels.
//!
//! ```sh
//! morgana-sun-disc out/sunset_sea.exr --fov-deg 0.75 [--threshold 1e-3]
//! ```
//!
//! The disc is the set of pixels brighter than `threshold` × the image's maximum (the sun is
//! ~10⁵ times brighter than sky or sea, so any threshold from 10⁻⁴ to 10⁻¹ finds the same disc).
//! Along a row or column the extent is measured to a fraction of a pixel: a pixel on the edge,
//! partly covered by the disc, holds b + f·(d − b) with d the disc's level just inside and b the
//! background just outside, so its coverage is f = (v − b)/(d − b) and the extent is the number
//! of fully covered pixels plus the fractions at both ends. The horizontal extent is the mean
//! over the three rows around the widest; the vertical the mean over the three columns around
//! the disc's centroid. Their ratio is the flattening, to compare with the ratio that
//! `morgana refraction` computes for the sun's limbs (0.847 for USA76 with the lower limb at
//! apparent 0°). Angles: pixels are `fov_deg / height` degrees (the pinhole's tangent scale
//! differs from that by < 10⁻⁵ within 0.5° of the axis).

use morgana::spectrum::colour::xyz_to_linear_srgb;
use morgana::tonemap::exr_read::{parse_emissive_wavelength_nm, read_exr};
use std::path::PathBuf;
use std::process::ExitCode;

/// A row-major image of one quantity.
struct Plane {
    width: usize,
    height: usize,
    v: Vec<f64>,
}

impl Plane {
    fn row(&self, y: usize) -> Vec<f64> {
        self.v[y * self.width..(y + 1) * self.width].to_vec()
    }
    fn column(&self, x: usize) -> Vec<f64> {
        (0..self.height).map(|y| self.v[y * self.width + x]).collect()
    }
}

/// The extent of the longest run above `threshold` in a profile, to a fraction of a pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
struct Extent {
    /// Edge positions in pixels from the profile's start (the first pixel spans [0, 1)).
    start: f64,
    end: f64,
}

impl Extent {
    fn length(&self) -> f64 {
        self.end - self.start
    }
}

/// The longest run of values above `threshold`, as (first, last) indices.
fn longest_run(p: &[f64], threshold: f64) -> Option<(usize, usize)> {
    let mut best: Option<(usize, usize)> = None;
    let mut start = None;
    for i in 0..=p.len() {
        let inside = i < p.len() && p[i] > threshold;
        match (inside, start) {
            (true, None) => start = Some(i),
            (false, Some(s)) => {
                if best.is_none_or(|(a, b)| i - 1 - s > b - a) {
                    best = Some((s, i - 1));
                }
                start = None;
            }
            _ => {}
        }
    }
    best
}

/// Coverage of pixel `i` between background `b` and disc level `d`, clamped to [0, 1].
fn coverage(p: &[f64], i: Option<usize>, b: f64, d: f64) -> f64 {
    match i.and_then(|i| p.get(i)) {
        Some(v) if d > b => ((v - b) / (d - b)).clamp(0.0, 1.0),
        _ => 0.0,
    }
}

/// The mean of `p` over indices `lo..=hi` clipped to the profile; `None` when empty.
fn mean(p: &[f64], lo: isize, hi: isize) -> Option<f64> {
    let lo = lo.max(0) as usize;
    let hi = (hi.min(p.len() as isize - 1)).max(-1);
    if hi < lo as isize {
        return None;
    }
    let s = &p[lo..=hi as usize];
    Some(s.iter().sum::<f64>() / s.len() as f64)
}

/// The sub-pixel extent of the longest run above `threshold` (see the module docs).
fn extent(p: &[f64], threshold: f64) -> Option<Extent> {
    let (i0, i1) = longest_run(p, threshold)?;
    let (a, b) = (i0 as isize, i1 as isize);
    // Disc level two to four pixels inside each end (the middle of the run if it is short).
    let mid = (a + b) / 2;
    let d_start = mean(p, (a + 2).min(mid), (a + 4).min(mid))?;
    let d_end = mean(p, (b - 4).max(mid), (b - 2).max(mid))?;
    // Background two to four pixels outside (none beyond the image: 0).
    let bg_start = mean(p, a - 4, a - 2).unwrap_or(0.0);
    let bg_end = mean(p, b + 2, b + 4).unwrap_or(0.0);
    let before = i0.checked_sub(1);
    let start = i0 as f64 + (1.0 - coverage(p, Some(i0), bg_start, d_start)) - coverage(p, before, bg_start, d_start);
    let end = (i1 + 1) as f64 - (1.0 - coverage(p, Some(i1), bg_end, d_end)) + coverage(p, Some(i1 + 1), bg_end, d_end);
    Some(Extent { start, end })
}

/// The disc in one plane: extents along the rows around the widest and the columns around
/// the centroid.
#[derive(Debug)]
struct Disc {
    horizontal: f64,
    vertical: Extent,
    centre_x: usize,
}

fn measure(plane: &Plane, threshold_fraction: f64) -> Option<Disc> {
    let max = plane.v.iter().copied().fold(0.0, f64::max);
    let t = threshold_fraction * max;
    let rows: Vec<f64> = (0..plane.height).map(|y| extent(&plane.row(y), t).map_or(0.0, |e| e.length())).collect();
    let widest = (0..plane.height).max_by(|a, b| rows[*a].total_cmp(&rows[*b]))?;
    let horizontal = mean(&rows, widest as isize - 1, widest as isize + 1)?;
    let (mut sx, mut n) = (0.0, 0.0);
    for (i, v) in plane.v.iter().enumerate() {
        if *v > t {
            sx += (i % plane.width) as f64 + 0.5;
            n += 1.0;
        }
    }
    let centre_x = (sx / n).floor() as usize;
    let columns: Vec<Extent> = (centre_x.saturating_sub(1)..=(centre_x + 1).min(plane.width - 1))
        .filter_map(|x| extent(&plane.column(x), t))
        .collect();
    let k = columns.len() as f64;
    let vertical = Extent {
        start: columns.iter().map(|e| e.start).sum::<f64>() / k,
        end: columns.iter().map(|e| e.end).sum::<f64>() / k,
    };
    (k > 0.0).then_some(Disc { horizontal, vertical, centre_x })
}

/// The spectral bands of an EXR as planes, by wavelength.
fn bands(path: &std::path::Path) -> Result<Vec<(f64, Plane)>, String> {
    let image = exr::prelude::read_all_flat_layers_from_file(path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut out = Vec::new();
    for layer in &image.layer_data {
        let (width, height) = (layer.size.0, layer.size.1);
        for c in &layer.channel_data.list {
            if let Some(nm) = parse_emissive_wavelength_nm(&c.name.to_string()) {
                let v = c.sample_data.values_as_f32().map(f64::from).collect();
                out.push((nm, Plane { width, height, v }));
            }
        }
    }
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

struct Args {
    exr: PathBuf,
    fov_deg: f64,
    threshold: f64,
}

fn parse_args() -> Result<Args, String> {
    let usage = "usage: morgana-sun-disc IMAGE.exr --fov-deg DEG [--threshold FRACTION]";
    let mut it = std::env::args().skip(1);
    let (mut exr, mut fov_deg, mut threshold) = (None, None, 1e-3);
    while let Some(a) = it.next() {
        let mut number = |name: &str| -> Result<f64, String> {
            let v = it.next().ok_or(format!("{name} needs a value; {usage}"))?;
            v.parse::<f64>()
                .ok()
                .filter(|x| x.is_finite() && *x > 0.0)
                .ok_or(format!("{name}: expected a positive number, found \"{v}\""))
        };
        match a.as_str() {
            "--fov-deg" => fov_deg = Some(number("--fov-deg")?),
            "--threshold" => threshold = number("--threshold")?,
            _ if exr.is_none() && !a.starts_with("--") => exr = Some(PathBuf::from(a)),
            _ => return Err(format!("unexpected argument \"{a}\"; {usage}")),
        }
    }
    match (exr, fov_deg) {
        (Some(exr), Some(fov_deg)) if threshold < 1.0 => Ok(Args { exr, fov_deg, threshold }),
        _ => Err(usage.into()),
    }
}

/// Linear sRGB scaled so that its largest component is 1, and as 8-bit values.
fn colour(xyz: [f64; 3]) -> String {
    let rgb = xyz_to_linear_srgb(xyz);
    let m = rgb.iter().copied().fold(f64::MIN_POSITIVE, f64::max);
    let n = rgb.map(|c| (c / m).max(0.0));
    let s = xyz[0] + xyz[1] + xyz[2];
    let (x, y) = if s > 0.0 { (xyz[0] / s, xyz[1] / s) } else { (0.0, 0.0) };
    let b = n.map(|c| (255.0 * c.powf(1.0 / 2.2)).round() as u8);
    format!(
        "Y {:10.4e} cd/m²  xy ({x:.4}, {y:.4})  linear sRGB/max ({:.3}, {:.3}, {:.3})  ≈ #{:02x}{:02x}{:02x}",
        xyz[1], n[0], n[1], n[2], b[0], b[1], b[2]
    )
}

fn run(args: &Args) -> Result<(), String> {
    let image = read_exr(&args.exr).map_err(|e| format!("{}: {e}", args.exr.display()))?;
    let luminance = Plane { width: image.width, height: image.height, v: image.xyz.iter().map(|p| p[1]).collect() };
    let arcsec = 3600.0 * args.fov_deg / image.height as f64;
    println!(
        "{}: {}×{} pixels, {arcsec:.3}″ per pixel, threshold {} × max",
        args.exr.display(),
        image.width,
        image.height,
        args.threshold
    );
    println!(
        "{:>10} {:>11} {:>11} {:>8} {:>10} {:>10}",
        "plane", "vertical″", "horizont.″", "ratio", "top px", "bottom px"
    );
    let disc = measure(&luminance, args.threshold).ok_or("no disc above the threshold in the luminance")?;
    let line = |name: &str, d: &Disc| {
        println!(
            "{name:>10} {:11.1} {:11.1} {:8.4} {:10.2} {:10.2}",
            d.vertical.length() * arcsec,
            d.horizontal * arcsec,
            d.vertical.length() / d.horizontal,
            d.vertical.start,
            d.vertical.end
        )
    };
    line("luminance", &disc);
    for (nm, plane) in bands(&args.exr)? {
        if let Some(d) = measure(&plane, args.threshold) {
            line(&format!("{nm:.2} nm"), &d);
        }
    }
    println!("rim pixels of column {} (rows from the top):", disc.centre_x);
    let (top, bottom) = (disc.vertical.start.floor() as usize, (disc.vertical.end.ceil() as usize).saturating_sub(1));
    let mid = (top + bottom) / 2;
    for y in [top, top + 1, top + 2, mid, bottom - 2, bottom - 1, bottom] {
        println!("  row {y:4}: {}", colour(image.xyz[y * image.width + disc.centre_x]));
    }
    Ok(())
}

fn main() -> ExitCode {
    match parse_args().and_then(|a| run(&a)) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("morgana-sun-disc: {e}");
            ExitCode::from(2)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// An ellipse of semi-axes (a, b) pixels centred at (cx, cy), supersampled 16×16 per pixel,
    /// of level `disc` over `sky`, with a vertical gradient of the disc's level (as extinction
    /// makes): the exact answer is 2a wide and 2b tall.
    fn ellipse(w: usize, h: usize, (cx, cy): (f64, f64), (a, b): (f64, f64), disc: f64, sky: f64) -> Plane {
        let n = 16;
        let mut v = vec![0.0; w * h];
        for y in 0..h {
            for x in 0..w {
                let mut inside = 0;
                for k in 0..n * n {
                    let px = x as f64 + ((k % n) as f64 + 0.5) / n as f64;
                    let py = y as f64 + ((k / n) as f64 + 0.5) / n as f64;
                    if ((px - cx) / a).powi(2) + ((py - cy) / b).powi(2) <= 1.0 {
                        inside += 1;
                    }
                }
                let f = inside as f64 / (n * n) as f64;
                let level = disc * (-(y as f64 - cy) / 200.0).exp();
                v[y * w + x] = sky + f * (level - sky);
            }
        }
        Plane { width: w, height: h, v }
    }

    #[test]
    fn an_ellipses_axes_are_measured_to_a_tenth_of_a_pixel() {
        let p = ellipse(160, 120, (80.3, 61.7), (50.0, 42.35), 1e4, 0.1);
        let d = measure(&p, 1e-3).expect("a disc");
        assert!((d.horizontal - 100.0).abs() < 0.1, "horizontal {}", d.horizontal);
        assert!((d.vertical.length() - 84.7).abs() < 0.1, "vertical {:?}", d.vertical);
        assert!((d.vertical.start - (61.7 - 42.35)).abs() < 0.05, "top {}", d.vertical.start);
        let ratio = d.vertical.length() / d.horizontal;
        assert!((ratio - 0.847).abs() < 0.002, "ratio {ratio}");
    }

    #[test]
    fn a_run_touching_the_profile_start_is_measured_from_zero() {
        let e = extent(&[5.0, 5.0, 5.0, 5.0, 5.0, 5.0, 2.5, 0.0, 0.0, 0.0, 0.0], 1.0).expect("a run");
        assert!((e.start - 0.0).abs() < 1e-12 && (e.end - 6.5).abs() < 1e-12, "{e:?}");
    }
}
