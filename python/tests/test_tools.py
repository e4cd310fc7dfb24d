"""refraction, terrestrial, lines_of_sight, trace, luminaire and tonemap give what their `morgana`
commands give."""

import csv
import io

import numpy as np
import pytest

import morgana
from conftest import EXAMPLES, ROOT


def csv_columns(text: str) -> dict:
    rows = list(csv.reader(io.StringIO(text)))
    return {h: np.array([float(r[i]) if r[i] != "" else np.nan for r in rows[1:]]) for i, h in enumerate(rows[0])}


def test_refraction_matches_the_cli_table(tmp_path, cli):
    altitudes = [-0.5, 0, 0.5, 1, 5, 45]
    out = tmp_path / "r.csv"
    cli("refraction", "--atmosphere", "usa76", "--apparent-altitudes-deg", ",".join(map(str, altitudes)), "--csv", out)
    c = csv_columns(out.read_text())
    r = morgana.refraction("usa76", altitudes)
    np.testing.assert_array_equal(r["apparent_altitude_deg"], c["apparent_altitude_deg"])
    # The CSV prints 9 decimals of degrees and 4 of arcseconds.
    np.testing.assert_allclose(r["true_altitude_deg"], c["true_altitude_deg"], atol=6e-10, equal_nan=True)
    np.testing.assert_allclose(r["refraction_arcsec"], c["refraction_arcsec"], atol=6e-5, equal_nan=True)
    # Bennett (1982): R = cot(h + 7.31/(h + 4.4)) arcmin at h = 0 is 34.5'; the traced value at
    # the horizon of the standard atmosphere is within 2' of it (about 35' in the literature).
    assert abs(r["refraction_arcsec"][1] / 60 - 34.5) < 2
    assert np.isnan(r["bennett_arcsec"][0])  # Bennett does not apply below 0°
    sun = r["sun"]
    assert 0.7 < sun["ratio"] < 0.9  # the setting sun is flattened to about 0.8 (Schaefer 1992)
    with pytest.raises(ValueError):
        morgana.refraction("usa76", [91])
    with pytest.raises(ValueError):
        morgana.refraction("no_such_atmosphere", [0])
    with pytest.raises(ValueError, match="method"):
        morgana.refraction("usa76", [0], method="bouguer")


def test_refraction_by_quadrature_and_by_trace_agree(tmp_path, cli):
    # The default is Bouguer's quadrature, as the command's; method="trace" is the ray equation,
    # as `--method trace`. The two agree within the trace's own error (tests/terrestrial.rs).
    altitudes = [-0.5, 0, 0.5, 1, 5, 45, 90]
    out = tmp_path / "t.csv"
    cli("refraction", "--atmosphere", "usa76", "--apparent-altitudes-deg", ",".join(map(str, altitudes)),
        "--method", "trace", "--csv", out)
    c = csv_columns(out.read_text())
    q, t = morgana.refraction("usa76", altitudes), morgana.refraction("usa76", altitudes, method="trace")
    assert (q["method"], t["method"]) == ("quadrature", "trace")
    assert morgana.refraction("usa76", altitudes, method="quadrature")["method"] == "quadrature"
    np.testing.assert_allclose(t["refraction_arcsec"], c["refraction_arcsec"], atol=6e-5, equal_nan=True)
    np.testing.assert_allclose(q["refraction_arcsec"], t["refraction_arcsec"], atol=2e-3, equal_nan=True)
    assert abs(q["sun"]["ratio"] - t["sun"]["ratio"]) < 1e-6


def test_terrestrial_matches_the_cli_table(tmp_path, cli):
    alts, dists = [-0.5, 0.5], [1, 100]
    out = tmp_path / "t.csv"
    cli("refraction", "--atmosphere", "usa76", "--observer-height-m", "10", "--apparent-altitudes-deg=-0.5,0.5",
        "--ground-distances-km", "1,100", "--csv", out)
    c = csv_columns(out.read_text())
    r = morgana.terrestrial("usa76", alts, dists, observer_height_m=10)
    assert r["height_m"].shape == (2, 2)
    # The CSV prints 9 decimals of metres; rows are altitudes outermost.
    np.testing.assert_allclose(r["height_m"].ravel(), c["height_m"], atol=6e-10, equal_nan=True)
    np.testing.assert_allclose(r["ground_at_km"].ravel(), c["ground_at_km"], atol=6e-10, equal_nan=True)
    assert np.isnan(r["height_m"][0, 1]) and r["ground_at_km"][0, 1] > 1  # 0.5 deg down meets the sea
    with pytest.raises(ValueError, match="duct"):
        morgana.terrestrial("inversion", [0], [10], observer_height_m=25)


def test_lines_of_sight_match_the_cli(tmp_path, cli):
    out = tmp_path / "s.csv"
    cli("refraction", "--atmosphere", "usa76", "--observer-height-m", "2", "--targets", "10:5,40:30", "--csv", out)
    c = csv_columns(out.read_text())
    r = morgana.lines_of_sight("usa76", [(10, 5), (40, 30)], observer_height_m=2)
    np.testing.assert_allclose(r["hidden_height_m"], c["hidden_height_m"], atol=6e-10)
    assert len(r["images_deg"][0]) == 1 and r["images_deg"][1] == []  # the second is hidden
    assert abs(r["images_deg"][0][0] - c["apparent_elevation_deg"][0]) < 6e-13
    # An eye 2 m up: the horizon ~5.5 km away with standard refraction (3.57 sqrt(h) km without).
    assert 5.0 < r["horizon_km"] < 6.0
    with pytest.raises(ValueError):
        morgana.lines_of_sight("usa76", [(0, 5)])


def test_trace_matches_the_cli_path(tmp_path, cli):
    scene_path = EXAMPLES / "mirage_hot_road.toml"
    out = tmp_path / "t.csv"
    origin, direction = [0.0, 1.5, 0.0], [0.0, -0.01, -1.0]
    text = cli("trace", scene_path, "--from", "0,1.5,0", "--dir", "0,-0.01,-1", "--csv", out)
    c = csv_columns(out.read_text())
    t = morgana.trace(morgana.Scene.from_file(scene_path), origin, direction)
    assert t["position"].shape == (len(c["s_m"]), 3)
    np.testing.assert_allclose(t["s_m"], c["s_m"], atol=6e-7)
    np.testing.assert_allclose(t["position"], np.stack([c["x"], c["y"], c["z"]], axis=1), atol=6e-7)
    np.testing.assert_allclose(t["direction"], np.stack([c["dx"], c["dy"], c["dz"]], axis=1), atol=6e-13)
    np.testing.assert_allclose(t["n"], c["n"], atol=6e-13)
    for line in t["events"]:
        assert line in text
    # Directions are unit vectors (the path's tangent), whatever length was given.
    np.testing.assert_allclose(np.linalg.norm(t["direction"], axis=1), 1.0, atol=1e-9)
    with pytest.raises(ValueError):
        morgana.trace(morgana.Scene.from_file(scene_path), origin, [0, 0, 0])


def test_luminaire_matches_the_cli_and_its_flux(cli):
    path = ROOT / "luminaires" / "road_batwing.ies"
    d = morgana.luminaire(path)
    assert d["summary"].strip() == cli("luminaire", path).strip()
    c, g, i = d["c_deg"], d["gamma_deg"], d["intensity_cd"]
    assert i.shape == (len(c), len(g)) and (i >= 0).all()
    # Independent quadrature of the web: Φ = ∫∫ I(C, γ) sin γ dγ dC by the trapezoid rule on the
    # full grid agrees with the library's flux to a fraction of a percent.
    gamma = np.radians(g)
    per_plane = np.trapezoid(i * np.sin(gamma), gamma, axis=1)
    cs = np.radians(c)
    if cs[-1] - cs[0] < 2 * np.pi - 1e-9:  # close the circle
        cs = np.append(cs, cs[0] + 2 * np.pi)
        per_plane = np.append(per_plane, per_plane[0])
    flux = np.trapezoid(per_plane, cs)
    assert abs(flux / d["flux_lm"] - 1) < 0.01, (flux, d["flux_lm"])
    assert d["peak"][2] == pytest.approx(i.max())


def test_tonemap_matches_the_cli_png(tmp_path, cli):
    image = pytest.importorskip("matplotlib.image")
    scene = morgana.Scene.from_file(EXAMPLES / "white_furnace.toml").with_overrides(photons=10_000)
    result = morgana.render(scene, progress=False)
    saved = result.save(tmp_path / "r")
    exr = next(p for p in saved if p.suffix == ".exr")
    png = tmp_path / "t.png"
    cli("tonemap", exr, "--out", png, "--operator", "reinhard")
    from_cli = np.round(image.imread(png)[:, :, :3] * 255).astype(np.uint8)
    from_file = morgana.tonemap(exr, operator="reinhard")
    from_result = result.tonemap(operator="reinhard")
    assert from_file.dtype == np.uint8 and from_file.shape == (64, 64, 3)
    np.testing.assert_array_equal(from_file, from_cli)
    np.testing.assert_array_equal(from_result, from_cli)
    with pytest.raises(ValueError):
        morgana.tonemap(result, operator="nope")
    with pytest.raises(TypeError):
        morgana.tonemap(3.5)
