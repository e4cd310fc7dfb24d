"""Type hints of the native module morgana._native (python/src/, PyO3); use the documented
wrappers in morgana/__init__.py."""

from typing import Any, Callable, Dict, List, Optional, Sequence, Tuple, Union

VERSION: str

class SceneError(ValueError):
    message: str
    file: Optional[str]
    line: Optional[int]
    column: Optional[int]
    field: Optional[str]

class NativeScene:
    @staticmethod
    def from_file(path: str) -> NativeScene: ...
    @staticmethod
    def from_str(text: str, base_dir: str, file: str, name: str) -> NativeScene: ...
    @staticmethod
    def dict_to_toml(d: Any) -> str: ...
    def with_overrides(self, kwargs: Dict[str, Any]) -> NativeScene: ...
    def plan_json(self) -> str: ...
    def integrator_json(self) -> str: ...
    text: str
    label: str
    warnings: List[str]
    size: Tuple[int, int]
    wavelengths_nm: List[float]
    band_edges_nm: List[float]
    output_files: List[str]
    overrides: Dict[str, Optional[int]]

class NativeResult:
    shape: Tuple[int, int, int]
    wavelengths_nm: List[float]
    band_edges_nm: List[float]
    threads: int
    run_warnings: List[str]
    def radiance_bytes(self) -> bytes: ...
    def stderr_bytes(self) -> Optional[bytes]: ...
    def rgb_bytes(self) -> bytes: ...
    def report_json(self, outputs: List[str]) -> str: ...
    def sensor_csvs(self) -> List[Tuple[str, str, str, Optional[str]]]: ...
    def save(self, dir: str) -> List[str]: ...

def render(
    scene: NativeScene,
    threads: Optional[int] = None,
    progress: Optional[Callable[[str, int, int], None]] = None,
    quiet: bool = False,
    max_seconds: Optional[float] = None,
    max_memory: Optional[str] = None,
) -> NativeResult: ...
def refraction(
    atmosphere: str,
    apparent_altitudes_deg: Sequence[float],
    wavelength_nm: float = 550.0,
    observer_height_m: float = 0.0,
    sun_lower_limb_deg: float = 0.0,
    method: Optional[str] = None,
) -> Dict[str, Any]: ...
def terrestrial(
    atmosphere: str,
    apparent_altitudes_deg: Sequence[float],
    ground_distances_km: Sequence[float],
    wavelength_nm: float = 550.0,
    observer_height_m: float = 0.0,
) -> Dict[str, Any]: ...
def lines_of_sight(
    atmosphere: str,
    targets: Sequence[Tuple[float, float]],
    wavelength_nm: float = 550.0,
    observer_height_m: float = 2.0,
) -> Dict[str, Any]: ...
def trace(
    scene: NativeScene,
    origin: Sequence[float],
    direction: Sequence[float],
    wavelength_nm: float = 550.0,
    events: int = 32,
    max_length_m: float = 1.0e8,
) -> Dict[str, Any]: ...
def luminaire(path: str, variant: Optional[str] = None) -> Dict[str, Any]: ...
def tonemap(source: Union[NativeResult, str], **options: Any) -> Tuple[int, int, bytes, List[str]]: ...
