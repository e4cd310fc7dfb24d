//! Spectra as a scene writes them.
//!
//! A spectrum value is one of:
//! - a number: the same value at every wavelength;
//! - a string: a spectrum defined under `[spectra]`, a CIE illuminant ("D65", "A", "E"),
//!   "solar": the extraterrestrial solar spectral irradiance (ASTM G173-03, W m⁻² nm⁻¹), or
//!   "pope_fry_1997": pure-water absorption a_w, m⁻¹, 380–727.5 nm (built in, Pope & Fry 1997);
//! - a table with exactly one of `constant = x`, `blackbody_k = T`, `rgb = [r, g, b]`
//!   (linear sRGB albedo, reflectances only), `illuminant = "D65"`, `nm = [...]` with
//!   `values = [...]`, or `file = "data.csv"` (two columns: wavelength_nm, value; `#` comments and
//!   one header row allowed); plus an optional `scale = k` multiplier.

use crate::spectrum::{RgbSigmoid, Spectrum, Tabulated, named_illuminant};
use crate::validate::{Ctx, R};
use std::collections::BTreeMap;
use std::ops::Range;
use toml::{Spanned, Value};

/// What a spectrum is used for, which decides the checks it must pass.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Use {
    /// Values in [0, 1]; RGB allowed.
    Reflectance,
    /// Values ≥ 0; RGB not allowed (an RGB colour does not define an emission spectrum).
    Emission,
}

const TABLE_KEYS: &[&str] = &["constant", "blackbody_k", "rgb", "illuminant", "nm", "values", "file", "scale"];

/// Named spectra from the scene's `[spectra]` table, parsed on first use.
pub struct SpectrumLibrary<'a> {
    pub named: &'a BTreeMap<String, Spanned<Value>>,
}

impl SpectrumLibrary<'_> {
    /// Parses `v` for `use_` over the scene's wavelength range and checks it there.
    pub fn parse(&self, ctx: &Ctx, v: &Spanned<Value>, what: &str, use_: Use, range: (f64, f64)) -> R<Spectrum> {
        let s = self.parse_unchecked(ctx, v, what, use_, 0)?;
        check_range(ctx, &v.span(), &s, what, use_, range)?;
        Ok(s)
    }

    fn parse_unchecked(&self, ctx: &Ctx, v: &Spanned<Value>, what: &str, use_: Use, depth: usize) -> R<Spectrum> {
        let span = v.span();
        match v.get_ref() {
            Value::Float(x) => Ok(Spectrum::Constant(*x)),
            Value::Integer(i) => Ok(Spectrum::Constant(*i as f64)),
            Value::String(name) => self.by_name(ctx, &span, name, what, use_, depth),
            Value::Table(t) => self.table(ctx, &span, t, what, use_),
            other => Err(ctx.err(
                &span,
                format!("{what}: a spectrum must be a number, a name or a table, not {}", other.type_str()),
            )),
        }
    }

    fn by_name(&self, ctx: &Ctx, span: &Range<usize>, name: &str, what: &str, use_: Use, depth: usize) -> R<Spectrum> {
        if let Some(def) = self.named.get(name) {
            if depth > 0 {
                return Err(
                    ctx.err(span, format!("{what}: spectrum \"{name}\" refers to another name; define it directly"))
                );
            }
            return self.parse_unchecked(ctx, def, &format!("spectrum \"{name}\""), use_, depth + 1);
        }
        if let Some(s) = named_illuminant(name) {
            return Ok(s);
        }
        if name == "solar" {
            return Ok(Spectrum::Tabulated(crate::spectrum::solar::extraterrestrial()));
        }
        if name == "pope_fry_1997" {
            return Ok(Spectrum::Tabulated(crate::media::ocean::builtin::pope_fry()));
        }
        let names: Vec<&str> = self.named.keys().map(String::as_str).collect();
        Err(ctx.err(
            span,
            format!(
                "{what}: no spectrum named \"{name}\"; define it under [spectra] (defined: {}) or use a CIE illuminant (D65, A, E), \"solar\" (ASTM G173 extraterrestrial, W m⁻² nm⁻¹) or \"pope_fry_1997\" (pure-water absorption, m⁻¹)",
                if names.is_empty() { "none".to_string() } else { names.join(", ") }
            ),
        ))
    }

    fn table(&self, ctx: &Ctx, span: &Range<usize>, t: &toml::Table, what: &str, use_: Use) -> R<Spectrum> {
        if let Some(k) = t.keys().find(|k| !TABLE_KEYS.contains(&k.as_str())) {
            return Err(
                ctx.err(span, format!("{what}: unknown spectrum key `{k}`; allowed: {}", TABLE_KEYS.join(", ")))
            );
        }
        let kinds: Vec<&str> = ["constant", "blackbody_k", "rgb", "illuminant", "nm", "file"]
            .into_iter()
            .filter(|k| t.contains_key(*k))
            .collect();
        if kinds.len() != 1 {
            return Err(ctx.err(
                span,
                format!(
                    "{what}: a spectrum table needs exactly one of constant, blackbody_k, rgb, illuminant, nm (with values) or file; found {}",
                    if kinds.is_empty() { "none".to_string() } else { kinds.join(", ") }
                ),
            ));
        }
        let num = |key: &str| -> R<f64> {
            t.get(key)
                .and_then(|v| v.as_float().or_else(|| v.as_integer().map(|i| i as f64)))
                .ok_or_else(|| ctx.err(span, format!("{what}: `{key}` must be a number")))
        };
        let base = match kinds[0] {
            "constant" => Spectrum::Constant(num("constant")?),
            "blackbody_k" => {
                let temperature_k = num("blackbody_k")?;
                if !(temperature_k > 0.0 && temperature_k.is_finite()) {
                    return Err(ctx.err(
                        span,
                        format!("{what}: blackbody_k = {temperature_k} must be a positive temperature in kelvin"),
                    ));
                }
                if use_ == Use::Reflectance {
                    return Err(ctx.err(
                        span,
                        format!("{what}: a reflectance cannot be a black body; use rgb, nm/values or a number"),
                    ));
                }
                Spectrum::Blackbody { temperature_k }
            }
            "rgb" => rgb(ctx, span, t, what, use_)?,
            "illuminant" => {
                let name = t.get("illuminant").and_then(Value::as_str).unwrap_or_default();
                named_illuminant(name).ok_or_else(|| {
                    ctx.err(span, format!("{what}: illuminant \"{name}\" is not known; allowed: D65, A, E"))
                })?
            }
            "nm" => inline_table(ctx, span, t, what)?,
            _ => from_csv(ctx, span, t, what)?,
        };
        match t.get("scale") {
            None => Ok(base),
            Some(_) => {
                let k = num("scale")?;
                if !(k.is_finite() && k >= 0.0) {
                    return Err(ctx.err(span, format!("{what}: scale = {k} must be a finite number ≥ 0")));
                }
                Ok(base.scaled(k))
            }
        }
    }
}

fn rgb(ctx: &Ctx, span: &Range<usize>, t: &toml::Table, what: &str, use_: Use) -> R<Spectrum> {
    if use_ == Use::Emission {
        return Err(ctx.err(
            span,
            format!(
                "{what}: rgb defines reflectances only; give a light a spectrum (blackbody_k, illuminant, nm/values)"
            ),
        ));
    }
    let arr = numbers(t.get("rgb"))
        .filter(|a| a.len() == 3)
        .ok_or_else(|| ctx.err(span, format!("{what}: rgb must be three numbers (linear sRGB albedo in [0, 1])")))?;
    let rgb = [arr[0], arr[1], arr[2]];
    if rgb.iter().any(|c| !(0.0..=1.0).contains(c)) {
        return Err(ctx.err(span, format!("{what}: rgb = {rgb:?} must lie in [0, 1] (linear sRGB albedo)")));
    }
    RgbSigmoid::fit(rgb).map(Spectrum::RgbReflectance).map_err(|e| ctx.err(span, format!("{what}: {e}")))
}

fn numbers(v: Option<&Value>) -> Option<Vec<f64>> {
    v?.as_array()?.iter().map(|x| x.as_float().or_else(|| x.as_integer().map(|i| i as f64))).collect()
}

fn inline_table(ctx: &Ctx, span: &Range<usize>, t: &toml::Table, what: &str) -> R<Spectrum> {
    let nm = numbers(t.get("nm")).ok_or_else(|| ctx.err(span, format!("{what}: nm must be an array of numbers")))?;
    let values = numbers(t.get("values"))
        .ok_or_else(|| ctx.err(span, format!("{what}: nm needs `values`, an array of numbers of the same length")))?;
    if nm.len() != values.len() {
        return Err(ctx.err(
            span,
            format!("{what}: nm has {} entries but values has {}; they must match", nm.len(), values.len()),
        ));
    }
    Tabulated::new(nm, values).map(Spectrum::Tabulated).map_err(|e| ctx.err(span, format!("{what}: {e}")))
}

fn from_csv(ctx: &Ctx, span: &Range<usize>, t: &toml::Table, what: &str) -> R<Spectrum> {
    let file = t
        .get("file")
        .and_then(Value::as_str)
        .ok_or_else(|| ctx.err(span, format!("{what}: file must be a string path")))?;
    let path = ctx.dir.join(file);
    let text = std::fs::read_to_string(&path)
        .map_err(|e| ctx.err(span, format!("{what}: cannot read spectrum file {}: {e}", path.display())))?;
    // Located at the scene's line that names the file; the message gives the file's own line.
    let (nm, values) = crate::spectrum::table::parse_two_column_csv(&text)
        .map_err(|(line, msg)| ctx.err(span, format!("{what}: spectrum file {}:{line}: {msg}", path.display())))?;
    Tabulated::new(nm, values)
        .map(Spectrum::Tabulated)
        .map_err(|e| ctx.err(span, format!("{what}: spectrum file {}: {e}", path.display())))
}

/// Checks that a spectrum covers the range and has allowed values there.
fn check_range(ctx: &Ctx, span: &Range<usize>, s: &Spectrum, what: &str, use_: Use, (lo, hi): (f64, f64)) -> R<()> {
    if let Some((a, b)) = tabulated_domain(s)
        && (a > lo || b < hi)
    {
        return Err(ctx.err(
            span,
            format!(
                "{what}: tabulated over {a}–{b} nm but the scene simulates {lo}–{hi} nm; extend the table (zeros are fine for a light) or set [output] min_nm/max_nm inside it"
            ),
        ));
    }
    let steps = ((hi - lo).ceil() as usize).max(1);
    for i in 0..=steps {
        let l = lo + (hi - lo) * i as f64 / steps as f64;
        let x = s.eval(l);
        let bad = match use_ {
            Use::Reflectance => !(0.0..=1.0).contains(&x),
            Use::Emission => !(x >= 0.0 && x.is_finite()),
        };
        if bad {
            let allowed = if use_ == Use::Reflectance { "in [0, 1]" } else { "finite and ≥ 0" };
            return Err(ctx.err(span, format!("{what}: value {x} at {l:.1} nm; values must be {allowed}")));
        }
    }
    Ok(())
}

fn tabulated_domain(s: &Spectrum) -> Option<(f64, f64)> {
    match s {
        Spectrum::Tabulated(t) => Some(t.domain_nm()),
        Spectrum::Scaled(_, b) => tabulated_domain(b),
        _ => None,
    }
}
