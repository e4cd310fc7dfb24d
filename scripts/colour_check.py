#!/usr/bin/env python3
"""Cross-check morgana's colorimetry and spectral EXR output against colour-science.

colour-science (0.4.7, pinned in scripts/requirements-colour.txt) is the field's reference
implementation. This script sends one JSON request to morgana's check binary (protocol:
src/cli/colour_check.rs), computes the same quantities with colour-science, and compares:

  group         what                                                   metric / tolerance
  cmf           Σ x̄, Σ ȳ, Σ z̄ over 360-830 nm at 1 nm                    relative ≤ 1e-3
  illuminant    D65 at its 5 nm table points, A at 1 nm                 relative ≤ 1e-6
  white         XYZ of the perfect reflector under D65 and A            relative ≤ 1e-3
  xyz           24 ColorChecker (N Ohta) patches under D65 and A,       ΔE2000 ≤ 0.1
                relative colorimetry (Y_white = 100)
  srgb          linear sRGB of XYZ/100 of the same patches              |Δ| ≤ 1e-3
  blackbody     XYZ/Y of Planck radiance, 1000-20000 K                  relative ≤ 1e-3
  albedo        sRGB under D65 of morgana's Jakob-Hanika reflectances   |Δ| ≤ 1e-3
                vs the requested albedo
  exr           morgana writes spectral EXRs; colour-science reads them  relative ≤ 1e-3
                (read_spectral_image_Fichet2021), rebuilds each pixel's   (of the pixel's
                spectrum (linear through the channel wavelengths,          largest |RGB|)
                constant half a band beyond the outer centres, zero
                beyond), takes absolute XYZ (K_m = 683.002) and sRGB, and
                compares with the R, G, B channels morgana wrote
  exr-layout    layout attributes and channel wavelengths               exact / 1e-4 nm
  cat           24 ColorChecker patches adapted A -> D65, D65 -> A and     ΔE2000 ≤ 0.1
                blue-green water (x,y = 0.24,0.36) -> D65 by complete
                von Kries adaptation in the Von Kries (HPE), Bradford and
                CAT16 spaces (colour.chromatic_adaptation, method "Von
                Kries"), Lab relative to the target white
  scotopic      scotopic luminance K'_m Σ L V' (K'_m = 1700.06) of black  relative ≤ 1e-4
                bodies, D65, A and ColorChecker x D65, against
                colour.luminous_flux with the CIE 1951 scotopic V'
  exr-scotopic  the scotopic luminance `morgana tonemap` reads from each   relative ≤ 1e-3
                spectral EXR pixel, against colour-science's V' integral
                of the spectrum it rebuilds from the same file

Spectra sent to morgana are colour-science's own, aligned to 360-830 nm at 1 nm with its
default interpolation and extrapolation, so both sides integrate the same function.

Usage (from the repository root):

    bash scripts/setup_venv.sh
    cargo build --release --bin morgana-colour-check
    .venv/bin/python scripts/colour_check.py --bin target/release/morgana-colour-check

--self-test additionally perturbs morgana's answers, one group at a time, by more than the
group's tolerance and fails unless every group then reports a failure (so no comparison can
pass vacuously). Exit status: 0 when every comparison passes, 1 otherwise.
"""

from __future__ import annotations

import argparse
import copy
import json
import os
import subprocess
import sys
import tempfile
import warnings

warnings.filterwarnings("ignore")

import numpy as np  # noqa: E402

import colour  # noqa: E402
import OpenEXR  # noqa: E402

K_M = 683.002
SHAPE = colour.SpectralShape(360, 830, 1)
WAVELENGTHS = np.arange(360, 831, 1.0)
CMFS = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
SRGB = colour.RGB_COLOURSPACES["sRGB"]

TOL = {
    "cmf": 1e-3,
    "illuminant": 1e-6,
    "white": 1e-3,
    "xyz": 0.1,
    "srgb": 1e-3,
    "blackbody": 1e-3,
    "albedo": 1e-3,
    "exr": 1e-3,
    "exr-layout": 1e-4,
    "cat": 0.1,
    "scotopic": 1e-4,
    "exr-scotopic": 1e-3,
}
K_M_SCOTOPIC = 1700.06
V_PRIME = colour.SDS_LEFS["CIE 1951 Scotopic Standard Observer"]
CAT_METHODS = {"von_kries": "Von Kries", "bradford": "Bradford", "cat16": "CAT16"}
WATER_XY = (0.24, 0.36)
TEMPERATURES = [1000, 1500, 2000, 2500, 2856, 3000, 4000, 5000, 6500, 8000, 10000, 15000, 20000]
ALBEDOS = [
    [0.0, 0.0, 0.0],
    [1.0, 1.0, 1.0],
    [0.18, 0.18, 0.18],
    [1.0, 0.0, 0.0],
    [0.0, 1.0, 0.0],
    [0.0, 0.0, 1.0],
    [1.0, 1.0, 0.0],
    [0.0, 1.0, 1.0],
    [1.0, 0.0, 1.0],
    [0.8, 0.3, 0.1],
    [0.05, 0.4, 0.9],
    [0.9, 0.9, 0.2],
    [0.02, 0.01, 0.005],
]


# --------------------------------------------------------------------------- reference data


def aligned(sd: colour.SpectralDistribution) -> np.ndarray:
    """colour-science's own 1 nm values of `sd` over 360-830 nm (default align)."""
    return sd.copy().align(SHAPE).values


def illuminants() -> dict[str, colour.SpectralDistribution]:
    return {
        "D65": colour.SDS_ILLUMINANTS["D65"],
        "A": colour.colorimetry.sd_CIE_standard_illuminant_A(SHAPE),
    }


def patches() -> dict[str, colour.SpectralDistribution]:
    return dict(colour.SDS_COLOURCHECKERS["ColorChecker N Ohta"])


def relative_xyz(values: np.ndarray, illuminant: colour.SpectralDistribution) -> np.ndarray:
    sd = colour.SpectralDistribution(values, WAVELENGTHS)
    return colour.sd_to_XYZ(sd, CMFS, illuminant, method="Integration")


def xyz_to_linear_srgb(xyz: np.ndarray) -> np.ndarray:
    return colour.XYZ_to_RGB(xyz, SRGB, apply_cctf_encoding=False)


def absolute_xyz(values_1nm: np.ndarray) -> np.ndarray:
    return np.asarray(colour.sd_to_XYZ(values_1nm, CMFS, k=K_M, method="Integration", shape=SHAPE))


# ------------------------------------------------------------------------------- the request


def exr_requests(tmp: str) -> list[dict]:
    """Spectral images of known spectra, sampled at the band centres."""
    out = []
    for name, (lo, hi, n) in {
        "16bands": (380.0, 780.0, 16),
        "7bands": (400.0, 700.0, 7),
        "64bands": (360.0, 830.0, 64),
        "1band": (500.0, 600.0, 1),
    }.items():
        width = (hi - lo) / n
        centres = lo + (np.arange(n) + 0.5) * width
        d65 = colour.SDS_ILLUMINANTS["D65"]
        sky = patches()["blue sky"]
        spectra = [
            np.zeros(n),
            np.ones(n) * 0.01,
            colour.sd_blackbody(3000, colour.SpectralShape(300, 900, 0.5))[centres] * 1e-9 / np.pi,
            d65[centres] * 1e-3,
            sky[centres] * d65[centres] * 2e-3,
            np.where(np.arange(n) == n // 2, 0.05, 0.0),
        ]
        out.append(
            {
                "path": os.path.join(tmp, f"morgana-{name}.exr"),
                "min_nm": lo,
                "max_nm": hi,
                "count": n,
                "width": 3,
                "height": 2,
                "pixels": [list(map(float, s)) for s in spectra],
            }
        )
    return out


def build_request(tmp: str) -> dict:
    return {
        "cmf_integrals": True,
        "illuminant_samples_nm": list(np.arange(300, 831, 1.0)),
        "illuminants": ["D65", "A"],
        "reflectances": [
            {"name": name, "nm": list(WAVELENGTHS), "values": list(map(float, aligned(sd)))}
            for name, sd in patches().items()
        ],
        "blackbodies_k": TEMPERATURES,
        "rgb_albedos": ALBEDOS,
        "exr": exr_requests(tmp),
        "chromatic_adaptation": cat_requests(),
        "scotopic": [
            {"name": name, "nm": list(WAVELENGTHS), "values": list(map(float, values))}
            for name, values in scotopic_spectra().items()
        ],
    }


def cat_cases() -> list[tuple[str, np.ndarray, np.ndarray, np.ndarray]]:
    """(label, XYZ, XYZ_w, XYZ_wr), all with Y_white = 1."""
    ill = illuminants()
    white = {name: relative_xyz(np.ones(len(WAVELENGTHS)), sd) / 100 for name, sd in ill.items()}
    water = colour.xy_to_XYZ(WATER_XY)
    cases = []
    for name, sd in patches().items():
        refl = aligned(sd)
        under_a = relative_xyz(refl, ill["A"]) / 100
        under_d65 = relative_xyz(refl, ill["D65"]) / 100
        cases.append((f"A->D65/{name}", under_a, white["A"], white["D65"]))
        cases.append((f"D65->A/{name}", under_d65, white["D65"], white["A"]))
        cases.append((f"water->D65/{name}", under_d65 * water / white["D65"], water, white["D65"]))
    return cases


def cat_requests() -> list[dict]:
    return [
        {"method": method, "xyz": list(map(float, xyz)), "xyz_w": list(map(float, w)), "xyz_wr": list(map(float, wr))}
        for method in CAT_METHODS
        for _, xyz, w, wr in cat_cases()
    ]


def scotopic_spectra() -> dict[str, np.ndarray]:
    """Spectral radiances (W m^-2 sr^-1 nm^-1) at 360-830 nm, 1 nm."""
    ill = illuminants()
    out = {f"blackbody {t} K": colour.sd_blackbody(t, SHAPE).values * 1e-9 for t in (2000, 2856, 6500, 20000)}
    out["D65"] = aligned(ill["D65"]) * 1e-3
    out["A"] = ill["A"].values * 1e-3
    for name, sd in patches().items():
        out[f"D65 x {name}"] = aligned(sd) * aligned(ill["D65"]) * 1e-3
    return out


def scotopic_reference(values_1nm: np.ndarray) -> float:
    """colour-science's scotopic luminance of a spectrum sampled at 360-830 nm, 1 nm."""
    sd = colour.SpectralDistribution(values_1nm, WAVELENGTHS)
    return float(colour.luminous_flux(sd, V_PRIME, K_m=K_M_SCOTOPIC))


# --------------------------------------------------------------------------- the comparisons


class Table:
    """Per group: the worst comparison, and whether any failed."""

    def __init__(self) -> None:
        self.rows: dict[str, dict] = {}

    def add(self, group: str, item: str, value: float, extra: str = "") -> None:
        tol = TOL[group]
        ok = bool(np.isfinite(value) and value <= tol)
        row = self.rows.setdefault(group, {"worst": -1.0, "item": "", "extra": "", "n": 0, "failed": 0})
        row["n"] += 1
        row["failed"] += 0 if ok else 1
        if not np.isfinite(value) or value > row["worst"]:
            row.update(worst=float(value) if np.isfinite(value) else float("inf"), item=item, extra=extra)

    def failed_groups(self) -> set[str]:
        return {g for g, r in self.rows.items() if r["failed"] or r["n"] == 0}

    def print(self, out=sys.stdout) -> None:
        print(f"{'group':<12} {'n':>4} {'failed':>6} {'worst':>11} {'tolerance':>9}  worst item", file=out)
        for group, r in self.rows.items():
            status = "FAIL" if r["failed"] else "ok"
            print(
                f"{group:<12} {r['n']:>4} {r['failed']:>6} {r['worst']:>11.3e} {TOL[group]:>9.0e}  "
                f"{r['item']} {r['extra']} [{status}]",
                file=out,
            )


def rel(a, b) -> float:
    a, b = np.asarray(a, float), np.asarray(b, float)
    return float(np.max(np.abs(a - b) / np.maximum(np.abs(b), 1e-300)))


def compare(answer: dict, request: dict, table: Table) -> None:
    ill = illuminants()

    sums = CMFS.values.sum(axis=0) * SHAPE.interval
    table.add("cmf", "Σx̄ Σȳ Σz̄", rel(answer["cmf_integrals"], sums), f"{np.round(answer['cmf_integrals'], 4)}")

    nm = np.asarray(request["illuminant_samples_nm"])
    d65 = colour.SDS_ILLUMINANTS["D65"]
    for name, values in answer["illuminant_values"].items():
        values = np.asarray(values)
        if name == "D65":
            mask = np.isin(nm, d65.wavelengths)
            ref = d65[nm[mask]]
            got = values[mask]
        else:
            mask = (nm >= 360) & (nm <= 830)
            ref = ill["A"][nm[mask]]
            got = values[mask]
        worst = np.argmax(np.abs(got - ref) / np.abs(ref))
        table.add("illuminant", f"{name} {nm[mask][worst]:g} nm", rel(got, ref))

    whites = {}
    for name, sd in ill.items():
        whites[name] = relative_xyz(np.ones(len(WAVELENGTHS)), sd)
        table.add("white", name, rel(answer["illuminant_white"][name], whites[name]))

    sds = patches()
    for ill_name, colours in answer["reflectances"].items():
        white_xy = colour.XYZ_to_xy(whites[ill_name] / 100)
        for c in colours:
            ref = relative_xyz(aligned(sds[c["name"]]), ill[ill_name])
            got = np.asarray(c["xyz"])
            de = float(
                colour.delta_E(
                    colour.XYZ_to_Lab(ref / 100, white_xy),
                    colour.XYZ_to_Lab(got / 100, white_xy),
                    method="CIE 2000",
                )
            )
            table.add("xyz", f"{ill_name}/{c['name']}", de)
            diff = float(np.max(np.abs(np.asarray(c["linear_srgb"]) - xyz_to_linear_srgb(ref / 100))))
            table.add("srgb", f"{ill_name}/{c['name']}", diff)

    for bb in answer["blackbodies"]:
        t = bb["temperature_k"]
        ref = absolute_xyz(colour.sd_blackbody(t, SHAPE).values)
        table.add("blackbody", f"{t:g} K", rel(bb["xyz_normalised"], ref / ref[1]))

    for a in answer["rgb_albedos"]:
        refl = np.asarray(a["reflectance"])
        if np.any(refl < 0) or np.any(refl > 1):
            table.add("albedo", f"{a['rgb']} leaves [0, 1]", float("inf"))
        rgb = xyz_to_linear_srgb(relative_xyz(refl, ill["D65"]) / 100)
        table.add("albedo", f"{a['rgb']}", float(np.max(np.abs(rgb - np.asarray(a["rgb"])))))

    for req, written in zip(request["exr"], answer["exr"], strict=True):
        compare_exr(req, written, table)

    cases = cat_cases()
    answers = iter(answer["chromatic_adaptation"])
    for method, cs_name in CAT_METHODS.items():
        for label, xyz, w, wr in cases:
            got = np.asarray(next(answers))
            ref = colour.chromatic_adaptation(xyz, w, wr, method="Von Kries", transform=cs_name)
            white_xy = colour.XYZ_to_xy(wr)
            de = float(
                colour.delta_E(colour.XYZ_to_Lab(ref, white_xy), colour.XYZ_to_Lab(got, white_xy), method="CIE 2000")
            )
            table.add("cat", f"{method} {label}", de)

    for name, values in scotopic_spectra().items():
        table.add("scotopic", name, rel(answer["scotopic"][name], scotopic_reference(values)))


def rebuild(centres: np.ndarray, values: np.ndarray, edges: tuple[float, float]) -> np.ndarray:
    """The documented band reconstruction, with colour-science's interpolator/extrapolator:
    linear through the centres, constant out to the outer band edges (half a band spacing
    beyond the outer centres), zero beyond; evaluated at 360, 361, ..., 830 nm."""
    x = np.concatenate([[edges[0]], centres, [edges[1]]])
    y = np.concatenate([[values[0]], values, [values[-1]]])
    spectrum = colour.Extrapolator(colour.LinearInterpolator(x, y), method="Constant", left=0, right=0)
    return np.where((WAVELENGTHS >= x[0]) & (WAVELENGTHS <= x[-1]), spectrum(WAVELENGTHS), 0.0)


def compare_exr(req: dict, written: dict, table: Table) -> None:
    path = written["path"]
    tag = os.path.basename(path)
    components, spec = colour.io.read_spectral_image_Fichet2021(path, additional_data=True)
    attrs = {a.name: a.value for a in spec.attributes}
    layout_ok = (
        spec.is_emissive
        and attrs.get("spectralLayoutVersion") == "1.0"
        and attrs.get("emissiveUnits") == "W.m^-2.sr^-1"
        and list(components) == ["S0"]
    )
    table.add("exr-layout", f"{tag} attributes", 0.0 if layout_ok else float("inf"), str(attrs))
    edges = (attrs.get("morganaBandMinNm"), attrs.get("morganaBandMaxNm"))
    table.add(
        "exr-layout",
        f"{tag} band edges",
        rel(edges, (req["min_nm"], req["max_nm"])) if None not in edges else float("inf"),
        f"{edges}",
    )
    wavelengths, values = components["S0"]
    order = np.argsort(wavelengths)
    wavelengths, values = wavelengths[order], values[..., order]
    n = req["count"]
    width = (req["max_nm"] - req["min_nm"]) / n
    centres = req["min_nm"] + (np.arange(n) + 0.5) * width
    if len(wavelengths) != n:
        table.add("exr-layout", f"{tag} has {len(wavelengths)} bands, wanted {n}", float("inf"))
        return
    table.add("exr-layout", f"{tag} centres", float(np.max(np.abs(wavelengths - centres))))
    half = 0.5 * (wavelengths[1] - wavelengths[0]) if n > 1 else None
    if half is not None:
        # The edges are half a band spacing beyond the outer centres.
        spacing_edges = (wavelengths[0] - half, wavelengths[-1] + half)
        table.add("exr-layout", f"{tag} edges vs centres", float(np.max(np.abs(np.subtract(spacing_edges, edges)))))

    channels = OpenEXR.File(path, separate_channels=True).channels()
    rgb_file = np.stack([channels[c].pixels for c in "RGB"], axis=-1).astype(float)
    h, w = req["height"], req["width"]
    for p, sent in enumerate(req["pixels"]):
        y, x = divmod(p, w)
        stored = values[y, x].astype(float)
        table.add("exr", f"{tag} pixel {p} spectrum", rel_or_abs(stored, np.asarray(sent, np.float32)))
        xyz = absolute_xyz(rebuild(wavelengths, stored, edges))
        ref = xyz_to_linear_srgb(xyz)
        got = rgb_file[y, x]
        table.add("exr", f"{tag} pixel {p} rgb", rel_or_abs(got, ref), f"{np.round(got, 6)}")
        spectrum = rebuild(wavelengths, stored, edges)
        scot_ref = scotopic_reference(spectrum)
        table.add("exr-scotopic", f"{tag} pixel {p}", rel_or_abs(written["scotopic"][p], scot_ref))
    assert rgb_file.shape[:2] == (h, w)


def rel_or_abs(got, ref) -> float:
    """max |Δ| relative to the largest |ref| (absolute when ref is all zero)."""
    got, ref = np.asarray(got, float), np.asarray(ref, float)
    scale = float(np.max(np.abs(ref)))
    d = float(np.max(np.abs(got - ref)))
    return d / scale if scale > 0 else d * 1e9


# ----------------------------------------------------------------------------- perturbations


def perturbations() -> dict[str, callable]:
    """One answer edit per group, each beyond that group's tolerance."""

    def cmf(a):
        a["cmf_integrals"][1] *= 1.002

    def illuminant(a):
        a["illuminant_values"]["D65"][260] *= 1 + 1e-5  # 560 nm

    def white(a):
        a["illuminant_white"]["A"][2] *= 1.002

    def xyz(a):
        a["reflectances"]["D65"][5]["xyz"][0] *= 1.01

    def srgb(a):
        a["reflectances"]["A"][3]["linear_srgb"][1] += 2e-3

    def blackbody(a):
        a["blackbodies"][4]["xyz_normalised"][2] *= 1.002

    def albedo(a):
        a["rgb_albedos"][9]["reflectance"] = [v * 1.01 for v in a["rgb_albedos"][9]["reflectance"]]

    def cat(a):
        a["chromatic_adaptation"][40][0] *= 1.01

    def scotopic(a):
        a["scotopic"]["A"] *= 1 + 2e-4

    def exr_scotopic(a):
        a["exr"][2]["scotopic"][3] *= 1.002

    return {
        "cat": cat,
        "scotopic": scotopic,
        "exr-scotopic": exr_scotopic,
        "cmf": cmf,
        "illuminant": illuminant,
        "white": white,
        "xyz": xyz,
        "srgb": srgb,
        "blackbody": blackbody,
        "albedo": albedo,
    }


def perturb_exr(path: str, channel: str, factor: float) -> None:
    """Rewrites `path` with one channel of pixel (0, 1) scaled (for --self-test)."""
    f = OpenEXR.File(path, separate_channels=True)
    pixels = f.channels()[channel].pixels
    pixels[0, 1] *= factor
    f.write(path)


# ------------------------------------------------------------------------------------- main


def run_morgana(binary: str, request: dict) -> dict:
    done = subprocess.run(
        [binary], input=json.dumps(request), capture_output=True, text=True, check=False
    )
    if done.returncode != 0:
        sys.exit(f"colour_check: {binary} failed ({done.returncode}): {done.stderr.strip()}")
    return json.loads(done.stdout)


def main() -> int:
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("--bin", required=True, help="path of the morgana-colour-check binary")
    parser.add_argument("--self-test", action="store_true", help="also check that every comparison can fail")
    parser.add_argument("--keep", metavar="DIR", help="write the EXRs into DIR and keep them")
    args = parser.parse_args()

    tmp_ctx = tempfile.TemporaryDirectory(prefix="morgana-colour-check-")
    tmp = args.keep or tmp_ctx.name
    os.makedirs(tmp, exist_ok=True)
    request = build_request(tmp)
    answer = run_morgana(args.bin, request)

    # Sanity of the reference itself: a flat 1 W m^-2 sr^-1 nm^-1 has Y = K_m Σȳ.
    flat = absolute_xyz(np.ones(len(WAVELENGTHS)))
    assert abs(flat[1] / (K_M * CMFS.values[:, 1].sum()) - 1) < 1e-12, flat

    table = Table()
    compare(answer, request, table)
    print(f"colour-science {colour.__version__}, morgana check binary {args.bin}")
    table.print()
    failed = table.failed_groups()

    if args.self_test:
        print("\nself-test: each group perturbed beyond its tolerance must fail")
        insensitive = []
        for group, edit in perturbations().items():
            bad = copy.deepcopy(answer)
            edit(bad)
            t = Table()
            compare(bad, request, t)
            status = "fails as it should" if group in t.failed_groups() else "DID NOT FAIL"
            print(f"  {group:<12} {status}")
            if group not in t.failed_groups():
                insensitive.append(group)
        for group, (channel, factor) in {"exr": ("G", 1.002), "exr-layout": ("S0.550,0nm", 1.0)}.items():
            if group == "exr-layout":
                # Drop a band from the request's expectation instead of editing the file.
                req = copy.deepcopy(request)
                req["exr"][1]["count"] = 8
                t = Table()
                compare_exr(req["exr"][1], answer["exr"][1], t)
            else:
                perturb_exr(answer["exr"][0]["path"], channel, factor)
                t = Table()
                compare_exr(request["exr"][0], answer["exr"][0], t)
            status = "fails as it should" if group in t.failed_groups() else "DID NOT FAIL"
            print(f"  {group:<12} {status}")
            if group not in t.failed_groups():
                insensitive.append(group)
        if insensitive:
            print(f"self-test FAILED: {insensitive} cannot fail")
            return 1
        print("self-test passed")

    if failed:
        print(f"\nFAILED: {sorted(failed)}")
        return 1
    print("\nall comparisons passed")
    return 0


if __name__ == "__main__":
    sys.exit(main())
