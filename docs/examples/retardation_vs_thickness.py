"""Retardation against thickness for common rock-forming minerals over the Michel-Lévy interference
colours: each mineral's line is t = Γ / Δn, its birefringence Δn at 550 nm from the mineral catalog
(the largest difference of its principal indices: a section that shows its highest colour).

Run: PYTHONPATH=build/python python3 docs/examples/retardation_vs_thickness.py"""
import numpy as np
from matplotlib.figure import Figure

import petroscope
from example_support import arguments, display, save

MINERALS = ["quartz", "orthoclase", "albite", "gypsum", "augite", "forsterite", "muscovite", "zircon"]
MAX_RETARDATION_NM = 2000.0
MAX_THICKNESS_UM = 50.0


def main():
    options = arguments(__doc__, size_px=800)
    chart = petroscope.michel_levy_colours(max_retardation_nm=MAX_RETARDATION_NM, step_nm=MAX_RETARDATION_NM / (options.size - 1))
    colours = display(chart["linear_srgb"])  # one colour per retardation, the same at every thickness
    plot = Figure(figsize=(10, 6)).subplots()
    plot.imshow(np.broadcast_to(colours[np.newaxis], (2, *colours.shape)), extent=(0, MAX_RETARDATION_NM, 0, MAX_THICKNESS_UM),
                aspect="auto", origin="lower")
    top_ticks, right_ticks = {}, {}  # each line is labelled where it leaves the chart: the top or the right edge
    for name in MINERALS:
        n = np.sort(petroscope.mineral(name).principal_n(550.0))
        birefringence = n[2] - n[0]
        nm_per_um = birefringence * 1e3
        plot.plot([0.0, MAX_THICKNESS_UM * nm_per_um], [0.0, MAX_THICKNESS_UM], color="black", linewidth=0.8)
        label = f"{name} {birefringence:.4f}"
        if MAX_THICKNESS_UM * nm_per_um <= MAX_RETARDATION_NM:
            top_ticks[MAX_THICKNESS_UM * nm_per_um] = label
        else:
            right_ticks[MAX_RETARDATION_NM / nm_per_um] = label
        print(f"{name:12s} birefringence {birefringence:.4f}: {30.0 * nm_per_um:6.0f} nm at 30 µm")
    top = plot.secondary_xaxis("top")
    top.set_xticks(list(top_ticks), list(top_ticks.values()), rotation=60, ha="left", fontsize=8)
    right = plot.secondary_yaxis("right")
    right.set_yticks(list(right_ticks), list(right_ticks.values()), fontsize=8)
    plot.axhline(30.0, color="white", linestyle="--", linewidth=1)
    plot.set(xlim=(0, MAX_RETARDATION_NM), ylim=(0, MAX_THICKNESS_UM), xlabel="retardation Γ (nm, at 550 nm)", ylabel="thickness (µm)")
    plot.set_title("Interference colours between crossed polars (D65, a section at 45°); lines: minerals by birefringence",
                   y=-0.2)
    save(plot.figure, options.output, "retardation_vs_thickness.png")


if __name__ == "__main__":
    main()
