#!/usr/bin/env python3
"""Equal-time RMSE of morgana against Mitsuba 3 (issue 4, "Benchmark against Mitsuba 3").

Protocol (README, "Benchmark against Mitsuba 3"):

1. Each scene is one morgana TOML under benches/scenes/. This script translates that file into
   a Mitsuba scene (`mi.load_dict`), so both renderers get the same numbers: geometry, spectra
   (tabulated ones are linearly interpolated by both), medium, camera. Emission is limited to
   the TOML's [min_nm, max_nm] in Mitsuba too (morgana simulates only that range).
2. Reference: Mitsuba 3 `volpath` (scalar_spectral, unbiased, next-event estimation with MIS)
   at `--ref-spp` samples per pixel, rendered in `--ref-chunks` independent chunks; the spread
   of the chunks gives the reference's own per-pixel variance and so its RMSE noise floor.
3. Series: Mitsuba `volpath` at increasing spp; morgana's photon map at increasing budgets;
   morgana's unbiased `method = "path"` at increasing spp, each with `--threads` cores. Timed:
   morgana, the sum of the phases report.json records (photon tracing, map builds, irradiance
   precompute, eye pass, colour conversion; not parsing or writing outputs), and its process's
   CPU time; Mitsuba, whose scalar variants render on one core when called from Python, runs
   in `--threads` worker processes that render a share of the samples each (`MitsubaRunner`):
   wall time from handing out the work until every share is back, and their CPU time.
4. RMSE against the reference over all pixels and the three linear sRGB channels, in morgana's
   units (absolute linear sRGB, Y in cd m^-2). The reference's noise is removed in quadrature:
   RMSE_c = sqrt(max(RMSE^2 - sigma_ref^2, 0)); the raw RMSE of a morgana run over Mitsuba's
   RMSE_c is a conservative bound on the ratio. Equal-time ratios interpolate each method's
   RMSE(time) curve linearly in log-log, at equal wall time and at equal CPU time. A scene may
   also be measured without its glints (pixels that see an emitter through glass alone).

Colour: Mitsuba's spectral film writes XYZ normalised so that a unit spectrum has Y ~ 1, i.e.
Y_mi = (integral of L ybar) / 106.7502594 nm with its 5 nm CIE 1931 table, interpolated
linearly; morgana writes absolute XYZ, Y = 683.002 lm/W * integral of L ybar, then linear sRGB
with the IEC 61966-2-1 matrix. So morgana's XYZ = 683.002 * 106.7502594 * Mitsuba's XYZ, and this script converts
Mitsuba's XYZ output that way and applies morgana's matrix.

Run through scripts/bench_mitsuba.sh (builds morgana, sets up the venv). Results go to
out/mitsuba_bench/ (CSV, markdown, preview PNGs); the table is printed at the end.
"""

from __future__ import annotations

import argparse
import csv
import hashlib
import json
import math
import os
import re
import resource
import subprocess
import sys
import time
import tomllib
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import progressive_chain  # noqa: E402

ROOT = Path(__file__).resolve().parent.parent

# Absolute luminance per unit of Mitsuba's normalised Y: K_m (lm/W) times the denominator of
# Mitsuba's MI_CIE_Y_NORMALIZATION (include/mitsuba/core/spectrum.h), nm.
K_M = 683.002
MITSUBA_Y_INTEGRAL_NM = 106.7502593994140625
# XYZ -> linear sRGB as morgana applies it (src/spectrum/colour.rs, IEC 61966-2-1, 4 decimals).
XYZ_TO_SRGB = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])


@dataclass
class SceneSpec:
    """One benchmark scene: its TOML, the budgets each method runs, regions to compare."""

    toml: str
    mitsuba_spp: list[int]
    morgana_path_spp: list[int]
    # [integrator] settings of each photon-map run (method = "photon_map").
    photon_map: list[dict]
    # name -> (x0, y0, x1, y1) in pixels, x1/y1 exclusive.
    regions: dict[str, tuple[int, int, int, int]] = field(default_factory=dict)
    # Also report RMSE without the pixels that show an emitter through specular surfaces alone
    # (L S+ E paths: glints, the light's images in glass), dilated by this many pixels (None: no
    # such second figure). See `specular_light_mask`.
    mask_glints_dilate: int | None = None
    # `--progressive`: the [integrator] settings of one pass of morgana's progressive runs, and
    # whether adaptive sampling (`--adaptive`) runs too.
    progressive: dict = field(default_factory=dict)
    progressive_adaptive: bool = False


PM_COMMON = {"direct": "shadow_rays", "final_gather": True}

SCENES = {
    "fog_box": SceneSpec(
        toml="benches/scenes/fog_box.toml",
        mitsuba_spp=[4, 16, 64, 256, 1024, 4096],
        morgana_path_spp=[4, 16, 64, 256, 1024],
        photon_map=[
            {"photons": 200_000, "volume_k": 50, "march_step": 0.1, "gather_rays": 4, "spp": 2},
            {"photons": 500_000, "volume_k": 50, "march_step": 0.1, "gather_rays": 4, "spp": 4},
            {"photons": 1_000_000, "volume_k": 100, "march_step": 0.1, "gather_rays": 4, "spp": 8},
            {"photons": 2_000_000, "volume_k": 100, "march_step": 0.05, "gather_rays": 8, "spp": 8},
            {"photons": 4_000_000, "volume_k": 200, "march_step": 0.1, "gather_rays": 4, "spp": 16},
        ],
        progressive={"photons": 200_000, "volume_k": 50, "march_step": 0.1, "gather_rays": 4, "spp": 2},
        regions={
            "left wall": (0, 48, 8, 80),
            "right wall": (120, 48, 128, 80),
            "back wall": (56, 56, 72, 72),
            "floor": (48, 116, 80, 128),
            "fog below light": (56, 8, 72, 24),
        },
    ),
    "volume_caustic": SceneSpec(
        toml="benches/scenes/volume_caustic.toml",
        mitsuba_spp=[4, 16, 64, 256, 1024, 2048],
        morgana_path_spp=[4, 16, 64, 256, 1024],
        photon_map=[
            {"photons": 1_000_000, "caustic_photons": 500_000, "volume_k": 50, "march_step": 0.1,
             "final_gather": False, "k": 100, "spp": 4},
            {"photons": 2_000_000, "caustic_photons": 1_000_000, "volume_k": 50, "march_step": 0.05,
             "gather_rays": 4, "spp": 4},
            {"photons": 4_000_000, "caustic_photons": 1_000_000, "volume_k": 100, "march_step": 0.05,
             "gather_rays": 4, "spp": 8},
            {"photons": 8_000_000, "caustic_photons": 2_000_000, "volume_k": 100, "march_step": 0.05,
             "gather_rays": 4, "spp": 16},
        ],
        # Cheap photons, more eye samples: the whole-image error is the glints' (eye samples).
        progressive={"photons": 100_000, "caustic_photons": 100_000, "volume_k": 50, "march_step": 0.1,
                     "final_gather": False, "k": 100, "spp": 4},
        progressive_adaptive=True,
        regions={
            "sphere": (56, 56, 72, 72),
            "caustic": (96, 96, 112, 112),
            "beam above sphere": (28, 28, 36, 36),
            "glint": (37, 37, 44, 44),
            "back wall": (8, 100, 24, 116),
        },
        mask_glints_dilate=1,
    ),
}


# ---------------------------------------------------------------------------------------------
# morgana TOML -> Mitsuba scene dictionary
# ---------------------------------------------------------------------------------------------


class Untranslatable(Exception):
    """The scene uses a feature this translation cannot reproduce identically in Mitsuba."""


def mi_spectrum(value, spectra: dict):
    """A morgana spectrum (number, [spectra] name, or nm/values table) as a Mitsuba spectrum."""
    if isinstance(value, (int, float)):
        return {"type": "uniform", "value": float(value)}
    if isinstance(value, str):
        if value not in spectra:
            raise Untranslatable(f"spectrum {value!r}: only [spectra] tables translate")
        return mi_spectrum(spectra[value], spectra)
    if isinstance(value, dict) and set(value) <= {"nm", "values", "scale"} and "nm" in value:
        scale = float(value.get("scale", 1.0))
        return {
            "type": "irregular",
            "wavelengths": ", ".join(f"{x:g}" for x in value["nm"]),
            "values": ", ".join(f"{scale * v:g}" for v in value["values"]),
        }
    if isinstance(value, dict) and set(value) <= {"constant", "scale"}:
        return {"type": "uniform", "value": float(value["constant"]) * float(value.get("scale", 1.0))}
    raise Untranslatable(f"spectrum {value!r}: only numbers and nm/values tables are identical in both")


def emission_spectrum(light: dict, spectra: dict, min_nm: float, max_nm: float):
    """Constant spectral radiance/intensity within [min_nm, max_nm], zero outside (as morgana)."""
    s, scale = light["spectrum"], light.get("scale")
    if scale is None or not isinstance(s, (int, float)):
        raise Untranslatable(f"light {light.get('name')!r}: only constant spectra with scale translate")
    v = float(s) * float(scale)
    return {"type": "regular", "wavelength_min": min_nm, "wavelength_max": max_nm, "values": f"{v}, {v}"}


def mi_bsdf(mat: dict | None, spectra: dict):
    if mat is None:
        return {"type": "diffuse", "reflectance": {"type": "uniform", "value": 0.0}}
    kind = mat["type"]
    if kind == "lambertian":
        diffuse = {"type": "diffuse", "reflectance": mi_spectrum(mat["reflectance"], spectra)}
        return {"type": "twosided", "bsdf": diffuse}
    if kind == "dielectric" and isinstance(mat.get("ior"), (int, float)):
        return {"type": "dielectric", "int_ior": float(mat["ior"]), "ext_ior": 1.0}
    raise Untranslatable(f"material {mat.get('name')!r} ({kind})")


def quad_transform(origin, u, v):
    """Mitsuba's rectangle [-1, 1]^2 x {0} (normal +z) onto origin + a u + b v, normal u x v."""
    o, u, v = (np.asarray(x, float) for x in (origin, u, v))
    n = np.cross(u, v)
    m = np.eye(4)
    m[:3, 0], m[:3, 1], m[:3, 2] = u / 2, v / 2, n / np.linalg.norm(n)
    m[:3, 3] = o + u / 2 + v / 2
    return m.tolist()


def mi_shape(shape: dict, bsdf, mi, media: dict):
    kind = shape["type"]
    if kind == "quad":
        d = {"type": "rectangle", "to_world": mi.ScalarTransform4f(quad_transform(shape["origin"], shape["u"], shape["v"]))}
    elif kind == "sphere":
        d = {"type": "sphere", "center": shape["center"], "radius": float(shape["radius"])}
    else:
        raise Untranslatable(f"shape {shape.get('name')!r} ({kind})")
    d["bsdf"] = bsdf
    d.update(media)
    return d


def mi_light(light: dict, spectra: dict, bands: tuple[float, float], mi):
    kind = light["type"]
    if kind == "area" and light.get("shape") == "quad" and light.get("side", "front") == "front":
        d = mi_shape({**light, "type": "quad"}, mi_bsdf(None, spectra), mi, {})
        d["emitter"] = {"type": "area", "radiance": emission_spectrum(light, spectra, *bands)}
        if "material" in light:
            raise Untranslatable("area light with a material")
        return d
    if kind == "spot" and light.get("falloff_start_deg", light["cone_deg"]) == light["cone_deg"]:
        # A hard-edged cone in both: Mitsuba's falloff (linear in angle) differs from morgana's
        # smoothstep, so only falloff_start_deg = cone_deg is identical.
        pos = np.asarray(light["position"], float)
        target = pos + np.asarray(light["direction"], float)
        up = [0.0, 0.0, 1.0] if abs(light["direction"][2]) < 0.9 else [1.0, 0.0, 0.0]
        cone = float(light["cone_deg"])
        return {
            "type": "spot",
            "to_world": mi.ScalarTransform4f().look_at(origin=pos.tolist(), target=target.tolist(), up=up),
            "intensity": emission_spectrum(light, spectra, *bands),
            "cutoff_angle": cone,
            "beam_width": cone * (1.0 - 1e-6),
        }
    raise Untranslatable(f"light {light.get('name')!r} ({kind})")


def mi_medium(m: dict):
    if m.get("phase", "isotropic") != "isotropic" or "density" in m or "sigma_t" not in m:
        raise Untranslatable(f"medium {m.get('name')!r}: only homogeneous isotropic sigma_t/albedo")
    return {
        "type": "homogeneous",
        "sigma_t": float(m["sigma_t"]),
        "albedo": float(m["albedo"]),
        "phase": {"type": "isotropic"},
        "sample_emitters": True,
    }


def to_mitsuba(scene: dict, mi) -> dict:
    """The Mitsuba scene dictionary of a morgana scene (the subset the benchmark scenes use)."""
    spectra = scene.get("spectra", {})
    out = scene.get("output", {})
    bands = (float(out.get("min_nm", 380.0)), float(out.get("max_nm", 780.0)))
    d = {"type": "scene", "integrator": {"type": "volpath", "max_depth": -1, "rr_depth": 5}}
    world = scene.get("world", {}).get("medium")
    for m in scene.get("medium", []):
        d[f"medium_{m['name']}"] = mi_medium(m) | {"id": m["name"]}
    ref = (lambda name: {"type": "ref", "id": name}) if world else None
    cam = scene["camera"]
    sensor = {
        "type": "perspective",
        "fov": float(cam["fov_deg"]),
        "fov_axis": "y",  # morgana's fov_deg is the full vertical field of view
        "to_world": mi.ScalarTransform4f().look_at(
            origin=cam["position"], target=cam["look_at"], up=cam.get("up", [0.0, 1.0, 0.0])
        ),
        "film": {
            "type": "hdrfilm",
            "width": int(cam["width"]),
            "height": int(cam["height"]),
            "pixel_format": "xyz",
            "rfilter": {"type": "box"},  # morgana: each sample in its pixel, equal weights
        },
        "sampler": {"type": "independent", "sample_count": 1},
    }
    if world:
        sensor["medium"] = ref(world)
    d["sensor"] = sensor
    mats = {m["name"]: m for m in scene.get("material", [])}
    for i, s in enumerate(scene.get("shape", [])):
        media = {}
        if world and mats.get(s.get("material"), {}).get("type") == "dielectric":
            media["exterior"] = ref(world)  # morgana: vacuum inside glass, the world outside
        if "interior" in s or "exterior" in s:
            raise Untranslatable(f"shape {s.get('name')!r}: explicit interior/exterior media")
        d[f"shape_{i}"] = mi_shape(s, mi_bsdf(mats.get(s.get("material")), spectra), mi, media)
    for i, light in enumerate(scene.get("light", [])):
        d[f"light_{i}"] = mi_light(light, spectra, bands, mi)
    return d


def mitsuba_xyz_to_srgb(xyz: np.ndarray) -> np.ndarray:
    """Mitsuba's normalised XYZ image -> morgana's absolute linear sRGB (module docstring)."""
    return (xyz.astype(np.float64) * (K_M * MITSUBA_Y_INTEGRAL_NM)) @ XYZ_TO_SRGB.T


# ---------------------------------------------------------------------------------------------
# Running the renderers
# ---------------------------------------------------------------------------------------------


class MitsubaRunner:
    """A Mitsuba scene loaded in `threads` worker processes; `render(spp)` splits the samples
    between them (different seeds) and averages. Mitsuba 3.9.1's scalar variants render on one
    core when called from Python (measured here: the same time with dr.set_thread_count 1 to 4,
    and two Python threads rendering at once take twice as long), so this is how it gets the
    same number of cores as morgana. Wall time: from handing out the work until both halves are
    back (scene loading and one warm-up render excluded); CPU time: the workers' render calls."""

    def __init__(self, scene_text: str, threads: int):
        import multiprocessing as mp

        ctx = mp.get_context("spawn")
        self.jobs = [ctx.Queue() for _ in range(threads)]
        self.results = ctx.Queue()
        self.procs = [ctx.Process(target=mitsuba_worker, args=(scene_text, q, self.results),
                                  daemon=True) for q in self.jobs]
        for proc in self.procs:
            proc.start()
        for _ in self.procs:
            self.results.get()  # "ready", after loading and a warm-up render

    def render(self, spp: int, seed: int) -> tuple[np.ndarray, float, float]:
        """Linear sRGB image, wall seconds and CPU seconds (all workers)."""
        n = len(self.jobs)
        shares = [spp // n + (1 if i < spp % n else 0) for i in range(n)]
        t = time.perf_counter()
        for i, (q, s) in enumerate(zip(self.jobs, shares)):
            if s:
                q.put((s, seed * n + i))
        parts = [self.results.get() for s in shares if s]
        seconds = time.perf_counter() - t
        img = sum(s * p[0] for s, p in zip([s for s in shares if s], parts)) / spp
        return mitsuba_xyz_to_srgb(img), seconds, sum(p[1] for p in parts)

    def close(self):
        for q in self.jobs:
            q.put(None)
        for proc in self.procs:
            proc.join(timeout=10)


def mitsuba_worker(scene_text: str, jobs, results):
    """One Mitsuba process: load the scene, answer (spp, seed) requests with (XYZ, CPU seconds)."""
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    mi.set_log_level(mi.LogLevel.Warn)
    scene = mi.load_dict(to_mitsuba(tomllib.loads(scene_text), mi))
    mi.render(scene, spp=1, seed=0)
    results.put("ready")
    while (job := jobs.get()) is not None:
        spp, seed = job
        c = time.process_time()
        img = np.array(mi.render(scene, spp=spp, seed=seed), dtype=np.float64)
        results.put((img, time.process_time() - c))


def variant_toml(base: str, integrator: dict, name: str) -> str:
    """The scene text with its [integrator] table replaced and only the EXR written."""
    lines = ["[integrator]"] + [f"{k} = {toml_value(v)}" for k, v in integrator.items()]
    text = re.sub(r"(?ms)^\[integrator\]\n.*?(?=^\[)", "\n".join(lines) + "\n\n", base, count=1)
    text = re.sub(r'(?m)^name = "[^"]*"$', f'name = "{name}"\npng = false', text, count=1)
    if "[integrator]" not in text:
        raise ValueError("the scene has no [integrator] table to replace")
    return text


def toml_value(v) -> str:
    if isinstance(v, bool):
        return "true" if v else "false"
    if isinstance(v, str):
        return json.dumps(v)
    return repr(v)


def read_exr_rgb(path: Path) -> np.ndarray:
    import OpenEXR

    ch = OpenEXR.File(str(path), separate_channels=True).channels()
    return np.stack([np.asarray(ch[c].pixels, dtype=np.float64) for c in "RGB"], axis=-1)


@dataclass
class MorganaResult:
    rgb: np.ndarray
    seconds: float
    # CPU seconds of the whole process (all threads; includes parsing and writing outputs).
    cpu_seconds: float
    report: dict


def run_morgana(binary: Path, base: str, integrator: dict, work: Path, name: str, threads: int) -> MorganaResult:
    work.mkdir(parents=True, exist_ok=True)
    scene_path = work / f"{name}.toml"
    scene_path.write_text(variant_toml(base, integrator, name))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    subprocess.run(
        [str(binary), "render", str(scene_path), "--out", str(work), "--threads", str(threads), "--quiet"],
        check=True,
        stdout=subprocess.DEVNULL,
    )
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    report = json.loads((work / "report.json").read_text())
    seconds = sum(p["seconds"] for p in report["phases"])
    return MorganaResult(read_exr_rgb(work / f"{name}.exr"), seconds, cpu, report)


# ---------------------------------------------------------------------------------------------
# Reference, metrics, equal-time interpolation
# ---------------------------------------------------------------------------------------------


@dataclass
class Reference:
    rgb: np.ndarray
    variance: np.ndarray  # per pixel and channel, of the mean
    spp: int
    seconds: float
    # Two independent halves of the reference (each an unbiased image), when its chunks'
    # images were kept: what the split-reference error (`Metric.cross`) needs.
    halves: tuple[np.ndarray, np.ndarray] | None = None


@dataclass
class ChunkSums:
    """Independent reference chunks of `per` spp each: their count, the per-pixel sums of their
    images and of their squares (float64), and the images of the chunks rendered one by one
    (`images`; the first n - len(images) chunks may be known by their sums alone). Two sets of
    chunks with different seeds combine exactly by adding the sums (Chan, Golub & LeVeque 1979),
    so a reference can be extended, or resumed after a kill, without rendering its chunks again;
    the images let the reference be split into independent halves (`halves`)."""

    n: int
    per: int
    total: np.ndarray
    squares: np.ndarray
    seconds: float
    cpu_seconds: float = 0.0
    images: list = field(default_factory=list)

    def add(self, img: np.ndarray, seconds: float, cpu: float) -> None:
        self.n += 1
        self.total = self.total + img
        self.squares = self.squares + img * img
        self.seconds += seconds
        self.cpu_seconds += cpu
        self.images.append(img)

    def reference(self) -> Reference:
        """The mean of the chunks; the variance of that mean, the chunks' sample variance / n."""
        mean = self.total / self.n
        var = np.maximum(self.squares - self.n * mean * mean, 0.0) / (self.n - 1) / self.n
        return Reference(mean, var, self.per * self.n, self.seconds, self.halves() if len(self.images) > 1 else None)

    @staticmethod
    def from_reference(ref: Reference, chunks: int) -> "ChunkSums":
        """Back from a reference of `chunks` chunks: sum = n mean, sum of squares =
        (n - 1) n var + n mean^2 (its variance is that of the mean, s^2 / n)."""
        n = chunks
        return ChunkSums(n, ref.spp // n, n * ref.rgb, (n - 1) * n * ref.variance + n * ref.rgb**2, ref.seconds)

    def arrays(self) -> dict:
        return {"n": self.n, "per": self.per, "total": self.total, "squares": self.squares,
                "seconds": self.seconds, "cpu_seconds": self.cpu_seconds,
                "images": np.stack(self.images) if self.images else np.zeros((0,))}

    @staticmethod
    def from_arrays(z) -> "ChunkSums":
        images = list(z["images"]) if z["images"].ndim == 4 else []
        return ChunkSums(int(z["n"]), int(z["per"]), z["total"], z["squares"], float(z["seconds"]),
                         float(z["cpu_seconds"]), images)

    def halves(self) -> tuple[np.ndarray, np.ndarray]:
        """Two independent unbiased references: the mean of the chunks known by their sums alone
        with the first half of the single images, and the mean of the other images."""
        m = len(self.images)
        prior = self.n - m
        k = max(0, (self.n + 1) // 2 - prior)
        first = self.total - sum(self.images[k:], np.zeros_like(self.total))
        second = sum(self.images[k:], np.zeros_like(self.total))
        return first / (prior + k), second / (m - k)


def render_reference(runner_factory, spp: int, chunks: int, log, sums: ChunkSums | None, save) -> ChunkSums:
    """Chunk i has seed 1_000_000 + i, so the first chunks of a larger reference with the same
    spp per chunk are those of a smaller one; `sums` holds the chunks already rendered and
    `save(sums)` is called after every eighth new one and the last (saving a large reference
    after each chunk cost seconds per chunk)."""
    per = max(1, spp // chunks)
    if sums is None or sums.per != per:
        sums = ChunkSums(0, per, 0.0, 0.0, 0.0)
    for i in range(sums.n, chunks):
        img, s, cpu = runner_factory().render(per, seed=1_000_000 + i)
        sums.add(img, s, cpu)
        if sums.n % 8 == 0 or sums.n == chunks:
            save(sums)
        log(f"  reference chunk {i + 1}/{chunks}: {per} spp, {s:.1f} s, CPU {cpu:.1f} s "
            f"(load {os.getloadavg()[0]:.1f})")
    return sums


def scene_digest(mi_dict: dict, version: str) -> str:
    """What a reference depends on: the translated scene and the Mitsuba version."""
    return hashlib.sha256((json.dumps(mi_dict, sort_keys=True, default=str) + version).encode()).hexdigest()


def load_or_render_reference(path: Path, digest: str, runner_factory, spp: int, chunks: int, log) -> Reference:
    """The reference at `path` if it has this digest and spp; otherwise rendered, continuing
    from the chunks of `path`.partial.npz (saved after each chunk) or of a smaller reference at
    `path` with the same spp per chunk (whose chunk count the file holds; 8 if it predates that)."""
    partial = path.with_suffix(".partial.npz")
    sums = None
    if path.exists():
        z = np.load(path)
        if str(z["digest"]) == digest:
            old = Reference(z["rgb"], z["variance"], int(z["spp"]), float(z["seconds"]))
            old_chunks = int(z["chunks"]) if "chunks" in z else 8
            if old.spp == spp:
                log(f"  reusing {path} ({spp} spp)")
                return ChunkSums.from_arrays(z).reference() if "images" in z else old
            if old.spp % old_chunks == 0 and old.spp // old_chunks == spp // chunks and old_chunks < chunks:
                sums = ChunkSums.from_arrays(z) if "images" in z else ChunkSums.from_reference(old, old_chunks)
                log(f"  extending {path}: its {old_chunks} chunks of {sums.per} spp are the first")
    if partial.exists():
        z = np.load(partial)
        if str(z["digest"]) == digest and int(z["per"]) == spp // chunks and int(z["n"]) > (sums.n if sums else 0):
            sums = ChunkSums.from_arrays(z)
            log(f"  resuming from {partial}: {sums.n} chunks of {sums.per} spp")

    def save(s: ChunkSums):
        tmp = partial.with_suffix(".tmp.npz")
        np.savez_compressed(tmp, **s.arrays(), digest=digest)
        os.replace(tmp, partial)

    sums = render_reference(runner_factory, spp, chunks, log, sums, save)
    ref = sums.reference()
    np.savez_compressed(path, rgb=ref.rgb, variance=ref.variance, spp=ref.spp, seconds=ref.seconds,
                        chunks=chunks, digest=digest, **{k: v for k, v in sums.arrays().items() if k != "seconds"})
    partial.unlink(missing_ok=True)
    return ref


@dataclass
class Metric:
    """RMSE over a set of pixels (all three linear sRGB channels) against the reference."""

    pixels: np.ndarray  # boolean mask (height, width)
    ref_rgb: np.ndarray
    noise: float  # the reference's own RMSE noise over these pixels
    mean: float  # the reference's mean over these pixels
    halves: tuple[np.ndarray, np.ndarray] | None = None

    @staticmethod
    def over(ref: Reference, pixels: np.ndarray) -> "Metric":
        return Metric(pixels, ref.rgb, float(np.sqrt(ref.variance[pixels].mean())), float(ref.rgb[pixels].mean()),
                      ref.halves)

    def cross(self, img: np.ndarray) -> tuple[float, float]:
        """The split-reference error: with A and B the two independent halves of the reference,
        each unbiased and independent of the image x, E[(x - A)(x - B)] = (x - truth)^2 per
        pixel and channel, so the mean of the products over pixels is an unbiased estimate of
        x's squared error that needs no estimate of the reference's variance (the corrected
        RMSE needs one, from the chunks' spread, which heavy-tailed noise makes unreliable).
        Returns (RMSE, the standard error of the mean square given x, from the products'
        spread over pixels, whose reference noise is independent). NaN without halves."""
        if self.halves is None:
            return NAN, NAN
        a, b = (h[self.pixels] for h in self.halves)
        x = img[self.pixels]
        prod = ((x - a) * (x - b)).ravel()
        mse = float(prod.mean())
        return math.sqrt(max(mse, 0.0)), float(prod.std(ddof=1) / math.sqrt(prod.size))

    def errors(self, img: np.ndarray) -> tuple[float, float]:
        """(raw RMSE, RMSE with the reference's noise removed in quadrature). The raw value
        overestimates the true RMSE (in expectation the reference's independent noise adds in
        quadrature), so it is a conservative bound; the corrected one is unbiased in the square."""
        raw = float(np.sqrt(np.mean((img[self.pixels] - self.ref_rgb[self.pixels]) ** 2)))
        return raw, math.sqrt(max(raw * raw - self.noise**2, 0.0))


def loglog_interp(times: list[float], errors: list[float], t: float) -> float:
    """RMSE at time t on the piecewise-linear log-log curve through (times, errors); NaN outside."""
    pts = sorted((a, b) for a, b in zip(times, errors) if a > 0 and b > 0)
    if not pts or not pts[0][0] <= t <= pts[-1][0]:
        return float("nan")
    for (t0, e0), (t1, e1) in zip(pts, pts[1:]):
        if t0 <= t <= t1:
            w = 0.0 if t1 == t0 else math.log(t / t0) / math.log(t1 / t0)
            return math.exp((1 - w) * math.log(e0) + w * math.log(e1))
    return pts[-1][1]


def region_means(img: np.ndarray, regions: dict) -> dict[str, list[float]]:
    return {k: img[y0:y1, x0:x1].reshape(-1, 3).mean(axis=0).tolist() for k, (x0, y0, x1, y1) in regions.items()}


# ---------------------------------------------------------------------------------------------
# Runs, ratios, tables
# ---------------------------------------------------------------------------------------------

NAN = float("nan")


@dataclass
class Run:
    """One render of a series, measured against the reference. `rmse` is the noise-corrected
    RMSE over all pixels, `raw` the uncorrected one; `rmse_m`/`raw_m` leave out the pixels the
    scene's mask removes (NaN without a mask)."""

    scene: str
    method: str
    settings: str
    seconds: float
    cpu_seconds: float
    raw: float
    rmse: float
    rel: float
    raw_m: float = NAN
    rmse_m: float = NAN
    rmse_x: float = NAN  # the split-reference RMSE (`Metric.cross`), all pixels
    mse_x_se: float = NAN  # the standard error of its square
    ratio: float = NAN  # rmse / Mitsuba's rmse at the same wall time
    ratio_cpu: float = NAN  # ... at the same CPU time
    bound: float = NAN  # raw / Mitsuba's rmse at the same wall time: an upper bound on ratio
    ratio_m: float = NAN
    bound_m: float = NAN
    photon_memory_mb: float = NAN
    photon_build_s: float = NAN
    photon_trace_s: float = NAN
    rgb: np.ndarray | None = None


def curve(runs: list[Run], method: str, key: str = "rmse", cpu: bool = False) -> tuple[list[float], list[float]]:
    sel = [r for r in runs if r.method == method]
    return [r.cpu_seconds if cpu else r.seconds for r in sel], [getattr(r, key) for r in sel]


def set_ratios(runs: list[Run]):
    """Each morgana run's RMSE over Mitsuba's at equal wall time, at equal CPU time, the
    conservative bound, and the same without the masked pixels."""
    mi_wall = curve(runs, MITSUBA)
    mi_cpu = curve(runs, MITSUBA, cpu=True)
    mi_m = curve(runs, MITSUBA, "rmse_m")
    for r in runs:
        if r.method == MITSUBA:
            continue
        at = loglog_interp(*mi_wall, r.seconds)
        r.ratio, r.bound = r.rmse / at, r.raw / at
        r.ratio_cpu = r.rmse / loglog_interp(*mi_cpu, r.cpu_seconds)
        at_m = loglog_interp(*mi_m, r.seconds)
        r.ratio_m, r.bound_m = r.rmse_m / at_m, r.raw_m / at_m


def equal_time_summary(scene: str, runs: list[Run], times: list[float], cpu: bool) -> list[dict]:
    """Each method's RMSE at common wall (or CPU) times, and morgana's ratios to Mitsuba there:
    `ratio` from noise-corrected RMSEs, `bound` from morgana's raw RMSE (an upper bound on the
    ratio in expectation), and the same without the masked pixels."""
    rows = []
    for t in times:
        row = {"scene": scene, "clock": "cpu" if cpu else "wall", "seconds": t}
        for key, method in (("mitsuba", MITSUBA), ("photon_map", PHOTON_MAP), ("path", PATH)):
            for suffix, field_ in (("", "rmse"), ("_raw", "raw"), ("_masked", "rmse_m"), ("_raw_masked", "raw_m")):
                row[key + suffix] = loglog_interp(*curve(runs, method, field_, cpu), t)
        for key in ("photon_map", "path"):
            row[key + "_ratio"] = row[key] / row["mitsuba"]
            row[key + "_bound"] = row[key + "_raw"] / row["mitsuba"]
            row[key + "_ratio_masked"] = row[key + "_masked"] / row["mitsuba_masked"]
            row[key + "_bound_masked"] = row[key + "_raw_masked"] / row["mitsuba_masked"]
        if any(math.isfinite(row[k]) for k in ("photon_map_ratio", "path_ratio")):
            rows.append(row)
    return rows


def write_png(path: Path, rgb: np.ndarray, white: float):
    """sRGB-encoded 8-bit preview with linear values scaled by 1/white."""
    import OpenImageIO as oiio

    x = np.clip(rgb / max(white, 1e-30), 0.0, 1.0)
    enc = np.where(x <= 0.0031308, 12.92 * x, 1.055 * np.power(x, 1 / 2.4) - 0.055)
    px = (enc * 255 + 0.5).astype(np.uint8)
    out = oiio.ImageOutput.create(str(path))
    out.open(str(path), oiio.ImageSpec(px.shape[1], px.shape[0], 3, oiio.UINT8))
    out.write_image(px)
    out.close()


RUN_FIELDS = ["scene", "method", "settings", "seconds", "cpu_seconds", "raw", "rmse", "rel", "raw_m", "rmse_m",
              "rmse_x", "mse_x_se",
              "ratio", "ratio_cpu", "bound", "ratio_m", "bound_m", "photon_memory_mb", "photon_build_s",
              "photon_trace_s"]


def write_csv(path: Path, rows: list[dict]):
    if not rows:
        path.write_text("")
        return
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows({k: (f"{v:.6g}" if isinstance(v, float) else v) for k, v in row.items()} for row in rows)


def fmt(x: float, spec: str) -> str:
    return "—" if not math.isfinite(x) else format(x, spec)


def markdown(runs: list[Run], summary: list[dict]) -> str:
    lines = ["| scene | method | settings | time (s) | CPU (s) | RMSE | rel. | ratio | ratio (CPU) | bound | "
             "RMSE masked | ratio masked | maps MB | build (s) |", "|---" * 3 + "|---:" * 11 + "|"]
    for r in runs:
        lines.append(f"| {r.scene} | {r.method} | {r.settings} | {r.seconds:.2f} | {r.cpu_seconds:.2f} | "
                     f"{r.rmse:.4g} | {100 * r.rel:.1f}% | {fmt(r.ratio, '.2f')} | {fmt(r.ratio_cpu, '.2f')} | "
                     f"{fmt(r.bound, '.2f')} | {fmt(r.rmse_m, '.4g')} | {fmt(r.ratio_m, '.2f')} | "
                     f"{fmt(r.photon_memory_mb, '.1f')} | {fmt(r.photon_build_s, '.3f')} |")
    lines += ["", "| scene | clock | time (s) | Mitsuba volpath | morgana photon map | morgana path | "
              "photon map / Mitsuba | bound | path / Mitsuba | masked: photon map / Mitsuba | masked bound |",
              "|---|---" + "|---:" * 9 + "|"]
    for s in summary:
        lines.append(f"| {s['scene']} | {s['clock']} | {s['seconds']:g} | {fmt(s['mitsuba'], '.4g')} | "
                     f"{fmt(s['photon_map'], '.4g')} | {fmt(s['path'], '.4g')} | {fmt(s['photon_map_ratio'], '.2f')} | "
                     f"{fmt(s['photon_map_bound'], '.2f')} | {fmt(s['path_ratio'], '.2f')} | "
                     f"{fmt(s['photon_map_ratio_masked'], '.3f')} | {fmt(s['photon_map_bound_masked'], '.3f')} |")
    return "\n".join(lines) + "\n"


def colour_check(log) -> list[dict]:
    """The colour conversions alone: absolute linear sRGB of spectra of the fog box (400-700 nm,
    zero outside) by Mitsuba's route (its 5 nm CIE table, linearly interpolated and integrated,
    times 683.002 * 106.7503 after its normalisation) and by morgana's (30 band averages,
    piecewise-linear reconstruction, the CIE 1 nm table from colour-science), as a share of the
    largest channel. Systematic differences below the RMSEs measured are harmless."""
    import colour
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    scene = tomllib.loads((ROOT / SCENES["fog_box"].toml).read_text())
    tab = {k: (lambda s: lambda x: np.interp(x, s["nm"], s["values"]))(v) for k, v in scene["spectra"].items()}
    nm = np.arange(360, 831)
    cmf = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"][nm]
    fine = np.arange(360.0, 830.0, 0.01)
    mi_cmf = np.stack([np.interp(fine, nm, np.array([mi.cie1931_xyz(float(x)) for x in nm])[:, k]) for k in range(3)], -1)

    def inside(x):
        return (x >= 400) & (x <= 700)

    edges = np.linspace(400, 700, 31)
    centres = (edges[1:] + edges[:-1]) / 2
    cases = [("white light", lambda x: 10 + 0 * x), ("red wall", lambda x: 10 * tab["red"](x)),
             ("green wall", lambda x: 10 * tab["green"](x)), ("red, 3 bounces", lambda x: 10 * tab["red"](x) ** 3),
             ("green, 3 bounces", lambda x: 10 * tab["green"](x) ** 3)]
    rows = []
    for label, f in cases:
        mitsuba = XYZ_TO_SRGB @ (K_M * (f(fine) * inside(fine)) @ mi_cmf * 0.01)
        x = np.linspace(400, 700, 300_001)
        bands = [f(x[(x >= a) & (x <= b)]).mean() for a, b in zip(edges, edges[1:])]
        morgana = XYZ_TO_SRGB @ (K_M * (np.interp(nm, centres, bands) * inside(nm)) @ cmf)
        diff = 100 * (morgana - mitsuba) / np.abs(mitsuba).max()
        rows.append({"spectrum": label, "dR_pct": diff[0], "dG_pct": diff[1], "dB_pct": diff[2]})
        log(f"  colour check {label:17s} morgana - Mitsuba, % of the largest channel: {np.round(diff, 2).tolist()}")
    return rows


TOUCHING_LIGHT = {"origin": "[-0.883883, 0.813173, -0.05]", "u": "[0.070711, 0.070711, 0.0]", "v": "[0.0, 0.0, 0.1]"}


def leak_check(args, log) -> list[dict]:
    """Scene 2 without fog and sphere, every wall black but the floor, so only direct light from
    the snooted spot reaches the floor, lower right. Rendered with the light 5 mm inside the
    snoot's walls (as benchmarked) and with its edges touching them: the floor left of the beam
    (pixels 0-63 of the bottom 8 rows) must stay black in both renderers and both geometries."""
    base = (ROOT / SCENES["volume_caustic"].toml).read_text().replace('\n[world]\nmedium = "fog"\n', "\n")
    sphere = base.index('[[shape]]\nname = "glass sphere"')
    base = base[:sphere] + base[base.index("\n[[", sphere + 1) + 1:]
    for wall in ("ceiling", "back", "front", "left", "right"):
        base = re.sub(rf'(name = "{wall}"\n(?:[^\n]*\n){{4}}material = )"\w+"', r'\1"black"', base)
    light = base.index('name = "spot"')
    touching = base[:light] + re.sub(r"(?m)^(origin|u|v) = \[.*\]$", lambda m: f"{m[1]} = {TOUCHING_LIGHT[m[1]]}",
                                     base[light:])
    out = args.out / "leak_check"
    rows = []
    for geometry, text in (("5 mm inside the walls", base), ("edges touching the walls", touching)):
        runner = MitsubaRunner(text, args.threads)
        mi_img = runner.render(256, seed=3)[0]
        runner.close()
        mo_img = run_morgana(args.bin, text, {"method": "path", "spp": 256}, out / "m", "m", args.threads).rgb
        for label, img in ((MITSUBA, mi_img), (PATH, mo_img)):
            left, beam = float(img[120:, :64].mean()), float(img[120:, 64:].mean())
            rows.append({"light": geometry, "renderer": label, "floor_left_of_beam": left, "floor_in_beam": beam})
            log(f"  light {geometry:25s} {label:15s} floor left of the beam {left:9.2f}, in the beam {beam:9.2f}")
    return rows


def print_table(runs: list[Run], summary: list[dict]):
    print()
    print(f"{'scene':15s} {'method':18s} {'settings':64s} {'time s':>7s} {'CPU s':>7s} {'RMSE':>9s} {'rel':>6s} "
          f"{'ratio':>6s} {'r(CPU)':>6s} {'bound':>6s} {'r mask':>6s} {'maps MB':>7s} {'build s':>7s}")
    for r in runs:
        print(f"{r.scene:15s} {r.method:18s} {r.settings:64s} {r.seconds:7.2f} {r.cpu_seconds:7.2f} {r.rmse:9.4g} "
              f"{100 * r.rel:5.1f}% {fmt(r.ratio, '6.2f'):>6s} {fmt(r.ratio_cpu, '6.2f'):>6s} "
              f"{fmt(r.bound, '6.2f'):>6s} {fmt(r.ratio_m, '6.2f'):>6s} {fmt(r.photon_memory_mb, '7.1f'):>7s} "
              f"{fmt(r.photon_build_s, '7.3f'):>7s}")
    print()
    print("equal time (RMSE interpolated in log-log; ratio = morgana / Mitsuba; bound = morgana's raw RMSE over")
    print("Mitsuba's, an upper bound on the ratio; masked = without the pixels the scene's mask leaves out):")
    print(f"{'scene':15s} {'clock':5s} {'time s':>7s} {'Mitsuba':>10s} {'photon map':>11s} {'path':>10s} "
          f"{'pm ratio':>9s} {'pm bound':>9s} {'path ratio':>10s} {'pm masked':>10s} {'bound m':>8s}")
    for s in summary:
        print(f"{s['scene']:15s} {s['clock']:5s} {s['seconds']:7g} {fmt(s['mitsuba'], '10.4g'):>10s} "
              f"{fmt(s['photon_map'], '11.4g'):>11s} {fmt(s['path'], '10.4g'):>10s} "
              f"{fmt(s['photon_map_ratio'], '9.2f'):>9s} {fmt(s['photon_map_bound'], '9.2f'):>9s} "
              f"{fmt(s['path_ratio'], '10.2f'):>10s} {fmt(s['photon_map_ratio_masked'], '10.3f'):>10s} "
              f"{fmt(s['photon_map_bound_masked'], '8.3f'):>8s}")


# ---------------------------------------------------------------------------------------------
# The benchmark
# ---------------------------------------------------------------------------------------------

MITSUBA, PHOTON_MAP, PATH = "mitsuba volpath", "morgana photon map", "morgana path"


def photon_stats(report: dict) -> tuple[float, float, float]:
    """Photon-map memory (MB), kd-tree build time (s) and photon tracing time (s), all maps."""
    maps = report.get("maps", [])
    if not maps:
        return NAN, NAN, NAN
    mem = sum(m["memory_bytes"] for m in maps) / 1e6
    build = sum(m["build_seconds"] for m in maps)
    trace = sum({m["trace_seconds"] for m in maps})  # the global and volume maps share one pass
    return mem, build, trace


def settings_label(integ: dict) -> str:
    keys = ("photons", "caustic_photons", "volume_k", "k", "march_step", "final_gather", "gather_rays", "spp",
            "volume_estimate")
    return " ".join(f"{k}={integ[k]}" for k in keys if k in integ)


def series(spec: SceneSpec, quick: bool):
    """(method, settings label, [integrator] table or Mitsuba spp) of every run of a scene."""
    cut = (lambda xs: xs[:3]) if quick else (lambda xs: xs)
    for spp in cut(spec.mitsuba_spp):
        yield MITSUBA, f"spp={spp}", spp
    for integ in cut(spec.photon_map):
        yield PHOTON_MAP, settings_label(integ), {"method": "photon_map", **PM_COMMON, **integ}
    for spp in cut(spec.morgana_path_spp):
        yield PATH, f"spp={spp}", {"method": "path", "spp": spp}


def load_scene(name: str, spec: SceneSpec, args, log):
    """The scene's text, its Mitsuba translation, a lazy Mitsuba runner and the reference."""
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    base = (ROOT / spec.toml).read_text()
    mi_dict = to_mitsuba(tomllib.loads(base), mi)
    runner = []

    def get_runner() -> MitsubaRunner:
        if not runner:
            runner.append(MitsubaRunner(base, args.threads))
        return runner[0]

    out = args.out / name
    out.mkdir(parents=True, exist_ok=True)
    log(f"{name}: reference, Mitsuba volpath {args.ref_spp} spp in {args.ref_chunks} chunks")
    ref = load_or_render_reference(out / "reference.npz", scene_digest(mi_dict, mi.__version__), get_runner,
                                   args.ref_spp, args.ref_chunks, log)
    return base, get_runner, ref, runner


def scene_metrics(spec: SceneSpec, scene: dict, ref: Reference, out: Path, log) -> tuple[Metric, Metric | None]:
    full = Metric.over(ref, np.ones(ref.rgb.shape[:2], dtype=bool))
    log(f"  reference: {ref.spp} spp, {ref.seconds:.0f} s, noise RMSE {full.noise:.4g} "
        f"({100 * full.noise / full.mean:.2f}% of the mean {full.mean:.4g})")
    if spec.mask_glints_dilate is None:
        return full, None
    glints = specular_light_mask(scene, spec.mask_glints_dilate)
    write_png(out / "glint_mask.png", np.repeat(glints[..., None], 3, axis=-1).astype(float), 1.0)
    masked = Metric.over(ref, ~glints)
    log(f"  mask: {int(glints.sum())} pixels that see the light through glass alone left out (glint_mask.png); "
        f"noise RMSE {masked.noise:.4g} ({100 * masked.noise / masked.mean:.2f}% of the mean {masked.mean:.4g})")
    return full, masked


def surfaces_only(scene: dict, mi):
    """The scene's surfaces and emitters as a Mitsuba scene (media, the sensor and the shapes'
    exterior media dropped), and the index of refraction of each dielectric shape by its
    Mitsuba id (`shape_<i>`)."""
    geo = {k: v for k, v in to_mitsuba(scene, mi).items() if not k.startswith("medium_")}
    geo.pop("sensor")
    for v in geo.values():
        if isinstance(v, dict):
            v.pop("exterior", None)
    iors = {f"shape_{i}": float(m["ior"]) for i, s in enumerate(scene.get("shape", []))
            for m in scene.get("material", []) if m["name"] == s.get("material") and m["type"] == "dielectric"}
    return mi.load_dict(geo), iors


def specular_light_mask(scene: dict, dilate: int, sub: int = 4, max_depth: int = 6) -> np.ndarray:
    """Pixels where some of `sub` x `sub` camera rays reach an emitter through dielectric surfaces
    alone (every reflection/refraction branch followed, media ignored), grown by `dilate` pixels:
    the glints, whose noise measures how often a renderer's few eye samples pick the Fresnel
    branch that sees a small bright light, not its light transport in the fog."""
    import mitsuba as mi

    mi_scene, iors = surfaces_only(scene, mi)
    cam = scene["camera"]
    w, h = int(cam["width"]), int(cam["height"])
    mask = np.zeros((h, w), dtype=bool)
    for y in range(h):
        for x in range(w):
            mask[y, x] = any(
                reaches_light(mi_scene, iors, np.asarray(cam["position"], float), d, 1.0, max_depth)
                for d in camera_dirs(cam, x, y, sub)
            )
    grown = mask.copy()
    for dy in range(-dilate, dilate + 1):
        for dx in range(-dilate, dilate + 1):
            grown |= np.roll(np.roll(mask, dy, axis=0), dx, axis=1)
    return grown


def camera_dirs(cam: dict, x: int, y: int, sub: int):
    """Directions of a sub x sub grid of rays through pixel (x, y), as morgana's camera makes
    them (src/geometry/camera.rs: full vertical fov, pixel (0, 0) top left)."""
    pos, look = np.asarray(cam["position"], float), np.asarray(cam["look_at"], float)
    fwd = (look - pos) / np.linalg.norm(look - pos)
    right = np.cross(fwd, np.asarray(cam.get("up", [0.0, 1.0, 0.0]), float))
    right /= np.linalg.norm(right)
    up = np.cross(right, fwd)
    w, h = int(cam["width"]), int(cam["height"])
    tan_half = math.tan(math.radians(cam["fov_deg"]) / 2)
    for j in range(sub):
        for i in range(sub):
            sx = (2 * (x + (i + 0.5) / sub) / w - 1) * tan_half * w / h
            sy = (1 - 2 * (y + (j + 0.5) / sub) / h) * tan_half
            d = fwd + sx * right + sy * up
            yield d / np.linalg.norm(d)


def reaches_light(mi_scene, iors: dict, o: np.ndarray, d: np.ndarray, weight: float, depth: int) -> bool:
    """Whether the ray (o, d), continued through dielectrics by both Fresnel branches, hits an
    emitter's front after at least one dielectric event (`weight` < 1 marks that one happened)."""
    import mitsuba as mi

    si = mi_scene.ray_intersect(mi.Ray3f(mi.Point3f(*o), mi.Vector3f(*d)))
    if not si.is_valid():
        return False
    n = np.array(si.n)
    if si.shape.is_emitter():
        return weight < 1.0 and np.dot(n, d) < 0
    ior = iors.get(si.shape.id())
    if ior is None or depth == 0:
        return False
    p = np.array(si.p)
    entering = np.dot(n, d) < 0
    nf = n if entering else -n
    eta = 1.0 / ior if entering else ior
    refl = d - 2 * np.dot(d, nf) * nf
    cos_i = -np.dot(d, nf)
    k = 1 - eta * eta * (1 - cos_i * cos_i)
    branches = [(p + 1e-5 * nf, refl)]
    if k > 0:
        branches.append((p - 1e-5 * nf, eta * d + (eta * cos_i - math.sqrt(k)) * nf))
    return any(reaches_light(mi_scene, iors, a, b, 0.5, depth - 1) for a, b in branches)


def bench_scene(name: str, spec: SceneSpec, args, log) -> tuple[list[Run], list[dict]]:
    base, get_runner, ref, started = load_scene(name, spec, args, log)
    out = args.out / name
    full, masked = scene_metrics(spec, tomllib.loads(base), ref, out, log)
    if args.reference_only:
        for r in started:
            r.close()
        return [], []
    runs: list[Run] = []
    for i, (method, label, what) in enumerate(series(spec, args.quick)):
        report = None
        if method == MITSUBA:
            img, seconds, cpu = get_runner().render(what, seed=1 + i)
            (out / f"run{i}").mkdir(exist_ok=True)
            np.save(out / f"run{i}" / "rgb.npy", img)
        else:
            r = run_morgana(args.bin, base, {**what, "seed": 1 + i}, out / f"run{i}", f"{name}_run{i}", args.threads)
            img, seconds, cpu, report = r.rgb, r.seconds, r.cpu_seconds, r.report
        raw, corr = full.errors(img)
        raw_m, corr_m = masked.errors(img) if masked else (NAN, NAN)
        mem, build, trace = photon_stats(report) if report else (NAN, NAN, NAN)
        runs.append(Run(name, method, label, seconds, cpu, raw, corr, corr / full.mean, raw_m, corr_m,
                        photon_memory_mb=mem, photon_build_s=build, photon_trace_s=trace, rgb=img))
        log(f"  {method:18s} {label:64s} {seconds:7.2f} s (CPU {cpu:7.2f} s, load {os.getloadavg()[0]:4.1f})  "
            f"RMSE {corr:.4g} ({100 * corr / full.mean:.2f}%), raw {raw:.4g}"
            + (f", masked {corr_m:.4g}" if masked else ""))
    for r in started:
        r.close()
    set_ratios(runs)
    previews(out, ref, runs, spec.regions, log)
    if spec.photon_map and not args.quick:
        noise_and_bias(base, spec, runs, full, masked, args, out, log)
    return runs, summaries(name, runs, args)


PROGRESSIVE, ADAPTIVE = "morgana progressive", "morgana adaptive"
# Mitsuba's budgets in --progressive mode (--mitsuba-spp): its RMSE at longer times follows from
# the largest by the law of an unbiased estimator (`mitsuba_at`).
PROGRESSIVE_MITSUBA_SPP = [64, 256, 1024]


def bench_scene_progressive(name: str, spec: SceneSpec, args, log) -> tuple[list[Run], list[dict]]:
    """`--progressive`: Mitsuba at PROGRESSIVE_MITSUBA_SPP, then morgana's progressive photon
    mapping as one run stopped and resumed at growing pass counts (scripts/progressive_chain.py),
    uniform and, where the scene says so, adaptive; each stop is a point of morgana's RMSE(time)."""
    base, get_runner, ref, started = load_scene(name, spec, args, log)
    out = args.out / name
    full, masked = scene_metrics(spec, tomllib.loads(base), ref, out, log)
    runs: list[Run] = []
    stops = out / "stops"  # every image measured, as linear sRGB .npy, to measure again later
    stops.mkdir(exist_ok=True)

    def add(method, label, img, seconds, cpu):
        raw, corr = full.errors(img)
        raw_m, corr_m = masked.errors(img) if masked else (NAN, NAN)
        cross, cross_se = full.cross(img)
        runs.append(Run(name, method, label, seconds, cpu, raw, corr, corr / full.mean, raw_m, corr_m, cross, cross_se,
                        rgb=img))
        log(f"  {method:26s} {label:40s} {seconds:7.2f} s (CPU {cpu:7.2f} s, load {os.getloadavg()[0]:4.1f})  "
            f"RMSE {corr:.4g} ({100 * corr / full.mean:.2f}%), raw {raw:.4g}"
            + (f", masked {corr_m:.4g}" if masked else "")
            + (f", split-reference {cross:.4g} ({100 * cross / full.mean:.2f}%; its square {cross**2:.4g} "
               f"± {cross_se:.2g})" if math.isfinite(cross) else ""))
        np.save(stops / f"{method.replace(' ', '_')}_{label.replace('=', '_')}.npy", img)

    for i, spp in enumerate(args.mitsuba_spp):
        img, seconds, cpu = get_runner().render(spp, seed=1 + i)
        add(MITSUBA, f"spp={spp}", img, seconds, cpu)
    for r in started:
        r.close()
    variants = [(PROGRESSIVE, [])] + ([(ADAPTIVE, ["--adaptive"])] if spec.progressive_adaptive else [])
    if args.no_adaptive:
        variants = variants[:1]
    if args.no_uniform:
        variants = variants[1:]
    for method, extra in variants:
        work = out / method.replace(" ", "_")
        work.mkdir(parents=True, exist_ok=True)
        scene = work / f"{name}.toml"
        integ = {"method": "photon_map", **PM_COMMON, **spec.progressive, "seed": 7}
        if args.volume_estimate:
            integ["volume_estimate"] = args.volume_estimate
        scene.write_text(variant_toml(base, integ, name))
        log(f"  {method}: {settings_label(integ)} a pass, up to {args.max_cpu:g} CPU s")
        for step in progressive_chain.run(args.bin, scene, work, args.threads, args.max_cpu, extra, log):
            add(method, f"passes={step.passes}", read_exr_rgb(work / f"{name}.exr"), step.phase_s, step.cpu_s)
    set_ratios(runs)
    previews(out, ref, runs, spec.regions, log)
    means = {"rmse": full.mean, "rmse_m": masked.mean if masked else NAN, "rmse_x": full.mean}
    return runs, progressive_summary(name, runs, means, args, log)


def mitsuba_at(runs: list[Run], key: str, t: float, cpu: bool) -> float:
    """Mitsuba's RMSE at time t from its largest run by the law of an unbiased estimator: its
    squared error is its variance, which falls as 1/spp, and its time grows as spp, so
    RMSE(t) = RMSE(t₀) √(t₀/t). (Measured on these scenes: Mitsuba's RMSE falls as t^-0.50,
    benchmarks.md.) The runs' own fit is logged as a check."""
    last = [r for r in runs if r.method == MITSUBA][-1]
    t0 = last.cpu_seconds if cpu else last.seconds
    return getattr(last, key) * math.sqrt(t0 / t)


def progressive_summary(name: str, runs: list[Run], means: dict, args, log) -> list[dict]:
    """Each progressive variant's RMSE at --cpu-times (and --times of wall/phase time), Mitsuba's
    there, their ratio, and the slope of morgana's RMSE over the chain."""
    ts, es = curve(runs, MITSUBA, cpu=True)
    slope_mi, _, _ = progressive_chain.fit_slope(ts, es)
    log(f"  {name}: Mitsuba's RMSE against CPU time over its runs: slope {slope_mi:.3f} (the law: -0.5)")
    rows = []
    for method in (PROGRESSIVE, ADAPTIVE):
        if not any(r.method == method for r in runs):
            continue
        for key, label in (("rmse", "all pixels"), ("rmse_m", "masked"), ("rmse_x", "all pixels, split reference")):
            t, e = curve(runs, method, key, cpu=True)
            if not all(math.isfinite(x) for x in e):
                continue
            sel = [(a, b) for a, b in zip(t, e) if args.fit_from <= a <= args.fit_to]
            slope, _, n = progressive_chain.fit_slope([a for a, _ in sel], [b for _, b in sel])
            log(f"  {name} {method} ({label}): RMSE against CPU time, slope {slope:.3f} over "
                f"{args.fit_from:g}..{args.fit_to:g} s ({n} points)")
            for cpu_t in args.cpu_times:
                mo = loglog_interp(t, e, cpu_t)
                mi_ = mitsuba_at(runs, key, cpu_t, cpu=True)
                rows.append({"scene": name, "method": method, "pixels": label, "clock": "cpu", "seconds": cpu_t,
                             "morgana": mo, "mitsuba": mi_, "ratio": mo / mi_, "slope": slope,
                             "reference_mean": means[key]})
                log(f"    {cpu_t:6g} CPU s: morgana {mo:.4g} ({100 * mo / means[key]:.1f}% of the mean), "
                    f"Mitsuba {mi_:.4g} ({100 * mi_ / means[key]:.1f}%), ratio {mo / mi_:.3f}")
    return rows


def summaries(name: str, runs: list[Run], args) -> list[dict]:
    return equal_time_summary(name, runs, args.times, cpu=False) + equal_time_summary(name, runs, args.cpu_times, True)


def noise_and_bias(base: str, spec: SceneSpec, runs: list[Run], full: Metric, masked: Metric | None, args, out, log):
    """Splits the largest photon-map run's error into noise and bias: a second render with
    another seed gives the noise, sigma^2 = |a - b|^2 / 2 per pixel and channel, and the rest of
    the (reference-noise-corrected) squared error is bias: bias^2 = RMSE^2 - sigma^2."""
    last = [r for r in runs if r.method == PHOTON_MAP][-1]
    settings = {"method": "photon_map", **PM_COMMON, **spec.photon_map[-1], "seed": 10_001}
    again = run_morgana(args.bin, base, settings, out / "run_seed2", "seed2", args.threads).rgb
    for label, m, rmse_c in (("all pixels", full, last.rmse), ("masked", masked, last.rmse_m)):
        if m is None:
            continue
        sigma = float(np.sqrt(np.mean((last.rgb[m.pixels] - again[m.pixels]) ** 2) / 2))
        bias = math.sqrt(max(rmse_c**2 - sigma**2, 0.0))
        log(f"  photon map {last.settings}, {label}: RMSE {rmse_c:.4g} = noise {sigma:.4g} "
            f"({100 * sigma / m.mean:.2f}%) (+) bias {bias:.4g} ({100 * bias / m.mean:.2f}%)")


def previews(out: Path, ref: Reference, runs: list[Run], regions: dict, log):
    """Preview PNGs (one exposure for all) and region means of the largest budget per method."""
    white = float(np.percentile(ref.rgb.mean(axis=-1), 99.5))
    write_png(out / "reference.png", ref.rgb, white)
    log("  region means (linear sRGB): the reference, then each method's largest budget")
    rows = [("reference", ref.rgb)]
    for method in dict.fromkeys(r.method for r in runs):
        last = [r for r in runs if r.method == method][-1]
        write_png(out / f"{method.replace(' ', '_')}.png", last.rgb, white)
        rows.append((method, last.rgb))
    for label, img in rows:
        for k, v in region_means(img, regions).items():
            log(f"    {label:18s} {k:18s} {np.round(v, 1).tolist()}")
    log(f"  32x32-pixel block means against the reference (luminance, %; the reference's own block noise "
        f"{block_noise(ref):.1f}% rms):")
    for label, img in rows[1:]:
        dev = block_deviation(img, ref)
        log(f"    {label:18s} rms {np.sqrt(np.mean(dev**2)):5.1f}%  " + " ".join(f"{d:+.0f}" for d in dev.ravel()))


BLOCK = 32


def blocks(x: np.ndarray) -> np.ndarray:
    h, w = x.shape[:2]
    return x.reshape(h // BLOCK, BLOCK, w // BLOCK, BLOCK).mean(axis=(1, 3))


def block_deviation(img: np.ndarray, ref: Reference) -> np.ndarray:
    """Per 32x32 block, the image's mean luminance (mean of R, G, B) over the reference's, in %."""
    return 100 * (blocks(img.mean(axis=-1)) / blocks(ref.rgb.mean(axis=-1)) - 1)


def block_noise(ref: Reference) -> float:
    """RMS over blocks of the reference's relative standard error of a block mean, in %."""
    var = blocks(ref.variance.mean(axis=-1)) / BLOCK**2  # of a block mean; channels taken as correlated
    return float(100 * np.sqrt(np.mean(var / blocks(ref.rgb.mean(axis=-1)) ** 2)))


POINT_SPOT = """[[light]]
name = "point spot"
type = "spot"
position = [-0.848528, 0.848528, 0.0]
direction = [1.0, -1.0, 0.0]
cone_deg = 20.8
spectrum = 1.0
scale = 8.1
"""


def point_spot_check(args, log) -> list[dict]:
    """Scene 2 with the snoot and its area light replaced by a point spotlight (same place, axis
    and beam, on-axis intensity L A = 8.1 W sr^-1 nm^-1): region means of Mitsuba volpath,
    morgana path and morgana's photon map. A unidirectional path tracer cannot reach a delta
    light through glass, so the first two lack the volume caustic however many samples they
    take; this is why scene 2 uses a finite source."""
    spec = SCENES["volume_caustic"]
    base = (ROOT / spec.toml).read_text()
    cut = base.index("# The snoot")
    text = base[:cut] + POINT_SPOT
    out = args.out / "point_spot"
    out.mkdir(parents=True, exist_ok=True)
    (out / "volume_caustic_point_spot.toml").write_text(text)
    spp = 256 if args.quick else 1024
    runner = MitsubaRunner(text, args.threads)
    img, seconds, _ = runner.render(spp, seed=7)
    runner.close()
    renders = [(f"mitsuba volpath spp={spp}", img)]
    path = run_morgana(args.bin, text, {"method": "path", "spp": spp}, out / "path", "path", args.threads)
    renders.append((f"morgana path spp={spp}", path.rgb))
    pm_settings = {"method": "photon_map", **PM_COMMON, **spec.photon_map[len(spec.photon_map) // 2]}
    pm = run_morgana(args.bin, text, pm_settings, out / "pm", "pm", args.threads)
    renders.append((f"morgana photon map {settings_label(pm_settings)}", pm.rgb))
    rows = []
    log("point spotlight (delta light behind glass): mean linear sRGB luminance per region")
    white = float(np.percentile(pm.rgb.mean(axis=-1), 99.5))
    for label, rgb in renders:
        write_png(out / f"{label.split(' spp')[0].split(' photons')[0].replace(' ', '_')}.png", rgb, white)
        means = {k: float(np.mean(v)) for k, v in region_means(rgb, spec.regions).items()}
        rows.append({"render": label, **means})
        log(f"  {label:70s} " + "  ".join(f"{k} {v:9.1f}" for k, v in means.items()))
    return rows


def parse_args(argv):
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("--bin", type=Path, default=ROOT / "target/release/morgana")
    p.add_argument("--out", type=Path, default=ROOT / "out/mitsuba_bench")
    p.add_argument("--scenes", nargs="+", default=list(SCENES), choices=list(SCENES))
    p.add_argument("--threads", type=int, default=2)
    p.add_argument("--ref-spp", type=int, default=8192)
    p.add_argument("--ref-chunks", type=int, default=8)
    p.add_argument("--times", type=float, nargs="+", default=[5, 10, 20, 45], help="wall seconds")
    p.add_argument("--cpu-times", type=float, nargs="+", default=[10, 20, 50, 90], help="CPU seconds")
    p.add_argument("--leak-check", action="store_true",
                   help="only the check that Mitsuba leaks light past occluders touching an emitter")
    p.add_argument("--retable", action="store_true", help="recompute the tables from OUT/runs.csv, render nothing")
    p.add_argument("--quick", action="store_true", help="the first three budgets of each series only")
    p.add_argument("--no-point-spot", action="store_true", help="skip the point-spotlight check of scene 2")
    p.add_argument("--reference-only", action="store_true", help="render (or reuse) the references only")
    p.add_argument("--progressive", action="store_true",
                   help="morgana's progressive runs (uniform and adaptive) against Mitsuba up to --max-cpu CPU s")
    p.add_argument("--max-cpu", type=float, default=300.0, help="--progressive: CPU seconds of each morgana run")
    p.add_argument("--fit-from", type=float, default=10.0, help="--progressive: slopes fitted from this CPU time")
    p.add_argument("--fit-to", type=float, default=300.0, help="--progressive: ... to this CPU time")
    p.add_argument("--no-adaptive", action="store_true", help="--progressive: the uniform passes only")
    p.add_argument("--no-uniform", action="store_true",
                   help="--progressive: the adaptive passes only (where a scene has them)")
    p.add_argument("--volume-estimate", choices=["point", "beam", "photon_beams"],
                   help="--progressive: [integrator] volume_estimate of morgana's passes (unset: the scene's "
                        "default); give another --out, or the runs replace the default's")
    p.add_argument("--mitsuba-spp", type=int, nargs="+", default=PROGRESSIVE_MITSUBA_SPP,
                   help="--progressive: Mitsuba's budgets (its RMSE beyond the largest by the 1/sqrt(t) law)")
    return p.parse_args(argv)


def retable(args) -> int:
    """Ratios, summaries and tables again from OUT/runs.csv (e.g. for other --times)."""
    with open(args.out / "runs.csv", newline="") as f:
        rows = list(csv.DictReader(f))
    floats = set(RUN_FIELDS) - {"scene", "method", "settings"}
    runs = [Run(**{k: (float(v) if k in floats else v) for k, v in row.items() if k in RUN_FIELDS}) for row in rows]
    summary = []
    for name in dict.fromkeys(r.scene for r in runs):
        sel = [r for r in runs if r.scene == name]
        set_ratios(sel)
        summary += summaries(name, sel, args)
    write_outputs(args.out, runs, summary)
    print_table(runs, summary)
    return 0


def write_outputs(out: Path, runs: list[Run], summary: list[dict]):
    write_csv(out / "runs.csv", [{k: getattr(r, k) for k in RUN_FIELDS} for r in runs])
    write_csv(out / "equal_time.csv", summary)
    (out / "table.md").write_text(markdown(runs, summary))


def main(argv=None):
    args = parse_args(argv)
    args.out.mkdir(parents=True, exist_ok=True)
    log_file = open(args.out / "log.txt", "a")

    def log(msg):
        print(msg, flush=True)
        log_file.write(msg + "\n")
        log_file.flush()

    log(f"peer_mitsuba: {time.strftime('%Y-%m-%d %H:%M:%S')}, threads {args.threads}, morgana {args.bin}, "
        f"{os.cpu_count()} CPUs, load {os.getloadavg()[0]:.1f}")
    if args.retable:
        return retable(args)
    if args.leak_check:
        write_csv(args.out / "leak_check.csv", leak_check(args, log))
        return 0
    write_csv(args.out / "colour_check.csv", colour_check(log))
    all_runs, all_summary = [], []
    if args.progressive:
        for name in args.scenes:
            runs, summary = bench_scene_progressive(name, SCENES[name], args, log)
            all_runs += runs
            all_summary += summary
        tag = "_".join(args.scenes)
        write_csv(args.out / f"progressive_runs_{tag}.csv", [{k: getattr(r, k) for k in RUN_FIELDS} for r in all_runs])
        write_csv(args.out / f"progressive_{tag}.csv", all_summary)
        print(f"\nwrote {args.out}/progressive_runs_{tag}.csv, progressive_{tag}.csv, log.txt and preview PNGs")
        return 0
    for name in args.scenes:
        runs, summary = bench_scene(name, SCENES[name], args, log)
        all_runs += runs
        all_summary += summary
    if args.reference_only:
        return 0
    write_outputs(args.out, all_runs, all_summary)
    print_table(all_runs, all_summary)
    if not args.no_point_spot and "volume_caustic" in args.scenes:
        write_csv(args.out / "point_spot.csv", point_spot_check(args, log))
    print(f"\nwrote {args.out}/runs.csv, equal_time.csv, table.md, point_spot.csv, log.txt and preview PNGs")
    return 0


if __name__ == "__main__":
    sys.exit(main())
