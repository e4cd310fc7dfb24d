"""morgana from Python: spectral light transport through media that bend and re-colour light.

Scenes are morgana's TOML scenes, read from a file, a string or a dict; ``render`` runs the same
code as ``morgana render`` and returns NumPy arrays, so the same scene and seed give the same
numbers in Python and on the command line::

    import morgana
    scene = morgana.Scene.from_file("examples/cornell_box.toml").with_overrides(photons=20_000, seed=7)
    result = morgana.render(scene, threads=2)
    result.radiance.shape          # (height, width, bands), W m^-2 sr^-1 nm^-1
    result.save("out")             # the files `morgana render --out out` writes

Errors in a scene raise ``SceneError`` (with ``.file``, ``.line``, ``.column``, ``.field``); a
missing file raises ``FileNotFoundError``; bad arguments ``ValueError``; an internal failure
``RuntimeError``. Ctrl-C stops a render cleanly (``KeyboardInterrupt``).
"""

from __future__ import annotations

import csv
import io
import json
import os
import sys
from pathlib import Path
from typing import Any, Callable, Dict, List, Mapping, Optional, Sequence, Tuple, Union

import numpy as np

from . import _native
from ._native import SceneError

__all__ = [
    "Scene",
    "Result",
    "SceneError",
    "render",
    "refraction",
    "terrestrial",
    "lines_of_sight",
    "trace",
    "luminaire",
    "tonemap",
    "__version__",
]

__version__: str = _native.VERSION

PathLike = Union[str, "os.PathLike[str]"]



class Scene:
    """A validated morgana scene, ready to render.

    Build one with ``Scene.from_file``, ``Scene.from_str`` or ``Scene.from_dict``; a scene is
    never changed in place (``with_overrides`` returns a new one).
    """

    __slots__ = ("_native",)

    def __init__(self, native: _native.NativeScene) -> None:
        self._native = native

    @classmethod
    def from_file(cls, path: PathLike) -> "Scene":
        """Reads a scene file (TOML); relative paths in it are resolved against its directory.

        Raises FileNotFoundError if the file is missing and SceneError if it is wrong.
        """
        return cls(_native.NativeScene.from_file(os.fspath(path)))

    @classmethod
    def from_str(
        cls,
        toml_text: str,
        base_dir: PathLike = ".",
        *,
        file: str = "<string>",
        name: str = "scene",
    ) -> "Scene":
        """Reads scene text (TOML).

        ``base_dir`` resolves relative paths (luminaire, grid and mesh files), ``file`` names the
        text in error messages, ``name`` is the output file stem when ``[output] name`` is absent.
        """
        return cls(_native.NativeScene.from_str(toml_text, os.fspath(base_dir), file, name))

    @classmethod
    def from_dict(
        cls,
        d: Mapping[str, Any],
        base_dir: PathLike = ".",
        *,
        name: str = "scene",
    ) -> "Scene":
        """Builds a scene from the TOML structure as Python values.

        Tables are dicts, arrays of tables (``[[light]]``) lists of dicts; values are str, int,
        float, bool and lists. ``Scene.from_dict(tomllib.load(f))`` reads the same scene as the
        file. Errors name the line of the TOML text the dict becomes (``Scene.to_toml(d)``).
        """
        text = cls.to_toml(d)
        return cls(_native.NativeScene.from_str(text, os.fspath(base_dir), "<dict>", name))

    @staticmethod
    def to_toml(d: Mapping[str, Any]) -> str:
        """The TOML text of a scene dict (what ``from_dict`` reads). TypeError for a value TOML
        cannot hold (None, an object)."""
        return _native.NativeScene.dict_to_toml(d)

    def with_overrides(self, **overrides: Any) -> "Scene":
        """The scene with the overrides of ``morgana render`` applied; a new scene.

        Accepted (each like the flag of ``morgana render`` it names):

        - ``photons``: photons of each photon map (``--photons``); ``seed`` (``--seed``).
        - ``passes``: progressive passes to run (``--passes``).
        - ``time``: wall-clock budget of the whole render, seconds or a text such as ``"90s"``,
          ``"1.5min"`` (``--time``).
        - ``target_rel_error``: stop when the relative standard error of the target's mean falls
          below it, e.g. 0.01 (``--target-rel-error``).
        - ``target``: what that error is measured on: ``"image"`` (its mean), ``"pixels"`` (95 %
          of the pixels each, for a picture), a sensor's name or a pixel region
          ``(x0, y0, x1, y1)``, x1 and y1 exclusive (``--target``).
        - ``adaptive``: from the second pass on, spend each pass's eye samples where the pixels'
          samples spread most (``--adaptive``; needs more than one pass).

        A stopping rule replaces the scene's ``[integrator]`` key of the same name. None leaves
        a setting as it is; an unknown name or a value of the wrong type is a TypeError, a value
        out of range (``passes=0``, ``time=-1``, a target naming no sensor) a ValueError.
        """
        return Scene(self._native.with_overrides(overrides))

    def plan(self) -> Dict[str, Any]:
        """The effect plan: what machinery runs and why (report.json's ``effects``)."""
        return json.loads(self._native.plan_json())

    def integrator(self) -> Dict[str, Any]:
        """The integrator settings after overrides (report.json's ``integrator``)."""
        return json.loads(self._native.integrator_json())

    @property
    def text(self) -> str:
        """The TOML text the scene was read from."""
        return self._native.text

    @property
    def label(self) -> str:
        """The scene's file, or ``<string>``/``<dict>``."""
        return self._native.label

    @property
    def warnings(self) -> List[str]:
        """Notes from validation: things that do not stop a render."""
        return list(self._native.warnings)

    @property
    def size(self) -> Tuple[int, int]:
        """(width, height) of the image, pixels."""
        return tuple(self._native.size)  # type: ignore[return-value]

    @property
    def wavelengths_nm(self) -> np.ndarray:
        """Band centres, nm."""
        return np.asarray(self._native.wavelengths_nm)

    @property
    def band_edges_nm(self) -> np.ndarray:
        """Band edges, nm (bands + 1 values)."""
        return np.asarray(self._native.band_edges_nm)

    @property
    def output_files(self) -> List[str]:
        """The files a render writes (``report.json`` last)."""
        return list(self._native.output_files)

    def __repr__(self) -> str:
        w, h = self.size
        return f"<morgana.Scene {self.label} {w}x{h}, {len(self.wavelengths_nm)} bands>"


def _columns(text: str) -> Dict[str, np.ndarray]:
    """The columns of a CSV text as NumPy arrays (float where every value is a number)."""
    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return {}
    header, body = rows[0], rows[1:]
    out: Dict[str, np.ndarray] = {}
    for i, name in enumerate(header):
        values = [r[i] if i < len(r) else "" for r in body]
        try:
            out[name] = np.array([float(v) if v != "" else np.nan for v in values], dtype=np.float64)
        except ValueError:
            out[name] = np.array(values, dtype=object)
    return out


class Result:
    """A finished render: NumPy arrays of the image and what the sensors measured.

    Attributes:
      radiance: float32 array (height, width, bands), band-averaged spectral radiance,
        W m^-2 sr^-1 nm^-1 (what the spectral EXR holds).
      rgb: float32 array (height, width, 3), linear sRGB (D65), Y in cd m^-2.
      wavelengths_nm: band centres; band_edges_nm: band edges (bands + 1).
      stderr: float32 array like ``radiance``: each pixel's and band's standard error from the
        spread between progressive passes (the EXR's ``stderr`` layer), W m^-2 sr^-1 nm^-1;
        None after a single pass, which has no estimate.
      sensors: sensor name -> {column: array}, the columns of its CSV file.
      derived: ocean-profile sensor name -> {"surface": {column: array}, "kd": {column: array}},
        the two tables of its ``_derived.csv`` (Ed(0+), Lu(0-), Lw, Rrs per band; K_d between
        consecutive depths per band).
      report: report.json's content as a dict (``outputs`` lists the files a save would write).
      scene: the Scene rendered.
    """

    def __init__(self, native: _native.NativeResult, scene: Scene) -> None:
        self._native = native
        self.scene = scene
        h, w, nb = native.shape
        self.radiance: np.ndarray = np.frombuffer(native.radiance_bytes(), dtype=np.float32).reshape(h, w, nb).copy()
        self.rgb: np.ndarray = np.frombuffer(native.rgb_bytes(), dtype=np.float32).reshape(h, w, 3).copy()
        self.wavelengths_nm: np.ndarray = np.asarray(native.wavelengths_nm)
        self.band_edges_nm: np.ndarray = np.asarray(native.band_edges_nm)
        se = native.stderr_bytes()
        self.stderr: Optional[np.ndarray] = (
            None if se is None else np.frombuffer(se, dtype=np.float32).reshape(h, w, nb).copy()
        )
        self.sensors: Dict[str, Dict[str, np.ndarray]] = {}
        self.derived: Dict[str, Dict[str, np.ndarray]] = {}
        for name, _kind, text, derived in native.sensor_csvs():
            self.sensors[name] = _columns(text)
            if derived is not None:
                tables = [_columns(t) for t in derived.split("\n\n") if t.strip()]
                self.derived[name] = dict(zip(("surface", "kd"), tables))
        self.report: Dict[str, Any] = json.loads(native.report_json(scene.output_files))
        self.warnings: List[str] = list(native.run_warnings)

    @property
    def threads(self) -> int:
        """Worker threads the render used."""
        return self._native.threads

    def save(self, directory: PathLike) -> List[Path]:
        """Writes the files ``morgana render --out DIRECTORY`` writes (spectral EXR, PNG, CSVs,
        sensor files, report.json, as the scene's ``[output]`` asks), all or nothing; returns
        their paths."""
        return [Path(p) for p in self._native.save(os.fspath(directory))]

    def tonemap(self, **options: Any) -> np.ndarray:
        """``morgana.tonemap(self, **options)``: an 8-bit sRGB array (height, width, 3)."""
        return tonemap(self, **options)

    def __repr__(self) -> str:
        h, w, nb = self.radiance.shape
        return f"<morgana.Result {w}x{h}, {nb} bands, {len(self.sensors)} sensors>"


class _Progress:
    """Draws a render's phases as tqdm bars when tqdm is installed, else as lines on stderr."""

    def __init__(self) -> None:
        try:
            from tqdm.auto import tqdm  # type: ignore[import-not-found]
        except ImportError:
            tqdm = None
        self._tqdm = tqdm
        self._bar: Any = None
        self._phase: Optional[str] = None
        self._last_percent = -1

    def __call__(self, phase: str, done: int, total: int) -> None:
        if phase != self._phase:
            self.close()
            self._phase = phase
            self._last_percent = -1
            if self._tqdm is not None:
                self._bar = self._tqdm(total=total, desc=phase, leave=False)
        if self._bar is not None:
            self._bar.update(done - self._bar.n)
        else:
            percent = int(100 * done / total) if total else 100
            if percent // 10 != self._last_percent // 10:
                print(f"morgana: {phase} {percent}%", file=sys.stderr, flush=True)
                self._last_percent = percent

    def close(self) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None


def render(
    scene: Scene,
    threads: Optional[int] = None,
    progress: Union[bool, Callable[[str, int, int], None]] = True,
    *,
    max_seconds: Optional[float] = None,
    max_memory: Optional[str] = None,
) -> Result:
    """Renders a scene, as ``morgana render`` does, and returns a Result of NumPy arrays.

    Args:
      scene: the Scene (use ``scene.with_overrides(photons=..., seed=...)`` for the CLI's
        ``--photons`` and ``--seed``).
      threads: worker threads (default: one per core); the image does not depend on it.
      progress: True draws each phase (photon passes, eye pass) as a tqdm bar when tqdm is
        installed, else as lines on stderr; False is silent; a callable gets
        ``(phase, done, total)`` about ten times a second.
      max_seconds: stop after this much wall time (``--max-seconds``): a scene with
        progressive passes keeps the passes it finished; with none finished, RuntimeError.
      max_memory: the memory the run may use, e.g. "8G" (``--max-memory``; default: what the
        machine has available).

    The GIL is released while the render runs, so other Python threads go on; Ctrl-C stops the
    render within a batch of photons or a row of pixels and raises KeyboardInterrupt.
    """
    drawer: Optional[_Progress] = None
    if progress is True:
        drawer = _Progress()
        callback: Optional[Callable[[str, int, int], None]] = drawer
    elif callable(progress):
        callback = progress
    else:
        callback = None
    try:
        native = _native.render(
            scene._native,
            threads=threads,
            progress=callback,
            quiet=callback is None,
            max_seconds=max_seconds,
            max_memory=max_memory,
        )
    finally:
        if drawer is not None:
            drawer.close()
    return Result(native, scene)


def refraction(
    atmosphere: str,
    apparent_altitudes_deg: Sequence[float] = (0, 0.5, 1, 2, 5, 10, 45),
    wavelength_nm: float = 550.0,
    observer_height_m: float = 0.0,
    sun_lower_limb_deg: float = 0.0,
    method: Optional[str] = None,
) -> Dict[str, Any]:
    """Astronomical refraction through an atmosphere, as ``morgana refraction`` computes it.

    ``atmosphere`` is a built-in name (usa76, hot_road, inversion, fata_morgana, tropical) or an
    atmosphere TOML file. ``method`` is ``"quadrature"`` (Bouguer's invariant; rays into the
    ground or ducted are traced), ``"trace"`` (the ray equation for every ray) or None: the
    quadrature where the air depends on height alone, else the trace. Returns a dict:
    ``method`` (the one used), ``apparent_altitude_deg``, ``true_altitude_deg``,
    ``refraction_arcsec`` (NaN where the ray does not escape), ``bennett_arcsec`` and
    ``saemundsson_arcsec`` (the classical formulas at the observer's conditions; NaN where they
    do not apply) as arrays; ``pressure_hpa`` and ``temperature_c`` at the observer; and ``sun``:
    the 0.53° sun with its lower limb seen at ``sun_lower_limb_deg`` (``lower_apparent_deg``,
    ``lower_true_deg``, ``upper_apparent_deg``, ``upper_true_deg``, ``ratio`` = apparent vertical
    over horizontal diameter), or None if a limb's ray does not escape.
    """
    d = _native.refraction(
        os.fspath(atmosphere),
        [float(a) for a in apparent_altitudes_deg],
        wavelength_nm=float(wavelength_nm),
        observer_height_m=float(observer_height_m),
        sun_lower_limb_deg=float(sun_lower_limb_deg),
        method=method,
    )
    for k in ("apparent_altitude_deg", "true_altitude_deg", "refraction_arcsec", "bennett_arcsec", "saemundsson_arcsec"):
        d[k] = np.asarray(d[k], dtype=np.float64)
    return d


def terrestrial(
    atmosphere: str,
    apparent_altitudes_deg: Sequence[float],
    ground_distances_km: Sequence[float],
    wavelength_nm: float = 550.0,
    observer_height_m: float = 0.0,
) -> Dict[str, Any]:
    """Terrestrial refraction: where rays from the observer are along the ground, as ``morgana
    refraction --ground-distances-km`` computes it (Bouguer's invariant by quadrature).

    ``atmosphere`` is a built-in name or an atmosphere TOML file with a round Earth and a
    height-only index; a ray that turns back inside the air (a duct) raises ValueError. Returns a
    dict with ``apparent_altitude_deg`` and ``ground_distance_km`` as given, and arrays of shape
    (altitudes, distances): ``height_m``, ``elevation_deg`` and ``straight_height_m`` (the
    straight line from the same start; NaN where it never gets there) — NaN where the ray met the
    ground first or left the air upward short of the distance — and ``ground_at_km``, where it
    met the ground (NaN otherwise).
    """
    alts = [float(a) for a in apparent_altitudes_deg]
    dists = [float(x) for x in ground_distances_km]
    d = _native.terrestrial(
        os.fspath(atmosphere), alts, dists, wavelength_nm=float(wavelength_nm), observer_height_m=float(observer_height_m)
    )
    for k in ("apparent_altitude_deg", "ground_distance_km"):
        d[k] = np.asarray(d[k], dtype=np.float64)
    for k in ("height_m", "elevation_deg", "straight_height_m", "ground_at_km"):
        d[k] = np.asarray(d[k], dtype=np.float64).reshape(len(alts), len(dists))
    return d


def lines_of_sight(
    atmosphere: str,
    targets: Sequence[Tuple[float, float]],
    wavelength_nm: float = 550.0,
    observer_height_m: float = 2.0,
) -> Dict[str, Any]:
    """Lines of sight over the round Earth, as ``morgana refraction --targets`` computes them.

    ``targets`` are (distance along the ground in km, height above the ground in m) pairs.
    Returns a dict: ``horizon_km`` and ``dip_deg`` (the horizon's distance and dip; 0 for an
    observer on the ground); arrays ``distance_km``, ``height_m``, ``hidden_height_m`` (how
    high the horizon hides things at that distance) and ``straight_elevation_deg``; and
    ``images_deg``: for each target the list of apparent elevations it is seen at (empty: hidden
    below the horizon; several: a mirage).
    """
    pairs = [(float(a), float(b)) for a, b in targets]
    d = _native.lines_of_sight(
        os.fspath(atmosphere), pairs, wavelength_nm=float(wavelength_nm), observer_height_m=float(observer_height_m)
    )
    for k in ("distance_km", "height_m", "hidden_height_m", "straight_elevation_deg"):
        d[k] = np.asarray(d[k], dtype=np.float64)
    return d


def trace(
    scene: Scene,
    origin: Sequence[float],
    direction: Sequence[float],
    wavelength_nm: float = 550.0,
    events: int = 32,
    max_length_m: float = 1.0e8,
) -> Dict[str, Any]:
    """Follows one ray through a scene's media without scattering, as ``morgana trace`` does.

    Returns a dict: ``events`` (one line of text per event: surfaces, medium boundaries, the
    end), ``end`` (how it ended), the sampled path as arrays ``s_m`` (N,), ``position`` (N, 3),
    ``direction`` (N, 3) and ``n`` (N,) (path length, point, unit direction, refractive index),
    and ``work`` (integrator steps, samples of n and grad n, chords).
    """
    d = _native.trace(
        scene._native,
        [float(x) for x in origin],
        [float(x) for x in direction],
        wavelength_nm=float(wavelength_nm),
        events=int(events),
        max_length_m=float(max_length_m),
    )
    d["s_m"] = np.asarray(d["s_m"], dtype=np.float64)
    d["position"] = np.asarray(d["position"], dtype=np.float64).reshape(-1, 3)
    d["direction"] = np.asarray(d["direction"], dtype=np.float64).reshape(-1, 3)
    d["n"] = np.asarray(d["n"], dtype=np.float64)
    return d


def luminaire(path: PathLike, variant: Optional[str] = None) -> Dict[str, Any]:
    """Reads a luminaire photometry file (IES LM-63, EULUMDAT, IES TM-33, GLDF) as
    ``morgana luminaire`` does.

    Returns a dict: the photometric web as arrays ``c_deg`` (C-planes), ``gamma_deg`` and
    ``intensity_cd`` (len(c_deg), len(gamma_deg)) on the full grid after symmetry expansion;
    header facts ``format``, ``manufacturer``, ``luminaire``, ``catalogue``,
    ``photometric_type``, ``symmetry``, ``absolute``, ``lamp_flux_lm``, ``stated_flux_lm``,
    ``input_watts``; ``flux_lm`` (the web's own quadrature), ``peak`` (C, gamma, cd), ``notes``
    and ``summary`` (the text the command prints). ``variant`` picks a GLDF variant.
    """
    d = _native.luminaire(os.fspath(path), variant)
    d["c_deg"] = np.asarray(d["c_deg"], dtype=np.float64)
    d["gamma_deg"] = np.asarray(d["gamma_deg"], dtype=np.float64)
    d["intensity_cd"] = np.asarray(d["intensity_cd"], dtype=np.float64).reshape(len(d["c_deg"]), len(d["gamma_deg"]))
    return d


def tonemap(
    source: Union[Result, PathLike],
    operator: Optional[str] = None,
    exposure: Union[None, str, float] = None,
    adapt_to: Optional[str] = None,
    cat: Optional[str] = None,
    adaptation_degree: Optional[float] = None,
    adaptation_time_s: Optional[float] = None,
    adapt_from_cd_m2: Optional[float] = None,
    scotopic: Optional[str] = None,
    false_colour: bool = False,
    fov_deg: Optional[float] = None,
) -> np.ndarray:
    """Tone-maps a render (a Result) or an EXR file into an 8-bit sRGB array (height, width, 3),
    as ``morgana tonemap`` does.

    Options are the command's: ``operator`` exposure | reinhard | ward-histogram | pattanaik;
    ``exposure`` "auto" or stops (EV); ``adapt_to`` none, d65, a, e, white, scene-average or
    "x,y"; ``cat`` von-kries | bradford | cat16; ``adaptation_degree`` 0..1;
    ``adaptation_time_s`` and ``adapt_from_cd_m2`` (pattanaik); ``scotopic`` auto | on | off;
    ``false_colour`` (luminance on a log scale with a legend); ``fov_deg`` (default 40).
    """
    src: Any = source._native if isinstance(source, Result) else os.fspath(source)
    h, w, data, _notes = _native.tonemap(
        src,
        operator=operator,
        exposure=None if exposure is None else str(exposure),
        adapt_to=adapt_to,
        cat=cat,
        adaptation_degree=adaptation_degree,
        adaptation_time_s=adaptation_time_s,
        adapt_from_cd_m2=adapt_from_cd_m2,
        scotopic=scotopic,
        false_colour=false_colour,
        fov_deg=fov_deg,
    )
    return np.frombuffer(data, dtype=np.uint8).reshape(h, w, 3).copy()
