# Type stubs of the petroscope package: what editors and type checkers read. The docstrings (help())
# come from the extension module; units are in the argument names.
import os
from typing import Callable, Optional, Sequence, Tuple, Union

import numpy as np
import numpy.typing as npt

__version__: str

Progress = Optional[Callable[[float], Optional[bool]]]
"""Called with the fraction done (0 to 1); return False to cancel (raises Cancelled)."""

LightArgument = Union["Light", float, None]
"""A Light, a wavelength in nm (monochromatic light), or None (white light, D65)."""

class Cancelled(Exception): ...

class Result:
    image: npt.NDArray[np.float32]  # (height, width, channels)
    channels: list[str]
    pixel_values: str
    measurements: dict[str, Optional[float]]
    notes: list[str]
    details: dict[str, object]

class Light:
    def __init__(
        self,
        *,
        wavelength_nm: Optional[float] = None,
        wavelengths_nm: Tuple[float, float, float] = (380.0, 780.0, 5.0),
        illuminant: str = "D65",
        white_balance: bool = True,
        exposure: float = 1.0,
    ) -> None: ...
    @property
    def wavelength_nm(self) -> Optional[float]: ...
    @property
    def wavelengths_nm(self) -> list[float]: ...
    illuminant: str
    white_balance: bool
    exposure: float

class Mineral:
    name: str
    aliases: list[str]
    formula: str
    system: str
    optical_class: str  # 'isotropic', 'uniaxial' or 'biaxial'
    reference_wavelength_nm: float
    source: str
    file: str
    def principal_n(self, wavelength_nm: float) -> npt.NDArray[np.float64]: ...
    def summary(self, wavelength_nm: float) -> dict[str, object]: ...

def minerals() -> list[str]: ...
def mineral(name: str) -> Mineral: ...
def indicatrix_axes(
    mineral: str,
    *,
    cut: Optional[str] = None,
    azimuth_deg: float = 0.0,
    tilt_deg: float = 0.0,
    euler_zyz_deg: Optional[Sequence[float]] = None,
) -> npt.NDArray[np.float64]: ...

class Grain:
    def __init__(
        self, label: int, mineral: str, *, euler_zyz_deg: Sequence[float] = (0.0, 0.0, 0.0), thickness_um: Optional[float] = None
    ) -> None: ...
    label: int
    mineral: str
    thickness_um: Optional[float]
    @property
    def euler_zyz_deg(self) -> npt.NDArray[np.float64]: ...

class Section:
    def __init__(
        self,
        labels: npt.ArrayLike,
        grains: Sequence[Grain],
        *,
        pixel_size_um: float = 1.0,
        thickness_um: float = 30.0,
        name: str = "section",
    ) -> None: ...
    name: str
    width_px: int
    height_px: int
    pixel_size_um: float
    grains: list[Grain]
    @property
    def labels(self) -> npt.NDArray[np.uint16]: ...

def michel_levy_colours(
    *, mineral: Optional[str] = None, max_retardation_nm: float = 2000.0, step_nm: float = 1.0, light: LightArgument = None
) -> dict[str, object]: ...
def michel_levy_chart(
    *,
    mineral: Optional[str] = None,
    max_retardation_nm: float = 2000.0,
    step_nm: float = 1.0,
    light: LightArgument = None,
    max_thickness_um: float = 50.0,
) -> npt.NDArray[np.float32]: ...
class Medium:
    def __init__(self, n: Union[complex, Sequence[complex]], *, euler_zyz_deg: Sequence[float] = (0.0, 0.0, 0.0)) -> None: ...
    @staticmethod
    def of_mineral(mineral: str, wavelength_nm: float, *, euler_zyz_deg: Sequence[float] = (0.0, 0.0, 0.0)) -> "Medium": ...
    @property
    def principal_n(self) -> npt.NDArray[np.complex128]: ...
    @property
    def axes(self) -> npt.NDArray[np.float64]: ...

class Wave:
    kind: str  # 'reflected' or 'transmitted'
    mode: str  # 's+p', 'ordinary', 'extraordinary', 'fast', 'slow'
    direction: npt.NDArray[np.float64]
    ray_direction: npt.NDArray[np.float64]
    n: complex
    power: float
    stokes: npt.NDArray[np.float64]
    jones: Optional[npt.NDArray[np.complex128]]
    amplitude: Optional[complex]
    e_field: npt.NDArray[np.complex128]
    d_direction: npt.NDArray[np.float64]
    evanescent: bool

class InterfaceResult:
    waves: list[Wave]
    incident_n: complex
    incident_ray_direction: npt.NDArray[np.float64]

def interface(
    medium1: Medium,
    medium2: Medium,
    *,
    direction: Sequence[float],
    normal: Sequence[float] = (0.0, 0.0, 1.0),
    polarization: Union[str, Sequence[complex], Sequence[float]] = "unpolarized",
    mode: Optional[str] = None,
) -> InterfaceResult: ...
def interface_case(path: Union[str, os.PathLike[str]]) -> InterfaceResult: ...
def verify(*, cases_dir: Union[str, os.PathLike[str], None] = None, own_sweeps: bool = True) -> list[dict[str, object]]: ...
def read_section(path: Union[str, os.PathLike[str]]) -> Section: ...
def read_image(path: Union[str, os.PathLike[str]]) -> npt.NDArray[np.float32]: ...
def conoscope(
    *,
    mineral: str = "muscovite",
    thickness_um: float = 30.0,
    cut: Optional[str] = None,
    azimuth_deg: float = 0.0,
    tilt_deg: float = 0.0,
    euler_zyz_deg: Optional[Sequence[float]] = None,
    numerical_aperture: float = 0.85,
    size_px: int = 512,
    light: LightArgument = None,
    stage_deg: float = 0.0,
    polarizer_deg: float = 0.0,
    analyzer_deg: float = 90.0,
    analyzer_in: bool = True,
    surround_n: float = 1.54,
    mounting: str = "immersed",
    plate: Optional[str] = None,
    plate_slow_deg: float = 45.0,
    wedge_position: float = 0.5,
    exact_spectrum: bool = False,
    handedness: str = "right",
    progress: Progress = None,
) -> Result: ...
def fit_conoscope(
    photo: npt.NDArray[np.floating],
    *,
    mineral: str = "muscovite",
    cut: Optional[str] = None,
    light: LightArgument = None,
    numerical_aperture: float = 0.85,
    polarizer_deg: float = 0.0,
    analyzer_deg: float = 90.0,
    surround_n: float = 1.54,
    thickness_um: Optional[float] = None,
    thickness_range_um: Optional[Tuple[float, float]] = None,
    tilt_deg: float = 0.0,
    azimuth_deg: float = 0.0,
    free: Sequence[str] = (
        "thickness_um", "center_x_px", "center_y_px", "field_radius_px", "rotation_deg",
        "gain_r", "gain_g", "gain_b", "black_level", "gamma", "blur_variance_px2",
    ),
    fixed: dict[str, float] = {},
    candidates: int = 3,
    handedness: str = "right",
    projection: str = "sine",
    field_stop: str = "sharp",
    illumination: str = "even",
    sensor: str = "full-colour",
    progress: Progress = None,
    verbose: bool = False,
) -> dict[str, object]: ...
def orthoscope(
    section: Section,
    *,
    analyzer_in: bool = True,
    stage_deg: float = 0.0,
    polarizer_deg: float = 0.0,
    analyzer_deg: float = 90.0,
    plate: Optional[str] = None,
    plate_slow_deg: float = 45.0,
    wedge_position: float = 0.5,
    condenser_na: float = 0.0,
    condenser_rings: int = 0,
    thickness_um: Optional[float] = None,
    exact: bool = False,
    light: LightArgument = None,
    progress: Progress = None,
) -> Result: ...
def conical(
    *,
    crystal: str = "KGd(WO4)2",
    length_um: float = 20000.0,
    wavelength_nm: float = 633.0,
    optics: str = "wave",
    beam: str = "gaussian",
    waist_um: float = 40.0,
    pinhole_um: float = 25.0,
    filter_um: float = 50000.0,
    polarization: Union[str, Sequence[float]] = "unpolarized",
    z: float = 0.0,
    rotate_deg: float = 0.0,
    tilt_deg: float = 0.0,
    screen_distance_um: float = 50000.0,
    rays: int = 200000,
    size_px: int = 1024,
    progress: Progress = None,
) -> Result: ...
def fit_orthoscope(
    photos: Union[npt.NDArray[np.floating], Sequence[npt.NDArray[np.floating]]],
    *,
    mineral: str,
    stage_deg: Union[float, Sequence[float]] = 0.0,
    plate: Union[Optional[str], Sequence[Optional[str]]] = None,
    plate_slow_deg: float = 45.0,
    mask: Union[npt.ArrayLike, Sequence[npt.ArrayLike], None] = None,
    region: Union[Tuple[int, int, int, int], Sequence[Tuple[int, int, int, int]], None] = None,
    orientation: str = "max-birefringence",
    euler_zyz_deg: Optional[Tuple[float, float, float]] = None,
    thickness_range_um: Tuple[float, float] = (1.0, 200.0),
    exposure_free: bool = False,
    candidates: int = 4,
    condenser_na: float = 0.0,
    polarizer_deg: float = 0.0,
    analyzer_deg: float = 90.0,
    light: LightArgument = None,
    progress: Progress = None,
    verbose: bool = False,
) -> dict[str, object]: ...
def render_scene(
    path: Union[str, os.PathLike[str]],
    *,
    samples_per_pixel: int = 64,
    max_depth: int = 15,
    polarizer_deg: Optional[float] = None,
    no_polarizer: bool = False,
    seed: int = 1,
    exposure: float = 1.0,
    allow_large: bool = False,
    progress: Progress = None,
) -> Result: ...

Compute = Union[Callable[..., Result], str]
"""petroscope.conoscope, petroscope.orthoscope or petroscope.conical, or its name."""

class Sweep:
    kind: str
    axes: dict[str, npt.NDArray[np.float64]]
    frames: list[int]
    results: list[Result]
    @property
    def shape(self) -> Tuple[int, ...]: ...
    @property
    def frame_count(self) -> int: ...
    def values(self, frame: int) -> dict[str, float]: ...
    @property
    def images(self) -> npt.NDArray[np.float32]: ...
    def grid(self) -> npt.NDArray[np.float32]: ...
    def measurement(self, name: str) -> npt.NDArray[np.float64]: ...
    @staticmethod
    def merge(parts: Sequence["Sweep"]) -> "Sweep": ...
    def __len__(self) -> int: ...

def sweep(
    compute: Compute,
    vary: dict[str, Sequence[float]],
    *,
    frames: Optional[Sequence[int]] = None,
    jobs: int = 0,
    progress: Progress = None,
    **arguments: object,
) -> Sweep: ...
def sweep_fields(compute: Compute) -> list[str]: ...
def shards(frame_count: int, count: int) -> list[list[int]]: ...
