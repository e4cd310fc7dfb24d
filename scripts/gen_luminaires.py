#!/usr/bin/env python3
"""Writes the project's own photometric files (luminaires/*.ies, *.ldt) from analytic intensity
distributions, for the examples. Python 3 standard library only; deterministic output.

    python3 scripts/gen_luminaires.py            # rewrite the files in luminaires/
    python3 scripts/gen_luminaires.py --check    # exit 1 if a file differs from what it would write

Each distribution I(C, gamma) (candela; C-gamma system of CIE 121 / LM-63 type C: gamma = 0 is
nadir, C = 0 the luminaire's length axis, C turning counterclockwise seen from above) is sampled
on the file's grid. The flux is integrated here from the analytic function by the midpoint rule
on a fine grid (0.05 deg in gamma, 0.25 deg in C), independently of morgana's reader, and written
into the file: the lamp lumens (LM-63 relative photometry) or LORL x lamp flux (EULUMDAT), and for
absolute LM-63 files the keyword [_FLUX_ANALYTIC_LM]. tests/luminaire_project_files.rs checks that
morgana's web of each file carries that flux.

Files:
- road_batwing.ies        LM-63-2002, absolute photometry, type C, 0-180 deg horizontal (symmetric
                          about the C0-C180 plane): a street light whose batwing throws light
                          along the road (C90/C270) at gamma ~ 65 deg, more to the street side
                          (C0) than to the house side (C180), full cut-off above 88 deg.
- underwater_flood_54.ies LM-63-2002, relative photometry (lamp lumens, LOR 85 %), rotationally
                          symmetric flood, 54 deg full width at half maximum, cut off at 90 deg.
- office_pendant.ldt      EULUMDAT, Isym 4: a direct/indirect linear pendant, 7000 lm, 33 % of
                          it downward (DFF), batwing-free cosine-power lobes, the downward lobe
                          wider across the luminaire (C90) than along it (C0).
- office_linear_led.ldt   EULUMDAT, Isym 4: a surface-mounted linear LED, 1500 mm x 60 mm opening,
                          5540 lm, a cosine^1.1 lobe narrowed along its length.
EULUMDAT field 27 (the ten direct ratios for room indices 0.6-5) is written as zeros: morgana does
not use them and this script does not compute them.
"""

import math
import sys
from pathlib import Path

OUT = Path(__file__).resolve().parent.parent / "luminaires"


def smoothstep_down(x, lo, hi):
    """1 below lo, 0 above hi, smooth in between."""
    if x <= lo:
        return 1.0
    if x >= hi:
        return 0.0
    t = (x - lo) / (hi - lo)
    return 1.0 - t * t * (3.0 - 2.0 * t)


def road(c, g):
    """Street light batwing (cd), peak about 5200 cd along the road at gamma 65 deg."""
    if g >= 88.0:
        return 0.0
    if c > 180.0:  # symmetric about the C0-C180 plane, as the file stores it
        c = 360.0 - c
    cut = smoothstep_down(g, 76.0, 88.0)
    cr = math.radians(c)
    along = math.sin(cr) ** 2
    across = math.cos(cr) ** 2
    street = across if c < 90.0 else 0.0
    house = across if c > 90.0 else 0.0
    f_along = 1350.0 * math.cos(math.radians(g)) ** 0.3 + 4190.0 * math.exp(-(((g - 65.0) / 13.0) ** 2))
    f_street = 1350.0 * math.cos(math.radians(g)) ** 0.3 + 1600.0 * math.exp(-(((g - 50.0) / 16.0) ** 2))
    f_house = 1350.0 * math.cos(math.radians(g)) ** 2.5
    return cut * (along * f_along + street * f_street + house * f_house)


FLOOD_HALF_DEG = 27.0


def flood(c, g):
    """Flood, 54 deg FWHM: a Gaussian in gamma, 1000 cd on axis."""
    if g >= 90.0:
        return 0.0
    return 1000.0 * math.exp(-math.log(2.0) * (g / FLOOD_HALF_DEG) ** 2) * smoothstep_down(g, 80.0, 90.0)


def pendant_shape(c, g):
    """Direct/indirect pendant, unscaled: (down lobe, up lobe)."""
    cr = math.radians(c)
    if g < 90.0:
        n = 1.0 + 1.0 * math.cos(cr) ** 2  # narrower along the length (C0)
        return max(0.0, math.cos(math.radians(g))) ** n, 0.0
    return 0.0, max(0.0, -math.cos(math.radians(g))) ** 1.5


def linear_led(c, g):
    """Linear LED, relative: cos^m with m larger along the length."""
    if g >= 90.0:
        return 0.0
    cr = math.radians(c)
    m = 1.1 + 0.4 * math.cos(cr) ** 2
    return max(0.0, math.cos(math.radians(g))) ** m


def flux(f, g_lo=0.0, g_hi=180.0, dg=0.05, dc=0.25):
    """Integral of f(C, gamma) over the sphere (lm for f in cd), midpoint rule."""
    total = 0.0
    nc = int(round(360.0 / dc))
    ng = int(round((g_hi - g_lo) / dg))
    for j in range(ng):
        g0 = g_lo + j * dg
        g1 = g0 + dg
        band = math.cos(math.radians(g0)) - math.cos(math.radians(g1))  # solid angle / dC (rad)
        gm = 0.5 * (g0 + g1)
        s = 0.0
        for i in range(nc):
            s += f((i + 0.5) * dc, gm)
        total += s * math.radians(dc) * band
    return total


def num(x):
    """A value with 6 significant digits, no exponent for ordinary magnitudes."""
    if x == 0.0:
        return "0"
    return f"{x:.6g}"


def lines_of(values, per_line=10):
    return [" ".join(num(v) for v in values[i : i + per_line]) for i in range(0, len(values), per_line)]


def ies(name, header, f, vertical, horizontal, lamp_lumens, opening_m, watts, flux_lm, absolute):
    lines = ["IESNA:LM-63-2002"] + header
    if absolute:
        lines.append(f"[_FLUX_ANALYTIC_LM] {flux_lm:.1f}")
    lines.append("TILT=NONE")
    w, l, h = opening_m
    lumens = -1 if absolute else lamp_lumens
    lines.append(f"1 {num(lumens)} 1.0 {len(vertical)} {len(horizontal)} 1 2 {w} {l} {h}")
    lines.append(f"1.0 1.0 {watts}")
    lines += lines_of(vertical)
    lines += lines_of(horizontal)
    for c in horizontal:
        lines += lines_of([f(c, g) for g in vertical])
    return name, "\r\n".join(lines) + "\r\n"


def ldt(name, fields, f_cd_per_klm, mc, ng):
    """EULUMDAT with Isym 4 (planes C0..C90 stored), Dc = 360/mc, Dg = 180/(ng-1)."""
    dc = 360.0 / mc
    dg = 180.0 / (ng - 1)
    c_angles = [i * dc for i in range(mc)]
    g_angles = [j * dg for j in range(ng)]
    stored = [c for c in c_angles if c <= 90.0 + 1e-9]
    out = [
        fields["company"],
        "2",  # Ityp: linear luminaire
        "4",  # Isym: symmetric about C0-C180 and C90-C270
        str(mc),
        num(dc),
        str(ng),
        num(dg),
        fields["report"],
        fields["luminaire"],
        fields["number"],
        name,
        fields["date"],
    ]
    out += [num(v) for v in fields["dims_mm"]]  # 13-15
    out += [num(v) for v in fields["area_mm"]]  # 16-21
    out += [num(fields["dff"]), num(fields["lorl"]), "1.0", "0"]  # 22-25
    out += ["1", "1", fields["lamp"], num(fields["lamp_lm"]), fields["cct"], fields["cri"], num(fields["watts"])]
    out += ["0"] * 10  # 27: direct ratios (not computed)
    out += [num(c) for c in c_angles]
    out += [num(g) for g in g_angles]
    for c in stored:
        out += [num(f_cd_per_klm(c, g)) for g in g_angles]
    return name, "\r\n".join(out) + "\r\n"


def files():
    made = []
    # Road luminaire.
    fl = flux(road, 0.0, 90.0)
    vertical = [0.5 * j for j in range(0, 181)]  # 0-90 deg
    horizontal = [5.0 * i for i in range(0, 37)]  # 0-180 deg
    made.append(
        ies(
            "road_batwing.ies",
            [
                "[TEST] morgana analytic distribution (scripts/gen_luminaires.py)",
                "[TESTLAB] none: generated, not measured",
                "[ISSUEDATE] 2026-12-01",
                "[MANUFAC] morgana project",
                "[LUMCAT] MORGANA-ROAD-BATWING",
                "[LUMINAIRE] street light, batwing along the road (C90/C270), street side C0, full cut-off",
                "[LAMP] LED module (absolute photometry)",
                "[OTHER] Analytic I(C, gamma); see scripts/gen_luminaires.py, function road()",
            ],
            road,
            vertical,
            horizontal,
            -1,
            (0.15, 0.25, 0.0),
            96,
            fl,
            True,
        )
    )
    # Underwater flood (relative photometry: lamp lumens = flux / LOR).
    fl = flux(flood, 0.0, 90.0)
    lor = 0.85
    vertical = [1.0 * j for j in range(0, 91)]
    made.append(
        ies(
            "underwater_flood_54.ies",
            [
                "[TEST] morgana analytic distribution (scripts/gen_luminaires.py)",
                "[TESTLAB] none: generated, not measured",
                "[ISSUEDATE] 2026-12-01",
                "[MANUFAC] morgana project",
                "[LUMCAT] MORGANA-FLOOD-54",
                "[LUMINAIRE] floodlight, 54 deg FWHM, rotationally symmetric",
                f"[LAMP] COB LED, lamp lumens = luminaire flux / {lor} (LOR {lor * 100:.0f} %)",
                "[OTHER] Analytic I(gamma) = 1000 cd exp(-ln2 (gamma/27 deg)^2); see scripts/gen_luminaires.py",
            ],
            flood,
            vertical,
            [0.0],
            round(fl / lor, 1),
            (0.06, 0.06, 0.0),
            12,
            fl,
            False,
        )
    )
    # Office pendant: scale the two lobes to 7000 lm with 33 % downward.
    down = flux(lambda c, g: pendant_shape(c, g)[0], 0.0, 90.0)
    up = flux(lambda c, g: pendant_shape(c, g)[1], 90.0, 180.0)
    total, dff = 7000.0, 0.33
    kd, ku = dff * total / down, (1.0 - dff) * total / up

    def pendant_cd_per_klm(c, g):
        d, u = pendant_shape(c, g)
        return (kd * d + ku * u) / (total / 1000.0)

    made.append(
        ldt(
            "office_pendant.ldt",
            {
                "company": "morgana project (analytic, scripts/gen_luminaires.py)",
                "report": "generated, not measured",
                "luminaire": "direct/indirect linear pendant, 33 % down",
                "number": "MORGANA-PENDANT-7000",
                "date": "2026-12-01 gen_luminaires.py",
                "dims_mm": (1500, 250, 50),
                "area_mm": (1500, 250, 0, 0, 0, 0),
                "dff": 100.0 * dff,
                "lorl": 100.0,
                "lamp": "LED",
                "lamp_lm": total,
                "cct": "4000",
                "cri": "80",
                "watts": 55,
            },
            pendant_cd_per_klm,
            24,
            37,
        )
    )
    # Linear LED, 5540 lm.
    rel = flux(linear_led, 0.0, 90.0)
    total = 5540.0
    k = total / rel
    made.append(
        ldt(
            "office_linear_led.ldt",
            {
                "company": "morgana project (analytic, scripts/gen_luminaires.py)",
                "report": "generated, not measured",
                "luminaire": "surface-mounted linear LED, 1500 x 60 mm opening",
                "number": "MORGANA-LINEAR-5540",
                "date": "2026-12-01 gen_luminaires.py",
                "dims_mm": (1500, 60, 85),
                "area_mm": (1500, 60, 0, 0, 0, 0),
                "dff": 100.0,
                "lorl": 100.0,
                "lamp": "LED",
                "lamp_lm": total,
                "cct": "4000",
                "cri": "80",
                "watts": 38,
            },
            lambda c, g: k * linear_led(c, g) / (total / 1000.0),
            24,
            37,
        )
    )
    return made


def main():
    check = "--check" in sys.argv[1:]
    differ = []
    for name, text in files():
        path = OUT / name
        if check:
            if not path.exists() or path.read_bytes() != text.encode("ascii"):
                differ.append(name)
        else:
            path.write_bytes(text.encode("ascii"))
            print(f"wrote {path}")
    if differ:
        print("differs from scripts/gen_luminaires.py: " + ", ".join(differ))
        sys.exit(1)


if __name__ == "__main__":
    main()
