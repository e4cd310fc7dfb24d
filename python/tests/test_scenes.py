"""Scenes from files, strings and dicts; errors as exceptions; a fuzz of mutated dicts."""

import copy
import math
import random
import re
import tomllib

import numpy as np
import pytest

import morgana
from conftest import EXAMPLES

ALL_EXAMPLES = sorted(EXAMPLES.glob("*.toml"))
# Examples small enough to render in a test (at most 64 x 64 pixels), with fewer photons.
SMALL = ["white_furnace.toml", "point_light_plane.toml", "chlorophyll_sweep.toml", "mobley1993_problem1.toml"]


@pytest.mark.parametrize("path", ALL_EXAMPLES, ids=lambda p: p.name)
def test_from_dict_reads_every_example_as_its_file(path):
    from_file = morgana.Scene.from_file(path)
    d = tomllib.loads(path.read_text())
    from_dict = morgana.Scene.from_dict(d, base_dir=path.parent, name=path.stem)
    assert from_dict.plan() == from_file.plan()
    assert from_dict.integrator() == from_file.integrator()
    assert from_dict.output_files == from_file.output_files
    assert from_dict.size == from_file.size
    np.testing.assert_array_equal(from_dict.band_edges_nm, from_file.band_edges_nm)
    # The TOML text written from the dict reads back as the same dict.
    assert tomllib.loads(morgana.Scene.to_toml(d)) == d


@pytest.mark.parametrize("name", SMALL)
def test_from_dict_renders_as_its_file(name):
    path = EXAMPLES / name
    a = morgana.Scene.from_file(path).with_overrides(photons=20_000, seed=4)
    b = morgana.Scene.from_dict(tomllib.loads(path.read_text()), base_dir=EXAMPLES).with_overrides(photons=20_000, seed=4)
    ra, rb = morgana.render(a, progress=False), morgana.render(b, progress=False)
    np.testing.assert_array_equal(ra.radiance, rb.radiance)
    assert ra.sensors.keys() == rb.sensors.keys()
    for s in ra.sensors:
        for k in ra.sensors[s]:
            np.testing.assert_array_equal(ra.sensors[s][k], rb.sensors[s][k])
    # Something was measured (the image, or the sensors of a 1-pixel scene).
    measured = [ra.radiance.max()] + [np.nanmax(c) for s in ra.sensors.values() for c in s.values() if c.dtype != object]
    assert np.isfinite(ra.radiance).all() and max(measured) > 0


def test_from_str_resolves_relative_paths_against_base_dir():
    path = EXAMPLES / "road_ies.toml"
    text = path.read_text()
    assert morgana.Scene.from_str(text, base_dir=EXAMPLES).plan() == morgana.Scene.from_file(path).plan()
    with pytest.raises(morgana.SceneError):
        morgana.Scene.from_str(text, base_dir=EXAMPLES / "meshes")


def test_overrides_change_the_integrator_and_reject_unknown_names():
    s = morgana.Scene.from_file(EXAMPLES / "white_furnace.toml")
    o = s.with_overrides(photons=1234, seed=99)
    assert (o.integrator()["photons"], o.integrator()["seed"]) == (1234, 99)
    assert s.integrator()["photons"] == 400000  # the original is unchanged
    assert o.with_overrides(seed=None).integrator()["seed"] == 99
    with pytest.raises(TypeError, match="accepted: photons, seed, passes, time, target_rel_error, target"):
        s.with_overrides(spp=4)
    with pytest.raises(ValueError):
        s.with_overrides(photons=0)


def test_stopping_rules_are_the_render_flags():
    """passes/time/target_rel_error/target replace the [integrator] keys as --passes, --time,
    --target-rel-error and --target do, and the effect plan says which rules stop the run."""
    s = morgana.Scene.from_file(EXAMPLES / "white_furnace.toml")
    assert not s.plan()["progressive_passes"]["on"]
    p = s.with_overrides(passes=5).integrator()["progressive"]
    assert p["passes"] == 5
    assert s.with_overrides(time=90).integrator()["progressive"]["time_s"] == 90.0
    assert s.with_overrides(time="1.5min").integrator()["progressive"]["time_s"] == 90.0
    t = s.with_overrides(target_rel_error=0.02, target=(0, 0, 4, 4))
    assert t.integrator()["progressive"]["target_rel_error"] == 0.02
    assert t.integrator()["progressive"]["target"] == {"region": [0, 0, 4, 4]}
    reason = t.plan()["progressive_passes"]
    assert reason["on"] and "region 0,0,4,4" in reason["why"], reason
    # Overrides accumulate; None leaves a rule as it is.
    both = s.with_overrides(passes=5).with_overrides(time=None, target_rel_error=0.1)
    assert both.integrator()["progressive"]["passes"] == 5
    assert both.integrator()["progressive"]["target_rel_error"] == 0.1


@pytest.mark.parametrize(
    "overrides,message",
    [
        ({"passes": 0}, "passes=0: expected between 1 and"),
        ({"time": -1}, "time=-1: expected a positive duration"),
        ({"time": "soon"}, "time=soon: expected a duration"),
        ({"target_rel_error": 2.0}, "target_rel_error=2: expected a relative standard error"),
        ({"target": "image"}, "target=image needs target_rel_error"),
        ({"target": "desk", "target_rel_error": 0.1}, 'target=desk names the sensor "desk"'),
        ({"target": (0, 0, 999, 4), "target_rel_error": 0.1}, "is not a non-empty rectangle"),
    ],
)
def test_bad_stopping_rules_are_value_errors_naming_the_keyword(overrides, message):
    s = morgana.Scene.from_file(EXAMPLES / "white_furnace.toml")
    with pytest.raises(ValueError, match=re.escape(message)):
        s.with_overrides(**overrides)


@pytest.mark.parametrize("overrides", [{"passes": "3"}, {"time": [1]}, {"target": 3}, {"target_rel_error": "x"}])
def test_stopping_rules_of_the_wrong_type_are_type_errors(overrides):
    with pytest.raises(TypeError):
        morgana.Scene.from_file(EXAMPLES / "white_furnace.toml").with_overrides(**overrides)


def white_furnace_lines():
    return (EXAMPLES / "white_furnace.toml").read_text().splitlines()


def line_of(lines, prefix):
    return next(i for i, l in enumerate(lines) if l.startswith(prefix)) + 1


def test_an_out_of_range_value_names_file_line_and_field(tmp_path):
    lines = white_furnace_lines()
    n = line_of(lines, "width = 64")
    lines[n - 1] = "width = -64"
    path = tmp_path / "bad.toml"
    path.write_text("\n".join(lines) + "\n")
    with pytest.raises(morgana.SceneError) as e:
        morgana.Scene.from_file(path)
    assert (e.value.file, e.value.line, e.value.field) == (str(path), n, "width")
    assert e.value.column >= 1
    assert str(e.value).startswith(f"{path}:{n}:")


def test_an_unknown_field_and_a_syntax_error_are_located():
    lines = white_furnace_lines()
    n = line_of(lines, "fov_deg = 90.0")
    lines.insert(n, "fov_degrees = 60.0")
    with pytest.raises(morgana.SceneError) as e:
        morgana.Scene.from_str("\n".join(lines), base_dir=EXAMPLES, file="mine.toml")
    assert (e.value.file, e.value.line, e.value.field) == ("mine.toml", n + 1, "fov_degrees")

    lines = white_furnace_lines()
    n = line_of(lines, "spp = 1")
    lines[n - 1] = "spp = = 1"
    with pytest.raises(morgana.SceneError) as e:
        morgana.Scene.from_str("\n".join(lines))
    assert (e.value.file, e.value.line) == ("<string>", n)


def test_a_dict_error_is_a_scene_error_with_the_field():
    d = tomllib.loads((EXAMPLES / "white_furnace.toml").read_text())
    d["material"][0]["reflectance"] = 1.5
    with pytest.raises(morgana.SceneError) as e:
        morgana.Scene.from_dict(d)
    assert e.value.file == "<dict>" and e.value.field == "reflectance"
    text = morgana.Scene.to_toml(d)
    assert text.splitlines()[e.value.line - 1].startswith("reflectance")


def test_a_missing_file_raises_file_not_found(tmp_path):
    with pytest.raises(FileNotFoundError):
        morgana.Scene.from_file(tmp_path / "nope.toml")
    with pytest.raises(FileNotFoundError):
        morgana.luminaire(tmp_path / "nope.ies")
    with pytest.raises(FileNotFoundError):
        morgana.tonemap(tmp_path / "nope.exr")


def test_values_toml_cannot_hold_are_type_errors():
    with pytest.raises(TypeError, match="camera.width"):
        morgana.Scene.from_dict({"camera": {"width": None}})
    with pytest.raises(TypeError):
        morgana.Scene.from_dict({"camera": {"width": object()}})
    with pytest.raises(TypeError):
        morgana.Scene.from_dict({1: 2})
    # NumPy numbers are numbers.
    d = tomllib.loads((EXAMPLES / "white_furnace.toml").read_text())
    d["camera"]["width"] = np.int64(32)
    d["camera"]["fov_deg"] = np.float32(80.0)
    assert morgana.Scene.from_dict(d).size == (32, 64)


def mutate(value, rng):
    """A random change of one place in a scene dict (in place where it is a container)."""
    odd = [None, -1, 0, 1e308, -1e-308, math.nan, math.inf, "", "x" * 300, [], {}, [1, 2], True, 2**63 - 1, -(2**62)]
    if isinstance(value, dict) and value:
        key = rng.choice(list(value))
        roll = rng.random()
        if roll < 0.2:
            del value[key]
        elif roll < 0.5:
            value[key] = rng.choice(odd)
        elif roll < 0.6:
            value[key + "_x"] = rng.choice(odd)
        else:
            value[key] = mutate(value[key], rng)
        return value
    if isinstance(value, list) and value:
        i = rng.randrange(len(value))
        roll = rng.random()
        if roll < 0.2:
            value.append(copy.deepcopy(value[i]))
        elif roll < 0.4:
            del value[i]
        else:
            value[i] = mutate(value[i], rng)
        return value
    if isinstance(value, bool):
        return not value
    if isinstance(value, (int, float)):
        return rng.choice([-value, value * 1e6, value / 1e9, 0, -1, math.nan, str(value)])
    if isinstance(value, str):
        return rng.choice(["", value + "x", value[: len(value) // 2], "🙂", 3])
    return rng.choice(odd)


def test_the_interpreter_survives_a_thousand_mutated_dicts():
    """No mutation crashes the interpreter or panics the library: each either reads or raises
    SceneError, TypeError or ValueError (a caught panic would be RuntimeError)."""
    rng = random.Random(20)
    bases = [tomllib.loads((EXAMPLES / n).read_text()) for n in ("white_furnace.toml", "chlorophyll_sweep.toml", "road_ies.toml", "mirage_hot_road.toml", "prism_dispersion.toml")]
    outcomes = {"ok": 0, "SceneError": 0, "TypeError": 0, "ValueError": 0}
    for _ in range(1000):
        d = copy.deepcopy(rng.choice(bases))
        for _ in range(rng.randint(1, 3)):
            d = mutate(d, rng)
        try:
            scene = morgana.Scene.from_dict(d, base_dir=EXAMPLES) if isinstance(d, dict) else morgana.Scene.from_dict(d)
            scene.plan()
            outcomes["ok"] += 1
        except morgana.SceneError as e:
            assert e.file == "<dict>"
            outcomes["SceneError"] += 1
        except TypeError:
            outcomes["TypeError"] += 1
        except ValueError:
            outcomes["ValueError"] += 1
    # The fuzz reached both sides: valid scenes and each kind of rejection.
    assert outcomes["ok"] > 0 and outcomes["SceneError"] > 100 and outcomes["TypeError"] > 0, outcomes
