//! `[output]` keys for tone reproduction: the options of `morgana tonemap`, validated with
//! errors that point at the key.
//!
//! ```toml
//! [output]
//! tonemap = "ward_histogram"   # exposure | reinhard | ward_histogram | pattanaik
//! adapt_to = "scene_average"   # none | d65 | a | e | white | scene_average | [x, y]
//! cat = "cat16"                # von_kries | bradford | cat16
//! adaptation_degree = 1.0
//! adaptation_time_s = 2.0      # pattanaik, with adapt_from_cd_m2
//! adapt_from_cd_m2 = 5000.0
//! scotopic = "auto"            # auto | on | off
//! false_colour = false
//! region = [10, 20, 60, 50]    # x0, y0, x1, y1: writes NAME.region.csv
//! ```
//!
//! Without any of these keys the PNG is the plain exposure preview, as before. The field of view
//! is the camera's.

use super::raw::RawOutput;
use crate::geometry::Camera;
use crate::tonemap::Exposure;
use crate::tonemap::region::Region;
use crate::tonemap::{ToneOptions, ToneSettings};
use crate::validate::{Ctx, R};
use std::ops::Range;
use toml::Value;

/// The tone settings (`None` for the plain preview) and the luminance region, if any.
pub fn tone(
    ctx: &Ctx,
    o: &RawOutput,
    exposure: Exposure,
    camera: &Camera,
) -> R<(Option<ToneSettings>, Option<Region>)> {
    let region = match &o.region {
        None => None,
        Some(r) => Some(region(ctx, &r.get_ref().0, &r.span(), camera)?),
    };
    let given = o.tonemap.is_some()
        || o.adapt_to.is_some()
        || o.cat.is_some()
        || o.adaptation_degree.is_some()
        || o.adaptation_time_s.is_some()
        || o.adapt_from_cd_m2.is_some()
        || o.scotopic.is_some()
        || o.false_colour.is_some();
    if !given {
        return Ok((None, region));
    }
    let options = ToneOptions {
        operator: o.tonemap.as_ref().map(|v| v.get_ref().clone()),
        exposure: o.exposure.as_ref().map(|_| exposure),
        adapt_to: o.adapt_to.as_ref().map(|v| adapt_to(ctx, v.get_ref(), &v.span())).transpose()?,
        cat: o.cat.as_ref().map(|v| v.get_ref().clone()),
        adaptation_degree: o.adaptation_degree.as_ref().map(|v| *v.get_ref()),
        adaptation_time_s: o.adaptation_time_s.as_ref().map(|v| *v.get_ref()),
        adapt_from_cd_m2: o.adapt_from_cd_m2.as_ref().map(|v| *v.get_ref()),
        scotopic: o.scotopic.as_ref().map(|v| v.get_ref().clone()),
        false_colour: o.false_colour.as_ref().is_some_and(|v| *v.get_ref()),
        fov_deg: Some(camera.fov_deg),
    };
    let settings = options.validate().map_err(|e| {
        let span = span_of(o, e.field).unwrap_or(0..0);
        ctx.err(&span, format!("[output] {}: {}", e.field, e.message))
    })?;
    Ok((Some(settings), region))
}

/// `adapt_to` as the string the options parser reads: a name, or "x,y" from `[x, y]`.
fn adapt_to(ctx: &Ctx, v: &Value, span: &Range<usize>) -> R<String> {
    match v {
        Value::String(s) => Ok(s.clone()),
        Value::Array(a) if a.len() == 2 => {
            let n: Vec<Option<f64>> = a.iter().map(|x| x.as_float().or(x.as_integer().map(|i| i as f64))).collect();
            match n.as_slice() {
                [Some(x), Some(y)] => Ok(format!("{x},{y}")),
                _ => Err(ctx.err(span, "[output] adapt_to = [x, y] needs two numbers")),
            }
        }
        _ => Err(ctx.err(
            span,
            "[output] adapt_to must be \"none\", \"d65\", \"a\", \"e\", \"white\", \"scene_average\" or a chromaticity [x, y]",
        )),
    }
}

fn region(ctx: &Ctx, r: &[i64; 4], span: &Range<usize>, camera: &Camera) -> R<Region> {
    let bad = |m: String| ctx.err(span, format!("[output] region: {m}"));
    let v: Vec<usize> = r.iter().map(|&x| usize::try_from(x)).collect::<Result<_, _>>().map_err(|_| {
        bad(format!("{r:?} has a negative coordinate; give pixel coordinates x0, y0, x1, y1 from the top left"))
    })?;
    let region = Region::new(v[0], v[1], v[2], v[3]).map_err(bad)?;
    region.check_inside(camera.width, camera.height).map_err(bad)?;
    Ok(region)
}

/// The span of the `[output]` key behind a validation error.
fn span_of(o: &RawOutput, field: &str) -> Option<Range<usize>> {
    match field {
        "tonemap" => o.tonemap.as_ref().map(|v| v.span()),
        "exposure" => o.exposure.as_ref().map(|v| v.span()),
        "adapt_to" => o.adapt_to.as_ref().map(|v| v.span()),
        "cat" => o.cat.as_ref().map(|v| v.span()),
        "adaptation_degree" => o.adaptation_degree.as_ref().map(|v| v.span()),
        "adaptation_time_s" => o.adaptation_time_s.as_ref().map(|v| v.span()),
        "adapt_from_cd_m2" => o.adapt_from_cd_m2.as_ref().map(|v| v.span()),
        "scotopic" => o.scotopic.as_ref().map(|v| v.span()),
        _ => o.false_colour.as_ref().map(|v| v.span()),
    }
}
