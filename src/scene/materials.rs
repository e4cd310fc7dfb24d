//! `[[material]]` records → [`Material`]s.

use super::context::{Ctx, R};
use super::raw::RawMaterial;
use super::spectrum_spec::{SpectrumLibrary, Use};
use crate::material::{Dielectric, Ior, Lambertian, Material, Mirror, named_glass};
use crate::present_fields;
use crate::spectrum::Bands;
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
        &["lambertian", "mirror", "dielectric"],
    )?;
    let present = present_fields!(m; reflectance, ior, ior_model, a, b_um2, c_um4, sellmeier_b, sellmeier_c_um2);
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
        _ => Material::Dielectric(Dielectric { ior: ior(ctx, m, &span, &what, &present, bands)? }),
    };
    Ok(NamedMaterial { name, material })
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
            constant_or_glass(ctx, v, what)?
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
            Ior::Sellmeier { b: *b.get_ref(), c_um2: *c.get_ref() }
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
