"""Off-centre figures: a sweep of the cut's tilt × its azimuth for aragonite (acute bisectrix), as a
grid of conoscopic figures. As the cut tilts away from the bisectrix the figure's centre moves out of
the field toward the azimuth; the frames render in parallel, each on one core.

Run: PYTHONPATH=build/python python3 docs/examples/sweep_tilt_azimuth.py"""
from matplotlib.figure import Figure

import petroscope
from example_support import arguments, display, save

VARY = {"tilt_deg": [0, 10, 20], "azimuth_deg": [0, 30, 60, 90]}


def main():
    options = arguments(__doc__, size_px=200)
    sweep = petroscope.sweep(petroscope.conoscope, VARY, mineral="aragonite", thickness_um=50, size_px=options.size,
                             progress=lambda fraction: print(f"\r{fraction:4.0%}", end="", flush=True))
    print()
    images = sweep.grid()  # (tilts, azimuths, height, width, 3)
    rows, columns = sweep.shape
    plots = Figure(figsize=(2.2 * columns, 2.3 * rows)).subplots(rows, columns, squeeze=False)
    for row in range(rows):
        for column in range(columns):
            plot = plots[row][column]
            plot.imshow(display(images[row, column]))
            plot.set_title(f"tilt {VARY['tilt_deg'][row]}°, azimuth {VARY['azimuth_deg'][column]}°", fontsize=9)
            plot.set_axis_off()
    save(plots[0][0].figure, options.output, "sweep_tilt_azimuth.png")
    luminance = sweep.measurement("mean_luminance").reshape(sweep.shape)
    print("mean luminance (rows: tilt, columns: azimuth):")
    print(luminance.round(3))


if __name__ == "__main__":
    main()
