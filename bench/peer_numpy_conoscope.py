#!/usr/bin/env python3
"""Benchmark peer (issue 22, goal 2): a plain numpy script that draws the textbook approximation of the
default figure `petroscope conoscope --mineral calcite --cut optic-axis --size 512 -o c.png`, end to end:
start-up, tables, 81 wavelengths, PNG. The time of this script is what petroscope's end-to-end time is
compared with (docs/conoscope.md, "End to end"); its picture is an approximation, not a reference.

    /usr/bin/python3 bench/peer_numpy_conoscope.py OUTPUT.png

The approximation (Hartshorne & Stuart, "Crystals and the Polarising Microscope", 4th ed., ch. 9; Born &
Wolf §15.4.4): a uniaxial plate of thickness d cut normal to its optic axis, crossed polars; a ray leaving
at angle θ (sin θ = NA·r) travels at θ' with sin θ' = sin θ / n̄ and meets the path difference
Δ = d (n_o − n_e) sin²θ' / cos θ' (the extraordinary index to second order in θ'); the intensity is
sin²(2φ) sin²(πΔ/λ), φ the azimuth. No Fresnel losses, no exact modes. White light: CIE 1931 observer and
D65 at 380 … 780 nm by 5 nm, XYZ to linear sRGB (IEC 61966-2-1), white balanced, sRGB encoded."""
import struct
import sys
import zlib
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parent.parent
SIZE_PX, NA, THICKNESS_UM = 512, 0.85, 30.0


def calcite_indices(wavelength_um):
    """Ghosh 1999 (Opt. Commun. 163, 95), refractiveindex.info formula 2, as minerals/calcite.txt."""
    def sellmeier(c1, c2, c3, c4, c5):
        squared = wavelength_um ** 2
        return np.sqrt(1 + c1 + c2 * squared / (squared - c3) + c4 * squared / (squared - c5))
    return sellmeier(0.73358749, 0.96464345, 1.94325203e-2, 1.82831454, 120), sellmeier(0.35859695, 0.82427830, 1.06689543e-2, 0.14429128, 120)


def table(name, wavelengths_nm):
    data = np.loadtxt(ROOT / "data" / "cie" / name, delimiter=",", skiprows=1)
    return data[np.searchsorted(data[:, 0], wavelengths_nm), 1:]


def figure():
    wavelengths_nm = np.arange(380.0, 781.0, 5.0)
    weights = table("cie1931_2deg_cmf_1nm.csv", wavelengths_nm) * table("cie_illuminant_d65_1nm.csv", wavelengths_nm)
    weights /= weights[:, 1].sum()
    axis = (np.arange(SIZE_PX) + 0.5 - SIZE_PX / 2) / (SIZE_PX / 2)
    x, y = np.meshgrid(axis, -axis)
    sin_theta = NA * np.hypot(x, y)
    inside = sin_theta <= NA
    azimuth_factor = np.sin(2 * np.arctan2(y, x)) ** 2
    xyz = np.zeros((SIZE_PX, SIZE_PX, 3))
    n_o, n_e = calcite_indices(wavelengths_nm / 1000)
    for k, wavelength_nm in enumerate(wavelengths_nm):
        sin_inside = sin_theta / (0.5 * (n_o[k] + n_e[k]))
        path_difference_nm = 1000 * THICKNESS_UM * (n_o[k] - n_e[k]) * sin_inside ** 2 / np.sqrt(1 - sin_inside ** 2)
        intensity = azimuth_factor * np.sin(np.pi * path_difference_nm / wavelength_nm) ** 2
        xyz += intensity[:, :, None] * weights[k]
    to_rgb = np.array([[3.2406, -1.5372, -0.4986], [-0.9689, 1.8758, 0.0415], [0.0557, -0.2040, 1.0570]])
    rgb = np.clip((xyz @ to_rgb.T) * inside[:, :, None], 0, 1)
    encoded = np.where(rgb <= 0.0031308, 12.92 * rgb, 1.055 * rgb ** (1 / 2.4) - 0.055)
    return np.round(255 * encoded).astype(np.uint8)


def write_png(path, rgb):
    """PNG (ISO/IEC 15948): signature, IHDR, one IDAT of filter-0 rows, IEND."""
    def chunk(kind, data):
        return struct.pack(">I", len(data)) + kind + data + struct.pack(">I", zlib.crc32(kind + data))
    rows = np.concatenate([np.zeros((rgb.shape[0], 1), np.uint8), rgb.reshape(rgb.shape[0], -1)], axis=1)
    header = struct.pack(">IIBBBBB", rgb.shape[1], rgb.shape[0], 8, 2, 0, 0, 0)
    Path(path).write_bytes(b"\x89PNG\r\n\x1a\n" + chunk(b"IHDR", header) + chunk(b"IDAT", zlib.compress(rows.tobytes(), 6)) + chunk(b"IEND", b""))


if __name__ == "__main__":
    if len(sys.argv) != 2:
        sys.exit("usage: peer_numpy_conoscope.py OUTPUT.png")
    write_png(sys.argv[1], figure())
