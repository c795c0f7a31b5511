"""The conoscopic figure of a muscovite flake cut perpendicular to its acute bisectrix, between crossed
polars in white light, with its optic axes marked where the library measures them. The two melatopes
(the dark spots of the isogyres' vertices at 45°) lie at the marks; their separation is the apparent
optic angle 2E of the objective's field.

Run: PYTHONPATH=build/python python3 docs/examples/conoscope_optic_axes.py"""
import math

from matplotlib.figure import Figure

import petroscope
from example_support import arguments, display, save


def main():
    options = arguments(__doc__, size_px=512)
    # The stage at 45°: the isogyres open into hyperbolas whose vertices are the melatopes.
    figure = petroscope.conoscope(mineral="muscovite", thickness_um=30, stage_deg=45, size_px=options.size)
    measured = figure.measurements
    axes_xy = [(measured[f"optic_axis_{k}_x"], measured[f"optic_axis_{k}_y"]) for k in (1, 2)]

    plot = Figure(figsize=(6, 6)).subplots()
    # Row 0 of the image is the North: with origin "upper" and this extent, y grows upward as in the measurements.
    plot.imshow(display(figure.image), extent=(-1, 1, -1, 1), origin="upper")
    for k, (x, y) in enumerate(axes_xy, start=1):
        plot.plot(x, y, marker="o", markersize=14, markerfacecolor="none", markeredgecolor="red", markeredgewidth=2)
        plot.annotate(f"optic axis {k}", (x, y), xytext=(10, 10), textcoords="offset points", color="red")
    separation = math.dist(*axes_xy)
    plot.set(title=f"muscovite, 30 µm, stage 45°, NA 0.85\noptic axes {separation:.3f} field radii apart",
             xlabel="x (East), field radius = 1", ylabel="y (North)")
    save(plot.figure, options.output, "conoscope_optic_axes.png")
    # In a centred acute-bisectrix figure the optic axes are symmetric about the centre.
    (x1, y1), (x2, y2) = axes_xy
    assert abs(x1 + x2) < 1e-9 and abs(y1 + y2) < 1e-9, axes_xy
    print(f"optic axes at ({x1:.4f}, {y1:.4f}) and ({x2:.4f}, {y2:.4f}) field radii")


if __name__ == "__main__":
    main()
