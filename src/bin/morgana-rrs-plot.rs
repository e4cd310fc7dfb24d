//! Plots a chlorophyll sweep: reads CSV rows `chl_mg_m3,wavelength_nm,Rrs_per_sr` (as written by
//! `scripts/chl_sweep.sh`) and writes a PNG of R_rs(λ), one line per concentration, with a
//! marker at the 685 nm chlorophyll fluorescence peak.
//!
//! `morgana-rrs-plot SWEEP.csv OUT.png`

use morgana::raster::spectrum_plot::{Series, write_png};
use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().collect();
    let [_, input, output] = args.as_slice() else {
        eprintln!("usage: morgana-rrs-plot SWEEP.csv OUT.png");
        return ExitCode::from(2);
    };
    let text = match std::fs::read_to_string(input) {
        Ok(t) => t,
        Err(e) => {
            eprintln!("morgana-rrs-plot: cannot read {input}: {e}");
            return ExitCode::from(2);
        }
    };
    let mut series: Vec<Series> = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let v: Vec<f64> = line.split(',').filter_map(|c| c.trim().parse().ok()).collect();
        let [chl, l, rrs] = v.as_slice() else {
            eprintln!("morgana-rrs-plot: {input}:{}: expected chl_mg_m3,wavelength_nm,Rrs_per_sr", i + 1);
            return ExitCode::from(2);
        };
        let label = format!("{chl} mg/m3");
        match series.iter_mut().find(|s| s.label == label) {
            Some(s) => s.points.push((*l, *rrs)),
            None => series.push(Series { label, points: vec![(*l, *rrs)] }),
        }
    }
    match write_png(
        std::path::Path::new(output),
        "Rrs (1/sr) by chlorophyll a",
        "wavelength (nm)",
        "Rrs",
        &series,
        &[685.0],
    ) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("morgana-rrs-plot: cannot write {output}: {e}");
            ExitCode::FAILURE
        }
    }
}
