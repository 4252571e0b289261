"""grtrace: general-relativistic ray tracing from Python.

Light rays are null geodesics traced backwards from a camera through a curved spacetime (Schwarzschild, Kerr,
Reissner-Nordstrom, Schwarzschild-de Sitter, a wormhole, flat space) until they reach the horizon, an object (a
thin Keplerian disk) or the sky. The tracing is grtrace's C++ application library, the same code and the same
checks as the command-line tool grtrace-render: every keyword below is one of its options with underscores for
dashes (``camera_r`` for ``--camera-r``), and a bad value raises ``ValueError`` with the message the tool prints.

    >>> import grtrace
    >>> frame = grtrace.render(metric="kerr", spin=0.9, scene="disk", camera_r=50, camera_theta=80,
    ...                        fov=30, width=256, height=256)
    >>> frame["redshift"].shape                   # a numpy view of the frame's own memory
    (256, 256)
    >>> frame.report["tracer"], frame.report["status_counts"]["hit"] > 0
    ('kerr-closed-form', True)
    >>> ray = grtrace.trace_ray(pixel=(128, 100), metric="kerr", spin=0.9, scene="disk", camera_r=50,
    ...                         camera_theta=80, fov=30, width=256, height=256)
    >>> ray.x.shape[1], ray.outcome["object"]
    (4, 'disk')

Rendering releases the GIL and runs on all cores (``threads``); Ctrl-C stops it within a tile's time and raises
KeyboardInterrupt. ``grtrace.options()`` lists every keyword with its default and meaning; ``grtrace.metrics()``,
``scenes()``, ``methods()``, ``tracers()`` and ``devices()`` what there is to choose from.
"""

from __future__ import annotations

import sys as _sys
from typing import Any, Callable, Dict, List, Optional, Sequence, Union

from . import _grtrace

__version__: str = _grtrace.__version__
"""The version of the C++ package this module was built from (grtrace/version.hpp)."""

__all__ = [
    "Frame",
    "Ray",
    "render",
    "trace_ray",
    "read_exr",
    "frame",
    "options",
    "metrics",
    "scenes",
    "methods",
    "tracers",
    "devices",
    "gpu",
    "__version__",
]


class Frame:
    """A frame: its channels as numpy arrays, its header and, for a render, its report.

    ``frame["redshift"]`` (or ``frame.channel("redshift")``) is a (height, width) float32 array over the frame's own
    memory: no copy is made, and the frame stays alive while the array does. The channels of a render are R, G, B
    (linear colour), object (0 sky, 1 horizon, 2 disk, ...), status (0 escaped, 1 captured, 2 hit, 3 max_steps,
    4 step_underflow, 5 non_finite), redshift (f_obs / f_src, NaN where undefined), sky_theta and sky_phi (the
    escaped ray's direction at infinity, radians) and steps; with ``error_map=True`` also error.
    """

    __slots__ = ("_frame",)

    def __init__(self, compiled: "_grtrace.Frame") -> None:
        self._frame = compiled

    @property
    def width(self) -> int:
        """Pixels across."""
        return self._frame.width

    @property
    def height(self) -> int:
        """Pixels down."""
        return self._frame.height

    @property
    def channel_names(self) -> List[str]:
        """The channels, in the order the EXR file lists them."""
        return list(self._frame.channel_names)

    def channel(self, name: str):
        """The channel `name` as a (height, width) float32 numpy array (a view, not a copy)."""
        return self._frame.channel(name)

    def __getitem__(self, name: str):
        return self._frame.channel(name)

    def __contains__(self, name: str) -> bool:
        return name in self._frame.channel_names

    @property
    def channels(self) -> Dict[str, Any]:
        """Every channel by name, each a numpy view."""
        return {name: self._frame.channel(name) for name in self._frame.channel_names}

    def rgb(self):
        """The linear colour as a new (height, width, 3) float32 array (the channels R, G, B stacked)."""
        import numpy

        return numpy.stack([self["R"], self["G"], self["B"]], axis=-1)

    @property
    def header(self) -> Dict[str, str]:
        """The EXR header's record: the request (metric, scene, method, camera) and the report, as text."""
        return dict(self._frame.header)

    @property
    def report(self) -> Dict[str, Any]:
        """What the render reports, typed, with the keys of grtrace-render's JSON line: width, height, seconds,
        rays_per_second, mean_steps, status_counts, tracer, tableau, control, device, sky_continuation, rtol, atol,
        threads, traced_rays, mirrors, ... and setup_seconds (the tracer's build, within seconds). Empty for a frame
        read from a file (its header has the record)."""
        return self._frame.report

    def write_exr(self, path: str, compression: str = "zips", preview: bool = True) -> None:
        """Writes the frame to the OpenEXR file `path` (every channel, lossless, and the header), and with
        `preview` its 8-bit PNG preview beside it (.png), whole or not at all. ValueError for a path that cannot be
        written or an unknown compression (zips, zip, piz, rle, none)."""
        self._frame.write_exr(path, compression, preview)

    def __repr__(self) -> str:
        tracer = self._frame.report.get("tracer", "")
        what = f", tracer {tracer!r}" if tracer else ""
        return f"<grtrace.Frame {self.width}x{self.height}, channels {', '.join(self.channel_names)}{what}>"


class Ray:
    """One ray's path, sampled along its accepted steps (several points a step, from the dense output).

    Arrays (numpy, one row a sample): ``lambda_`` the affine parameter, ``x`` the coordinates (N, 4) and ``k`` the
    momenta (N, 4) in the metric's chart (``chart``: "spherical" (t, r, theta, phi), or "cartesian" (t, x, y, z)
    for Kerr-Schild), ``cartesian`` the points embedded in 3D (N, 3), ``h`` the step each sample lies on, ``step``
    its index, ``redshift`` the observer's frequency over a static observer's at the sample (NaN without a camera).
    ``status`` says how the path ended; ``outcome`` what a frame's pixel shows for the ray (status, object, radius,
    redshift, steps).
    """

    __slots__ = ("lambda_", "x", "k", "h", "step", "cartesian", "redshift", "status", "outcome", "chart")

    def __init__(self, d: Dict[str, Any]) -> None:
        self.lambda_ = d["lambda"]
        self.x = d["x"]
        self.k = d["k"]
        self.h = d["h"]
        self.step = d["step"]
        self.cartesian = d["cartesian"]
        self.redshift = d["redshift"]
        self.status: str = d["status"]
        self.outcome: Dict[str, Any] = d["outcome"]
        self.chart: str = d["chart"]

    def __len__(self) -> int:
        return len(self.lambda_)

    def __repr__(self) -> str:
        return f"<grtrace.Ray {len(self)} samples, {self.status}, ended on {self.outcome['object'] or '-'}>"


ProgressCallback = Callable[[int, int], Any]


def _progress_printer() -> ProgressCallback:
    """A progress bar on stderr, redrawn at most every 0.1 s."""
    import time

    state = {"last": 0.0}

    def show(done: int, total: int) -> None:
        now = time.monotonic()
        if now - state["last"] < 0.1 and done < total:
            return
        state["last"] = now
        share = done / total if total else 1.0
        bar = "#" * int(30 * share)
        _sys.stderr.write(f"\rrender [{bar:<30}] {100 * share:5.1f} %")
        if done >= total:
            _sys.stderr.write("\n")
        _sys.stderr.flush()

    return show


def render(*, progress: Union[None, bool, ProgressCallback] = None, **options: Any) -> Frame:
    """Renders a frame and returns it (a :class:`Frame`): the channels as numpy arrays and the report.

    Keywords are grtrace-render's options with underscores (see :func:`options` for every one with its default):
    the scene (``scene``: checker, sky, redshift, disk), the metric (``metric``, ``mass``, ``spin``, ``charge``,
    ``lambda_`` (the tool's --lambda: ``lambda`` is Python's), ``throat``, ``chart``), the camera
    (``camera_r``, ``camera_theta``, ``camera_phi`` in degrees, ``observer``, ``velocity``, ``look``, ``up``,
    ``fov``, ``width``, ``height``), the method (``tableau``, ``control``, ``rtol``, ``atol``, ``step``,
    ``max_steps``), ``tracer``, ``device`` (auto, cpu, cuda: chosen as grtrace-render chooses), ``threads`` and the
    rest; the disk drawn by its light with ``disk_light=True`` or ``disk_transparent=True`` (channels intensity and
    intensity_n0 .. intensity_n3_up by image order; ``emissivity_index``, ``redshift_power``); a medium
    (``scene``: accretion, riaf, torus) whose every pixel is integrated also splits its intensity by image order
    (the same channels; the report's flux_n0 .. flux_n3_up). ``progress``: True draws a bar on stderr; a callable
    gets (pixels done, pixels in all) every 20 ms.

    Raises ValueError (the tool's message) for a bad keyword or value, before any work; KeyboardInterrupt when
    interrupted (Ctrl-C), within a tile's time, leaving nothing behind.
    """
    if progress is True:
        progress = _progress_printer()
    elif progress is False:
        progress = None
    elif progress is not None and not callable(progress):
        raise ValueError("progress must be None, True or a callable (done, total)")
    return Frame(_grtrace._render(progress, options))


def trace_ray(
    pixel: Optional[Sequence[int]] = None,
    *,
    position: Optional[Sequence[float]] = None,
    momentum: Optional[Sequence[float]] = None,
    samples_per_step: int = 8,
    scene_objects: bool = True,
    **options: Any,
) -> Ray:
    """Traces one ray and returns its path (a :class:`Ray`).

    Either ``pixel=(column, row)`` of the camera the keywords describe (as :func:`render` reads them; row 0 at the
    top), or ``position`` and ``momentum`` (4 numbers each, in the metric's chart: (t, r, theta, phi), or
    (t, x, y, z) for Kerr-Schild; a camera ray is past-directed, k^t < 0). The ray is integrated by the general
    tracer with the request's method; with ``scene_objects`` the scene's objects (the disk) end it, else only the
    horizon and the sky sphere do. ``samples_per_step`` points are kept per accepted step (1 .. 1000).
    """
    return Ray(_grtrace._trace_ray(pixel, position, momentum, samples_per_step, scene_objects, options))


def line_profile(**options: Any) -> Dict[str, Any]:
    """The line profile of a thin disk around a Kerr (or Schwarzschild) hole as a distant observer sees it: the flux
    per energy bin of a line emitted at ``line_energy`` by the disk's gas, in total and by image order n = 0, 1, 2,
    >= 3, every ray in closed form on an adaptive image-plane mesh (grtrace-render ``--spectrum line``).

    Keywords are grtrace-render's (``scene`` and ``spectrum`` default to disk and line here): ``metric`` (kerr or
    schwarzschild), ``spin``, ``mass``, ``camera_theta`` (the inclination, degrees), ``disk_inner`` (default: the
    ISCO), ``disk_outer``, ``disk_retrograde``, ``disk_transparent``, ``line_energy``, ``emissivity_index``,
    ``emissivity_index_outer``, ``emissivity_break``, ``energy_range`` ((lo, hi); default: around the light's
    energies), ``energy_bins``, ``line_finest``, ``threads``; a frame's options raise ValueError.

    Returns a dict: ``edges`` (bins + 1 energies), ``flux`` (F_E, energy flux per unit energy, in eps(r = M) M^2:
    a distant observer's flux times D^2 / M^2), ``flux_by_order`` (four arrays that sum to ``flux``), ``report``
    (seconds, rays, the totals by order, the bins' range, the disk's radii) and ``csv`` (the table as text).
    """
    options.setdefault("spectrum", "line")
    options.setdefault("scene", "disk")
    return _grtrace._line_profile(options)


def ring_image(**options: Any) -> Dict[str, Any]:
    """The photon ring of a thin disk around a Kerr (or Schwarzschild) hole by order, as a distant observer sees it:
    the image of each order n = 0, 1, 2, >= 3, each ring integrated across its width however thin and taken into
    the pixels with its flux kept, every ray in closed form (grtrace-render ``--rings``).

    Keywords are grtrace-render's (``scene`` and ``rings`` default to disk and True here): ``metric`` (kerr or
    schwarzschild), ``spin``, ``mass``, ``camera_theta`` (the inclination, degrees), ``disk_inner`` (default: the
    ISCO), ``disk_outer``, ``disk_retrograde``, ``disk_transparent``, ``emissivity_index``,
    ``emissivity_index_outer``, ``emissivity_break``, ``width``, ``height``, ``ring_field`` (the image's half width,
    M), ``ring_cuts``, ``redshift_power`` (the observed intensity is g^p eps(r)), ``source`` (m87 or sgr-a: the
    rings' sizes in microarcseconds too), ``threads``; a frame's options raise ValueError.

    Returns a dict: ``intensity`` (four arrays, height x width, the top row first: each pixel's mean intensity of
    order n = 0, 1, 2, >= 3, in eps(r = M) units), ``flux`` (each order's integral over the field, M^2 eps(r = M)),
    ``ring_diameter`` and ``ring_width`` (n = 1, 2, 3; M) and ``report`` (grtrace-render's JSON line: seconds,
    rays, fluxes, the rings' sizes).
    """
    options.setdefault("rings", True)
    options.setdefault("scene", "disk")
    return _grtrace._ring_image(options)


def read_exr(path: str) -> Frame:
    """Reads an OpenEXR file (a frame grtrace-render or :meth:`Frame.write_exr` wrote, or any float image) as a
    :class:`Frame`: its channels as numpy arrays and its header. ValueError for a file that is not a readable EXR
    or too large for the memory limit (GRTRACE_MEMORY_LIMIT)."""
    return Frame(_grtrace._read_exr(str(path)))


def frame(channels: Dict[str, Any], header: Optional[Dict[str, str]] = None) -> Frame:
    """A :class:`Frame` of your own arrays (each (height, width), converted to float32) and header strings, e.g. to
    write with :meth:`Frame.write_exr`."""
    return Frame(_grtrace._frame(dict(channels), dict(header or {})))


def options() -> List[Dict[str, Any]]:
    """Every keyword :func:`render` and :func:`trace_ray` take: name (the keyword), option (grtrace-render's
    spelling), default (as text), help, flag (True/False keywords)."""
    return _grtrace._options()


def metrics() -> List[Dict[str, Any]]:
    """The named metrics: name, help, has_mass, charts, parameters (name, default, help)."""
    return _grtrace._metrics()


def scenes() -> List[str]:
    """The preset scenes: checker, sky, redshift, disk."""
    return _grtrace._scenes()


def methods() -> List[Dict[str, str]]:
    """The declared integration methods (tableau, control, purpose): the pairs compiled into the library."""
    return _grtrace._methods()


def tracers() -> List[str]:
    """The tracers a request can name: auto (the fastest whose assumptions hold), general, planar."""
    return _grtrace._tracers()


def devices() -> List[str]:
    """The devices a request can name: auto, cpu, cuda."""
    return _grtrace._devices()


def gpu() -> Dict[str, Any]:
    """Whether this build has the CUDA backend (built), a CUDA device (present), its name, or why not."""
    return _grtrace._gpu()


def _option_list() -> str:
    lines = []
    for o in options():
        default = "False" if o["flag"] else repr(o["default"])
        lines.append(f"    {o['name']} (default {default}): {o['help']}")
    return "\n".join(lines)


render.__doc__ = (render.__doc__ or "") + "\n    Every keyword:\n\n" + _option_list() + "\n"
