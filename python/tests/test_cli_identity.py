"""Python and the CLI run the same code: the same scene and seed give identical radiance arrays,
sensor columns and output files (report.json aside: it records times)."""

import csv
import tomllib
from pathlib import Path

import numpy as np
import pytest

import morgana
from conftest import EXAMPLES


def read_csv(path: Path, table: int = 0) -> dict:
    """The columns of a CSV file (of its `table`-th table, tables being separated by blank lines)."""
    text = path.read_text().split("\n\n")[table]
    rows = list(csv.reader(text.strip().splitlines()))
    header, body = rows[0], rows[1:]
    out = {}
    for i, h in enumerate(header):
        values = [r[i] for r in body]
        try:
            out[h] = np.array([float(v) if v != "" else np.nan for v in values])
        except ValueError:  # a text column (a sensor's name)
            out[h] = np.array(values, dtype=object)
    return out


def scene_file(tmp_path: Path, example: str, **output) -> Path:
    """The example with `[output]` changes, written as a scene file in tmp_path."""
    d = tomllib.loads((EXAMPLES / example).read_text())
    d.setdefault("output", {}).update(output)
    path = tmp_path / example
    path.write_text(morgana.Scene.to_toml(d))
    return path


@pytest.mark.parametrize(
    "example,photons,seed",
    [("white_furnace.toml", 20_000, 11), ("chlorophyll_sweep.toml", 40_000, 5)],
)
def test_python_and_cli_give_identical_arrays_and_files(tmp_path, cli, example, photons, seed):
    path = scene_file(tmp_path, example, csv=True, exr=True)
    cli_out, py_out = tmp_path / "cli", tmp_path / "py"
    cli("render", path, "--out", cli_out, "--photons", photons, "--seed", seed, "--threads", 2, "--quiet")
    scene = morgana.Scene.from_file(path).with_overrides(photons=photons, seed=seed)
    result = morgana.render(scene, threads=1, progress=False)

    # The radiance array is the per-pixel CSV's values (f32, printed so that they read back exactly).
    stem = scene.output_files[0].rsplit(".", 1)[0]
    pixels = read_csv(cli_out / f"{stem}.csv")
    h, w, nb = result.radiance.shape
    assert len(pixels["x"]) == h * w
    for b, centre in enumerate(result.wavelengths_nm):
        column = pixels[f"L_{centre:.2f}nm"].astype(np.float32).reshape(h, w)
        np.testing.assert_array_equal(result.radiance[:, :, b], column)

    # Sensor columns are the CLI's sensor CSV columns.
    for name, columns in result.sensors.items():
        cli_columns = read_csv(cli_out / f"{stem}_{name}.csv")
        assert columns.keys() == cli_columns.keys()
        for k in columns:
            np.testing.assert_array_equal(columns[k], cli_columns[k], err_msg=f"{name}.{k}")
    for name, columns in result.derived.items():
        assert list(columns) == ["surface", "kd"]
        for t, table in enumerate(columns.values()):
            cli_columns = read_csv(cli_out / f"{stem}_{name}_derived.csv", t)
            assert table.keys() == cli_columns.keys()
            for k in table:
                np.testing.assert_array_equal(table[k], cli_columns[k], err_msg=f"{name} derived {k}")

    # save() writes the same files, byte for byte (report.json records times and threads).
    written = result.save(py_out)
    assert [p.name for p in written] == scene.output_files
    for p in written:
        if p.name != "report.json":
            assert p.read_bytes() == (cli_out / p.name).read_bytes(), p.name
    report = result.report
    assert report["seed"] == seed and report["effects"] == scene.plan()


def test_the_radiance_is_what_the_spectral_exr_holds(tmp_path, cli):
    """The EXR the CLI writes, read back by OpenEXR, holds the Python radiance array."""
    OpenEXR = pytest.importorskip("OpenEXR")
    path = scene_file(tmp_path, "white_furnace.toml", exr=True)
    cli("render", path, "--out", tmp_path / "cli", "--photons", 10_000, "--seed", 3, "--quiet")
    result = morgana.render(morgana.Scene.from_file(path).with_overrides(photons=10_000, seed=3), progress=False)
    exr = next((tmp_path / "cli").glob("*.exr"))
    channels = OpenEXR.File(str(exr), separate_channels=True).channels()
    spectral = sorted((k for k in channels if k.startswith("S0.")), key=lambda k: float(k[3:].rstrip("nm").replace(",", ".")))
    assert len(spectral) == result.radiance.shape[2]
    for b, k in enumerate(spectral):
        np.testing.assert_array_equal(np.asarray(channels[k].pixels, dtype=np.float32), result.radiance[:, :, b])


def exr_layers(OpenEXR, path: Path, prefix: str) -> list:
    """The channels `prefix<λ>nm` of a spectral EXR, ordered by wavelength, as float32 arrays."""
    channels = OpenEXR.File(str(path), separate_channels=True).channels()
    names = [k for k in channels if k.startswith(prefix) and k[len(prefix) :].rstrip("nm").replace(",", ".").replace(".", "", 1).isdigit()]
    names.sort(key=lambda k: float(k[len(prefix) :].rstrip("nm").replace(",", ".")))
    return [np.asarray(channels[k].pixels, dtype=np.float32) for k in names]


def test_progressive_passes_give_the_cli_image_and_its_error_layer(tmp_path, cli):
    """`with_overrides(passes=3)` renders what `morgana render --passes 3` renders, and
    `.stderr` is the EXR's standard-error layer (`stderr.S0.<λ>nm`) the CLI writes."""
    OpenEXR = pytest.importorskip("OpenEXR")
    path = scene_file(tmp_path, "white_furnace.toml", exr=True)
    cli("render", path, "--out", tmp_path / "cli", "--photons", 5_000, "--seed", 3, "--passes", 3, "--quiet")
    scene = morgana.Scene.from_file(path).with_overrides(photons=5_000, seed=3, passes=3)
    result = morgana.render(scene, threads=2, progress=False)
    exr = next((tmp_path / "cli").glob("*.exr"))
    radiance, stderr = exr_layers(OpenEXR, exr, "S0."), exr_layers(OpenEXR, exr, "stderr.S0.")
    assert result.stderr is not None and result.stderr.shape == result.radiance.shape
    assert len(radiance) == len(stderr) == result.radiance.shape[2]
    for b in range(result.radiance.shape[2]):
        np.testing.assert_array_equal(radiance[b], result.radiance[:, :, b])
        np.testing.assert_array_equal(stderr[b], result.stderr[:, :, b])
    # Three passes of independent maps differ, so the spread is positive somewhere (and never
    # negative or NaN); the report says three passes ran and why they stopped.
    assert np.all(np.isfinite(result.stderr)) and np.all(result.stderr >= 0) and np.any(result.stderr > 0)
    p = result.report["progressive"]
    assert p["passes"] == 3 and len(p["history"]) == 3 and p["stopped"]["rule"] == "passes"
    assert scene.plan()["progressive_passes"]["on"]
    # One pass has no spread to estimate from: None.
    single = morgana.render(scene.with_overrides(passes=1), progress=False)
    assert single.stderr is None and single.report["progressive"]["passes"] == 1


def test_the_thread_count_does_not_change_the_image():
    scene = morgana.Scene.from_file(EXAMPLES / "white_furnace.toml").with_overrides(photons=10_000, seed=2)
    one = morgana.render(scene, threads=1, progress=False)
    two = morgana.render(scene, threads=2, progress=False)
    np.testing.assert_array_equal(one.radiance, two.radiance)
    assert one.threads == 1 and two.threads == 2
    # A different seed gives a different image (the test above could otherwise pass vacuously).
    other = morgana.render(scene.with_overrides(seed=3), threads=2, progress=False)
    assert not np.array_equal(one.radiance, other.radiance)
