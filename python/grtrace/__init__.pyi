# Type stubs of the grtrace package. The keywords of render() and trace_ray() are grtrace-render's options with
# underscores (grtrace.options() lists them with their defaults; python/tests/test_api.py checks this file lists
# exactly those).
from typing import Any, Callable, Dict, List, Literal, Optional, Sequence, Union

import numpy
import numpy.typing

__version__: str

FloatArray = numpy.typing.NDArray[numpy.float32]
DoubleArray = numpy.typing.NDArray[numpy.float64]
Number = Union[int, float]
Triple = Sequence[Number]
ProgressCallback = Callable[[int, int], Any]

class Frame:
    @property
    def width(self) -> int: ...
    @property
    def height(self) -> int: ...
    @property
    def channel_names(self) -> List[str]: ...
    def channel(self, name: str) -> FloatArray: ...
    def __getitem__(self, name: str) -> FloatArray: ...
    def __contains__(self, name: str) -> bool: ...
    @property
    def channels(self) -> Dict[str, FloatArray]: ...
    def rgb(self) -> FloatArray: ...
    @property
    def header(self) -> Dict[str, str]: ...
    @property
    def report(self) -> Dict[str, Any]: ...
    def write_exr(self, path: str, compression: str = "zips", preview: bool = True) -> None: ...

class Ray:
    lambda_: DoubleArray
    x: DoubleArray
    k: DoubleArray
    h: DoubleArray
    step: numpy.typing.NDArray[numpy.int32]
    cartesian: DoubleArray
    redshift: DoubleArray
    status: str
    outcome: Dict[str, Any]
    chart: Literal["spherical", "cartesian"]
    def __len__(self) -> int: ...

def render(
    *,
    progress: Union[None, bool, ProgressCallback] = None,
    scene: str = "checker",
    metric: str = "schwarzschild",
    mass: Number = 1,
    spin: Number = 0,
    charge: Number = 0.5,
    lambda_: Number = 1e-5,
    throat: Number = 1,
    chart: str = "bl",
    camera_r: Number = 200,
    camera_theta: Number = 90,
    camera_phi: Number = 0,
    observer: Optional[str] = None,
    velocity: Triple = (0, 0, 0),
    look: Triple = (-1, 0, 0),
    up: Triple = (0, -1, 0),
    fov: Number = 90,
    width: int = 1024,
    height: int = 1024,
    tableau: str = "rkf78",
    control: str = "i",
    step: Number = 0,
    rtol: Number = 1e-9,
    atol: Number = 1e-11,
    sky_radius: Number = 400,
    angle_correction: str = "exact",
    max_steps: int = 100000,
    tracer: str = "auto",
    device: str = "auto",
    table_rays: int = 1024,
    sky_texture: str = "",
    checker_squares: int = 18,
    disk_inner: Optional[Number] = None,
    disk_outer: Number = 20,
    disk_retrograde: bool = False,
    spectrum: str = "",
    rings: bool = False,
    ring_field: Number = 8,
    ring_cuts: int = 0,
    redshift_power: Number = 3,
    line_energy: Number = 6.4,
    emissivity_index: Number = 3,
    emissivity_index_outer: Optional[Number] = None,
    emissivity_break: Optional[Number] = None,
    energy_range: Optional[Sequence[Number]] = None,
    energy_bins: int = 200,
    line_finest: Number = 0.015625,
    disk_transparent: bool = False,
    disk_light: bool = False,
    accretion_gas: str = "free-fall",
    accretion_power: float = 2,
    source: str = "m87",
    accretion_rate: Optional[Number] = None,
    frequency: Number = 230,
    torus_inner: Number = 6,
    torus_peak: Number = 10,
    torus_opacity: Number = 0,
    threads: int = 0,
    error_map: bool = False,
    no_mirrors: bool = False,
) -> Frame: ...
def trace_ray(
    pixel: Optional[Sequence[int]] = None,
    *,
    position: Optional[Sequence[Number]] = None,
    momentum: Optional[Sequence[Number]] = None,
    samples_per_step: int = 8,
    scene_objects: bool = True,
    scene: str = "checker",
    metric: str = "schwarzschild",
    mass: Number = 1,
    spin: Number = 0,
    charge: Number = 0.5,
    lambda_: Number = 1e-5,
    throat: Number = 1,
    chart: str = "bl",
    camera_r: Number = 200,
    camera_theta: Number = 90,
    camera_phi: Number = 0,
    observer: Optional[str] = None,
    velocity: Triple = (0, 0, 0),
    look: Triple = (-1, 0, 0),
    up: Triple = (0, -1, 0),
    fov: Number = 90,
    width: int = 1024,
    height: int = 1024,
    tableau: str = "rkf78",
    control: str = "i",
    step: Number = 0,
    rtol: Number = 1e-9,
    atol: Number = 1e-11,
    sky_radius: Number = 400,
    angle_correction: str = "exact",
    max_steps: int = 100000,
    tracer: str = "auto",
    device: str = "auto",
    table_rays: int = 1024,
    sky_texture: str = "",
    checker_squares: int = 18,
    disk_inner: Optional[Number] = None,
    disk_outer: Number = 20,
    disk_retrograde: bool = False,
    spectrum: str = "",
    rings: bool = False,
    ring_field: Number = 8,
    ring_cuts: int = 0,
    redshift_power: Number = 3,
    line_energy: Number = 6.4,
    emissivity_index: Number = 3,
    emissivity_index_outer: Optional[Number] = None,
    emissivity_break: Optional[Number] = None,
    energy_range: Optional[Sequence[Number]] = None,
    energy_bins: int = 200,
    line_finest: Number = 0.015625,
    disk_transparent: bool = False,
    disk_light: bool = False,
    accretion_gas: str = "free-fall",
    accretion_power: float = 2,
    source: str = "m87",
    accretion_rate: Optional[Number] = None,
    frequency: Number = 230,
    torus_inner: Number = 6,
    torus_peak: Number = 10,
    torus_opacity: Number = 0,
    threads: int = 0,
    error_map: bool = False,
    no_mirrors: bool = False,
) -> Ray: ...
def line_profile(**options: Any) -> Dict[str, Any]: ...
def ring_image(**options: Any) -> Dict[str, Any]: ...
def read_exr(path: str) -> Frame: ...
def frame(channels: Dict[str, Any], header: Optional[Dict[str, str]] = None) -> Frame: ...
def options() -> List[Dict[str, Any]]: ...
def metrics() -> List[Dict[str, Any]]: ...
def scenes() -> List[str]: ...
def methods() -> List[Dict[str, str]]: ...
def tracers() -> List[str]: ...
def devices() -> List[str]: ...
def gpu() -> Dict[str, Any]: ...
