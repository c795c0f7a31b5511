"""petroscope: the polarizing microscope and light in crystals, computed exactly.

Images come back as float32 numpy arrays (height, width, channels) inside a Result, with what their
channels and values mean and the numbers measured on them. Units are in the argument names
(thickness_um, wavelength_nm, stage_deg). Bad input raises ValueError or TypeError naming the argument;
a progress callback that returns False raises Cancelled; Ctrl-C raises KeyboardInterrupt. The
computations release the GIL, so several threads can compute at once. Guide: docs/python.md.
"""
import os as _os

from . import _petroscope

from ._petroscope import (
    Cancelled,
    Grain,
    InterfaceResult,
    Light,
    Medium,
    Mineral,
    Result,
    Section,
    Wave,
    conical,
    conoscope,
    fit_conoscope,
    fit_orthoscope,
    indicatrix_axes,
    interface,
    michel_levy_colours,
    mineral,
    minerals,
    orthoscope,
)

__version__ = "0.1.0"


def read_section(path):
    """The thin section of a folder or description file (thin_sections/README.md) as a Section.

    Reading the label image loads the image libraries, so they are loaded here, on first use, and not by
    `import petroscope`.
    """
    from ._files import read_section as _read

    return _read(_os.fspath(path))


def michel_levy_chart(*, mineral=None, max_retardation_nm=2000.0, step_nm=1.0, light=None, max_thickness_um=50.0):
    """The Michel-Lévy chart drawn as the command line draws it: a float32 array (height, width, 3), linear
    sRGB, interference colours over retardation (x) and thickness up to max_thickness_um (y), with the
    birefringence lines and labels. The arguments and the colours are michel_levy_colours'. Drawing loads
    the image libraries (OpenCV) on first use."""
    from ._files import michel_levy_chart as _draw

    return _draw(mineral=mineral, max_retardation_nm=max_retardation_nm, step_nm=step_nm, light=light, max_thickness_um=max_thickness_um)


def interface_case(path):
    """Solves an interface case file (docs/interface.md) as `petroscope interface --case` does, and returns
    its InterfaceResult. Reading JSON files is the files module's, loaded on first use."""
    from ._files import interface_case as _solve

    return _solve(_os.fspath(path))


def verify(*, cases_dir=None, own_sweeps=True):
    """The verification suite of the interface model, as `petroscope verify` runs it: the checks of every
    case file in cases_dir (default: the repository's verification/cases) and, with own_sweeps, petroscope's
    own sweeps (about a minute). Returns a list of dicts: name, statement, source, passed, checks (each a
    dict: quantity, measured, expected, tolerance, passed)."""
    from ._files import verify as _verify

    return _verify(cases_dir=None if cases_dir is None else _os.fspath(cases_dir), own_sweeps=own_sweeps)


def render_scene(path, *, samples_per_pixel=64, max_depth=15, polarizer_deg=None, no_polarizer=False, seed=1, exposure=1.0,
                 allow_large=False, progress=None):
    """A scene file (docs/render.md; the paper's scene: scenes/calcite-box.json) rendered by backward spectral
    polarized ray tracing, as `petroscope render` renders it.

    samples_per_pixel: paths per pixel, 1 to 65536 (to 1e6 with allow_large). max_depth: crystal-face
    interactions along a path, 1 to 100000. polarizer_deg: a camera polarizer (from the image's right toward
    up) instead of the scene's; no_polarizer ignores the scene's. seed: the image does not depend on the
    threads. exposure: multiplies the image. allow_large: above 4096 x 4096 px (88 bytes a pixel).
    progress: called with the fraction of rows done; return False to cancel. Ctrl-C cancels.

    Returns a Result: image float32 (height, width, 3), linear sRGB; measurements noise_median and noise_p90
    (the standard error of a pixel's luminance over its value, over the pixels that see a crystal); details:
    stokes_xyz (height, width, 12: XYZ of S0, S1, S2, S3), standard_error_y (height, width, 4), statistics.
    Scene files may name texture images: the image libraries are loaded on first use.
    """
    from ._files import render_scene as _render

    return _render(_os.fspath(path), samples_per_pixel=samples_per_pixel, max_depth=max_depth, polarizer_deg=polarizer_deg,
                   no_polarizer=no_polarizer, seed=seed, exposure=exposure, allow_large=allow_large, progress=progress)


def sweep(compute, vary, *, frames=None, jobs=0, progress=None, **arguments):
    """The frames of conoscope, orthoscope or conical over a grid of their numeric arguments, rendered in
    parallel (each frame on one thread, so a frame never depends on how the work was split).

    compute: petroscope.conoscope, petroscope.orthoscope or petroscope.conical (or its name).
    vary: {field: values}, e.g. {'tilt_deg': range(0, 40, 10), 'azimuth_deg': [0, 45, 90]}; the last field
      runs fastest. Fields: those of the function with their units; petroscope.sweep_fields(compute) lists them.
    frames: frame numbers of the grid to render (None: all); petroscope.shards splits them into parts for
      other processes or machines (docs/scaling.md), and Sweep.merge joins the parts.
    jobs: frames at once (0: one per core). progress: called with the fraction of frames done; return False
      to cancel. arguments: the function's other arguments, the same for every frame.

    Returns a Sweep: results (a Result per frame), images, grid(), measurement(name), values(frame).
    """
    from ._sweep import run

    return run(compute, vary, frames, jobs, progress, arguments)


def sweep_fields(compute):
    """The numeric arguments of conoscope, orthoscope or conical (or its name) that sweep can vary."""
    from ._sweep import _kind

    return _petroscope._sweep_fields(_kind(compute))


def shards(frame_count, count):
    """The frames 0 … frame_count−1 in `count` contiguous parts (as the command line's --shard K/N)."""
    from ._sweep import shards as _shards

    return _shards(frame_count, count)


def __getattr__(name):
    # Sweep needs numpy, which `import petroscope` does not load: it comes with its first use.
    if name == "Sweep":
        from ._sweep import Sweep

        return Sweep
    raise AttributeError("module 'petroscope' has no attribute " + repr(name))


def read_image(path):
    """An image file's values as a float32 array (height, width, channels): EXR and TIFF as stored (the
    command line's float output), PNG and JPEG as codes / 255 (a photo's camera values)."""
    from ._files import read_image as _read

    return _read(_os.fspath(path))


__all__ = [
    "Cancelled",
    "Grain",
    "InterfaceResult",
    "Light",
    "Medium",
    "Mineral",
    "Result",
    "Section",
    "Sweep",
    "Wave",
    "conical",
    "conoscope",
    "fit_conoscope",
    "fit_orthoscope",
    "indicatrix_axes",
    "interface",
    "interface_case",
    "michel_levy_chart",
    "michel_levy_colours",
    "mineral",
    "minerals",
    "orthoscope",
    "read_image",
    "read_section",
    "render_scene",
    "shards",
    "sweep",
    "sweep_fields",
    "verify",
]
