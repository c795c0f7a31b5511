"""What the examples share: their command line (--output, --size) and turning linear sRGB into what a
screen shows. The examples draw on matplotlib's Figure directly, so no window or GUI backend is needed."""
import argparse
import pathlib

import numpy as np


def arguments(description, size_px):
    """--output FOLDER (default: this folder, where the docs show the pictures) and --size PIXELS."""
    parser = argparse.ArgumentParser(description=description)
    parser.add_argument("--output", type=pathlib.Path, default=pathlib.Path(__file__).resolve().parent, help="folder of the PNG written")
    parser.add_argument("--size", type=int, default=size_px, help="width of the rendered images in pixels (default %(default)s)")
    return parser.parse_args()


def display(linear_srgb):
    """Linear sRGB (1 = white) as sRGB codes 0 … 1 for the screen: the sRGB transfer curve (IEC 61966-2-1)."""
    x = np.clip(linear_srgb, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055)


def save(figure, folder, name):
    """Writes the figure to folder/name through a temporary file, so that a failed run leaves no half PNG."""
    folder.mkdir(parents=True, exist_ok=True)
    path = folder / name
    partial = folder / (name + ".partial.png")
    figure.savefig(partial, dpi=100, bbox_inches="tight")
    partial.replace(path)
    print("wrote", path)
