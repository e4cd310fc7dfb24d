//! The text `morgana luminaire FILE` prints: what the file says and what its web gives.

use super::beam::{plane_curve, spread_angle_deg};
use super::{PhotometricType, Photometry, Symmetry};
use std::fmt::Write;

/// Curve sampling step for beam and field angles, degrees.
const CURVE_STEP_DEG: f64 = 0.1;

/// A multi-line summary of `p` (see the module docs).
pub fn summary(p: &Photometry) -> String {
    let mut s = String::new();
    let mut row = |k: &str, v: String| {
        let _ = writeln!(s, "{k:<14}{v}");
    };
    row("format", format!("{} ({})", p.format, p.encoding));
    row("maker", p.manufacturer.clone());
    let catalogue = if p.catalogue.is_empty() { String::new() } else { format!(" (catalogue {})", p.catalogue) };
    row("luminaire", format!("{}{catalogue}", p.luminaire));
    for (i, l) in p.lamps.iter().enumerate() {
        let flux = l.flux_lm.map_or("absolute photometry".to_string(), |f| format!("{f} lm"));
        let watts = l.watts.map_or(String::new(), |w| format!(", {w} W"));
        let extra = [l.colour_temperature.as_str(), l.colour_rendering.as_str()]
            .iter()
            .filter(|x| !x.is_empty())
            .map(|x| format!(", {x}"))
            .collect::<String>();
        let label = if i == 0 { "lamps" } else { "" };
        let set = if p.lamps.len() > 1 { format!("set {}: ", i + 1) } else { String::new() };
        row(label, format!("{set}{} × {}, {flux}{extra}{watts}", l.count, l.description));
    }
    if let Some(sp) = &p.spectrum {
        row(
            "spectrum",
            format!("{} (the light's emission spectrum unless the scene gives spectrum or cct_k)", sp.describe()),
        );
    }
    flux_rows(p, &mut row);
    row("symmetry", symmetry_text(p));
    let web = &p.web;
    let g = web.gamma_deg();
    row(
        "grid",
        format!(
            "{} × {} stored, {} × {} full ({} planes × polar angles {}–{}°)",
            p.stored_grid.0,
            p.stored_grid.1,
            web.c_deg().len(),
            g.len(),
            angle_names(p.photometric_type).0,
            g[0],
            g[g.len() - 1]
        ),
    );
    row("opening", p.opening.describe());
    let (peak, c, gamma) = web.peak();
    let (cn, gn) = angle_names(p.photometric_type);
    row("peak", format!("{peak:.1} cd at {cn} = {c}°, {gn} = {gamma}° (file angles)"));
    row("beam (50%)", spreads(p, 0.5));
    row("field (10%)", spreads(p, 0.1));
    if let Some(t) = &p.tilt {
        row("tilt", format!("TILT={}: lamp geometry {}, {} angles", t.source, t.geometry, t.angles_deg.len()));
    }
    for n in &p.notes {
        row("note", n.clone());
    }
    s
}

fn flux_rows(p: &Photometry, row: &mut impl FnMut(&str, String)) {
    let web_flux = p.flux_lm();
    match (p.stated_flux_lm, p.lamp_flux_lm) {
        (Some(stated), Some(lamp)) => {
            let lorl = p.lorl_percent.map_or(String::new(), |l| format!(" × LORL {l}%"));
            row("flux, file", format!("{stated:.1} lm (lamps {lamp} lm{lorl})"));
        }
        (None, Some(lamp)) => row("flux, file", format!("lamps {lamp} lm (luminaire flux not stated)")),
        (Some(stated), None) => row("flux, file", format!("{stated:.1} lm (absolute photometry)")),
        _ => row("flux, file", "not stated (absolute photometry)".to_string()),
    }
    let vs = match (p.flux_mismatch(), p.lamp_flux_lm) {
        (Some(m), _) => format!(", {:+.2}% vs the file", 100.0 * m),
        (None, Some(lamp)) if lamp > 0.0 => format!(", {:.1}% of the lamp flux", 100.0 * web_flux / lamp),
        _ => String::new(),
    };
    row("flux, web", format!("{web_flux:.1} lm by the web's quadrature{vs}"));
    if let Some(dff) = p.dff_percent
        && p.photometric_type == PhotometricType::C
        && web_flux > 0.0
    {
        let down = 100.0 * p.web.flux_between_lm(0.0, 1.0) / web_flux;
        let flag = if (down - dff).abs() > 2.0 { " — the file's DFF disagrees with its own table" } else { "" };
        row("downward", format!("DFF {dff}% (file), {down:.1}% (web){flag}"));
    }
}

fn symmetry_text(p: &Photometry) -> String {
    match p.symmetry {
        Symmetry::None => "none".into(),
        s => s.to_string(),
    }
}

/// Names of the plane and polar angles in the file's own system.
fn angle_names(t: PhotometricType) -> (&'static str, &'static str) {
    match t {
        PhotometricType::C => ("C", "γ"),
        PhotometricType::B | PhotometricType::A => ("H", "90° − V"),
    }
}

fn spreads(p: &Photometry, fraction: f64) -> String {
    [0.0, 90.0]
        .iter()
        .map(|c| {
            let curve = plane_curve(&p.web, *c, CURVE_STEP_DEG);
            let v = spread_angle_deg(&curve, fraction).map_or("—".to_string(), |a| format!("{a:.1}°"));
            format!("C{}–C{} {v}", c, c + 180.0)
        })
        .collect::<Vec<_>>()
        .join(", ")
}
