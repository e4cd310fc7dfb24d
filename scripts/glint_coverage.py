#!/usr/bin/env python3
"""Where, inside a few pixels, a small light seen through glass lands: a third opinion on the
volume caustic's glints, independent of both renderers' sampling (issue 17, "Measured goals").

    .venv/bin/python scripts/glint_coverage.py [--scene volume_caustic] [--sub 48] Y,X ...

For each pixel (row Y, column X) and its 3 x 3 neighbourhood: a sub x sub grid of camera rays
(morgana's camera, `peer_mitsuba.camera_dirs`) followed through every dielectric surface by both
Fresnel branches (exact unpolarised Fresnel weights), media ignored, each ray's weight summed
where it reaches an emitter's front after at least one dielectric event: the pixel's share of
L S+ E light, up to the fog's transmittance (nearly the same over a glint's few pixels). Printed
beside morgana's and the Mitsuba reference's luminance sums of the same pixels, each normalised
to its neighbourhood's sum, so that the three distributions of the glint over its pixels can be
compared whatever the absolute scale. Mitsuba's ray casting (scalar_spectral) does the geometry.
"""

from __future__ import annotations

import argparse
import math
import sys
import tomllib
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parent))
import peer_mitsuba as pm  # noqa: E402


def fresnel(cos_i: float, eta: float) -> float:
    """Unpolarised Fresnel reflectance for relative index eta = n_i / n_t (Born & Wolf §1.5)."""
    sin2_t = eta * eta * (1.0 - cos_i * cos_i)
    if sin2_t >= 1.0:
        return 1.0
    cos_t = math.sqrt(1.0 - sin2_t)
    rs = (eta * cos_i - cos_t) / (eta * cos_i + cos_t)
    rp = (cos_i - eta * cos_t) / (cos_i + eta * cos_t)
    return 0.5 * (rs * rs + rp * rp)


def light_weight(mi, mi_scene, iors: dict, o, d, weight: float, depth: int, specular: bool) -> float:
    """The Fresnel-weighted share of ray (o, d) that reaches an emitter's front through dielectric
    surfaces, at least one of them (`specular`)."""
    si = mi_scene.ray_intersect(mi.Ray3f(mi.Point3f(*o), mi.Vector3f(*d)))
    if not si.is_valid() or weight < 1e-4:
        return 0.0
    n = np.array(si.n)
    if si.shape.is_emitter():
        return weight if specular and np.dot(n, d) < 0 else 0.0
    ior = iors.get(si.shape.id())
    if ior is None or depth == 0:
        return 0.0
    p = np.array(si.p)
    entering = np.dot(n, d) < 0
    nf = n if entering else -n
    eta = 1.0 / ior if entering else ior
    cos_i = -float(np.dot(d, nf))
    r = fresnel(cos_i, eta)
    total = light_weight(mi, mi_scene, iors, p + 1e-5 * nf, d + 2 * cos_i * nf, weight * r, depth - 1, True)
    if r < 1.0:
        cos_t = math.sqrt(1 - eta * eta * (1 - cos_i * cos_i))
        t = eta * d + (eta * cos_i - cos_t) * nf
        total += light_weight(mi, mi_scene, iors, p - 1e-5 * nf, t, weight * (1 - r), depth - 1, True)
    return total


def main(argv=None) -> int:
    p = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    p.add_argument("pixels", nargs="+", help="Y,X (row, column) at the centre of each neighbourhood")
    p.add_argument("--scene", default="volume_caustic", choices=list(pm.SCENES))
    p.add_argument("--sub", type=int, default=48, help="rays per pixel side")
    p.add_argument("--morgana", type=Path,
                   default=pm.ROOT / "out/mitsuba_bench/volume_caustic/morgana_adaptive/volume_caustic.exr")
    p.add_argument("--out", type=Path, default=pm.ROOT / "out/mitsuba_bench")
    p.add_argument("--camera", choices=["morgana", "mitsuba"], default="morgana",
                   help="whose camera makes the rays: morgana's (peer_mitsuba.camera_dirs) or the translated "
                        "scene's Mitsuba sensor (sample_ray at the same film positions)")
    args = p.parse_args(argv)
    import mitsuba as mi

    mi.set_variant("scalar_spectral")
    scene = tomllib.loads((pm.ROOT / pm.SCENES[args.scene].toml).read_text())
    mi_scene, iors = pm.surfaces_only(scene, mi)
    cam = scene["camera"]
    o = np.asarray(cam["position"], float)
    rays = (lambda x, y: ((o, d) for d in pm.camera_dirs(cam, x, y, args.sub)))
    if args.camera == "mitsuba":
        sensor = mi.load_dict({k: v for k, v in pm.to_mitsuba(scene, mi)["sensor"].items() if k != "medium"})
        width, height = int(cam["width"]), int(cam["height"])

        def rays(x, y):
            for j in range(args.sub):
                for i in range(args.sub):
                    pos = mi.Point2f((x + (i + 0.5) / args.sub) / width, (y + (j + 0.5) / args.sub) / height)
                    ray, _ = sensor.sample_ray(0.0, 0.5, pos, mi.Point2f(0.5, 0.5))
                    yield np.array(ray.o), np.array(ray.d)
    z = np.load(args.out / args.scene / "reference.npz")
    ref = z["rgb"].sum(-1)
    var = z["variance"].sum(-1)
    mo = pm.read_exr_rgb(args.morgana).sum(-1)
    for spec in args.pixels:
        cy, cx = (int(v) for v in spec.split(","))
        cover = np.zeros((3, 3))
        for j, y in enumerate(range(cy - 1, cy + 2)):
            for i, x in enumerate(range(cx - 1, cx + 2)):
                w = [light_weight(mi, mi_scene, iors, ro, rd, 1.0, 6, False) for ro, rd in rays(x, y)]
                cover[j, i] = float(np.mean(w))
        win = (slice(cy - 1, cy + 2), slice(cx - 1, cx + 2))
        print(f"pixels ({cy - 1}..{cy + 1}, {cx - 1}..{cx + 1}), each a share of its 3 x 3 sum "
              f"(reference's ± from its chunks):")
        for j in range(3):
            y = cy - 1 + j
            cells = []
            for i in range(3):
                x = cx - 1 + i
                c = cover[j, i] / max(cover.sum(), 1e-30)
                m = mo[y, x] / mo[win].sum()
                r = ref[y, x] / ref[win].sum()
                dr = math.sqrt(var[y, x]) / ref[win].sum()
                cells.append(f"cover {c:5.3f} morgana {m:5.3f} ref {r:5.3f}±{dr:5.3f}")
            print("   " + " | ".join(cells))
        print(f"   coverage-weighted share of the pixels seeing the light: {cover.sum():.4g} (sum over the 9)")
    return 0


if __name__ == "__main__":
    sys.exit(main())
