//! `[[material]]` records → [`Material`]s.

use super::raw::RawMaterial;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::material::{
    Beckmann, COX_MUNK_MAX_WIND_M_S, Dielectric, Ior, Lambertian, Material, Mirror, RoughDielectric, named_glass,
};
use crate::spectrum::Bands;
use crate::validate::present_fields;
use crate::validate::{Ctx, R};
use toml::{Spanned, Value};

pub struct NamedMaterial {
    pub name: String,
    pub material: Material,
}

pub fn material(
    ctx: &Ctx,
    lib: &SpectrumLibrary,
    rec: &Spanned<RawMaterial>,
    index: usize,
    bands: &Bands,
) -> R<NamedMaterial> {
    let span = rec.span();
    let m = rec.get_ref();
    let owner = format!("material #{}", index + 1);
    let name = ctx.require(&m.name, "name", &span, &owner)?.get_ref().clone();
    let what = format!("material \"{name}\"");
    let kind = ctx.choice(
        ctx.require(&m.kind, "type", &span, &what)?,
        &format!("{what}: type"),
        &["lambertian", "mirror", "dielectric", "rough_dielectric"],
    )?;
    let all = present_fields!(m; reflectance, ior, ior_model, a, b_um2, c_um4, sellmeier_b, sellmeier_c_um2, wind_speed_m_s, rms_slope);
    let rough_fields = ["wind_speed_m_s", "rms_slope"];
    let present: Vec<_> =
        all.iter().filter(|(k, _)| kind != "rough_dielectric" || !rough_fields.contains(k)).cloned().collect();
    let range = (bands.min_nm, bands.max_nm);
    let material = match kind {
        "lambertian" | "mirror" => {
            ctx.only(&present, &["reflectance"], &format!("{what} ({kind})"))?;
            let r = ctx.require(&m.reflectance, "reflectance", &span, &what)?;
            let reflectance = lib.parse(ctx, r, &format!("{what}: reflectance"), Use::Reflectance, range)?;
            if kind == "mirror" {
                Material::Mirror(Mirror { reflectance })
            } else {
                Material::Lambertian(Lambertian { reflectance })
            }
        }
        "dielectric" => Material::Dielectric(Dielectric { ior: ior(ctx, m, &span, &what, &present, bands)? }),
        _ => Material::RoughDielectric(RoughDielectric {
            ior: ior(ctx, m, &span, &what, &present, bands)?,
            facets: facets(ctx, m, &span, &what)?,
        }),
    };
    Ok(NamedMaterial { name, material })
}

/// The facets of a rough dielectric: `wind_speed_m_s = W` (the Cox–Munk sea, α² = 0.003 +
/// 5.12·10⁻³ W) or `rms_slope = α` (Beckmann), exactly one.
fn facets(ctx: &Ctx, m: &RawMaterial, span: &std::ops::Range<usize>, what: &str) -> R<Beckmann> {
    match (&m.wind_speed_m_s, &m.rms_slope) {
        (Some(w), None) => {
            let v = *w.get_ref();
            if !(v.is_finite() && (0.0..=COX_MUNK_MAX_WIND_M_S).contains(&v)) {
                return Err(ctx.err(
                    &w.span(),
                    format!(
                        "{what}: wind_speed_m_s = {v}; expected a wind speed in [0, {COX_MUNK_MAX_WIND_M_S}] m/s (Cox & Munk fitted 1–14 m/s)"
                    ),
                ));
            }
            Ok(Beckmann::cox_munk(v))
        }
        (None, Some(a)) => {
            let v = *a.get_ref();
            if !(v.is_finite() && v > 0.0 && v <= 1.0) {
                return Err(ctx.err(&a.span(), format!("{what}: rms_slope = {v}; expected a slope in (0, 1]")));
            }
            Ok(Beckmann { alpha: v })
        }
        (Some(_), Some(r)) => Err(ctx.err(
            &r.span(),
            format!("{what} (rough_dielectric): give wind_speed_m_s (Cox–Munk sea) or rms_slope, not both"),
        )),
        (None, None) => Err(ctx.err(
            span,
            format!("{what} (rough_dielectric): needs wind_speed_m_s (Cox–Munk sea, m/s) or rms_slope (Beckmann α)"),
        )),
    }
}

/// `ior = 1.5` or `ior = "N-BK7"`, or `ior_model = "cauchy"` with `a`, `b_um2` (and `c_um4`), or
/// `ior_model = "sellmeier"` with `sellmeier_b`, `sellmeier_c_um2`.
fn ior(
    ctx: &Ctx,
    m: &RawMaterial,
    span: &std::ops::Range<usize>,
    what: &str,
    present: &[(&str, Option<std::ops::Range<usize>>)],
    bands: &Bands,
) -> R<Ior> {
    let model = match (&m.ior_model, &m.ior) {
        (Some(model), _) => ctx.choice(model, &format!("{what}: ior_model"), &["constant", "cauchy", "sellmeier"])?,
        (None, Some(_)) => "constant",
        (None, None) => {
            return Err(
                ctx.err(span, format!("{what} (dielectric): needs `ior` (a number or a glass name) or `ior_model`"))
            );
        }
    };
    let dwhat = format!("{what} (dielectric, ior_model \"{model}\")");
    let ior = match model {
        "constant" => {
            ctx.only(present, &["ior", "ior_model"], &dwhat)?;
            let v = ctx.require(&m.ior, "ior", span, &dwhat)?;
            let ior = constant_or_glass(ctx, v, what)?;
            // A number is refused at its own line.
            ior.validate(bands.min_nm, bands.max_nm).map_err(|e| ctx.err(&v.span(), format!("{what}: ior: {e}")))?;
            ior
        }
        "cauchy" => {
            ctx.only(present, &["ior_model", "a", "b_um2", "c_um4"], &dwhat)?;
            let (Some(a), Some(b)) = (&m.a, &m.b_um2) else {
                return Err(ctx.err(
                    span,
                    format!("{what}: ior_model \"cauchy\" needs both a and b_um2 (n = a + b/λ² + c/λ⁴, λ in μm)"),
                ));
            };
            let c = m.c_um4.as_ref().map_or(0.0, |c| *c.get_ref());
            Ior::Cauchy { a: *a.get_ref(), b_um2: *b.get_ref(), c_um4: c }
        }
        _ => {
            ctx.only(present, &["ior_model", "sellmeier_b", "sellmeier_c_um2"], &dwhat)?;
            let (Some(b), Some(c)) = (&m.sellmeier_b, &m.sellmeier_c_um2) else {
                return Err(ctx.err(span, format!("{what}: ior_model \"sellmeier\" needs both sellmeier_b and sellmeier_c_um2 (three numbers each)")));
            };
            Ior::Sellmeier { b: b.get_ref().0, c_um2: c.get_ref().0 }
        }
    };
    ior.validate(bands.min_nm, bands.max_nm).map_err(|e| ctx.err(span, format!("{what}: {e}")))?;
    Ok(ior)
}

fn constant_or_glass(ctx: &Ctx, v: &Spanned<Value>, what: &str) -> R<Ior> {
    match v.get_ref() {
        Value::Float(n) => Ok(Ior::Constant { n: *n }),
        Value::Integer(n) => Ok(Ior::Constant { n: *n as f64 }),
        Value::String(name) => named_glass(name).ok_or_else(|| {
            ctx.err(
                &v.span(),
                format!(
                    "{what}: glass \"{name}\" is not in the catalogue; known: {}",
                    crate::material::GLASS_NAMES.join(", ")
                ),
            )
        }),
        _ => Err(ctx.err(&v.span(), format!("{what}: ior must be a number or a glass name"))),
    }
}
