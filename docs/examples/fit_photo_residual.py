"""A photo of muscovite's conoscopic figure fitted for the flake's thickness, with the residual.

The photo is made the way a camera makes one: the figure rendered in white light, the camera's own
channel gains and tone curve (gamma 2.2), and sensor noise. The fit recovers the thickness with its
1σ and the camera's parameters. The residual (photo − best fit) is the noise, plus what the model leaves
out on purpose: four patches where the red gain pushed the brightest white past 1 and the photo clipped
(the fit leaves saturated pixels out), and a few pixels on the field's edge, where the circle of the
field cuts a pixel.

Run: PYTHONPATH=build/python python3 docs/examples/fit_photo_residual.py"""
import numpy as np
from matplotlib.figure import Figure

import petroscope
from example_support import arguments, display, save

TRUE_THICKNESS_UM = 40.0


def camera_photo(size_px, rng):
    figure = petroscope.conoscope(mineral="muscovite", thickness_um=TRUE_THICKNESS_UM, size_px=size_px)
    gains = np.array([1.08, 1.0, 0.93])  # the camera's white balance, a little off
    photo = np.clip(figure.image * gains, 0.0, 1.0) ** (1 / 2.2)
    return np.clip(photo + rng.normal(0.0, 0.01, photo.shape), 0.0, 1.0).astype(np.float32)


def main():
    options = arguments(__doc__, size_px=192)
    photo = camera_photo(options.size, np.random.default_rng(7))
    fit = petroscope.fit_conoscope(photo, mineral="muscovite", thickness_um=30.0, fixed={"field_radius_px": options.size / 2})
    thickness, sigma = fit["values"]["thickness_um"], fit["sigma"]["thickness_um"]
    residual = photo - fit["model"]

    plots = Figure(figsize=(13, 4.4)).subplots(1, 3)
    plots[0].imshow(photo)
    plots[0].set_title(f"photo (muscovite, {TRUE_THICKNESS_UM:g} µm)")
    plots[1].imshow(np.clip(fit["model"], 0.0, 1.0))
    plots[1].set_title(f"best fit: {thickness:.3f} ± {sigma:.3f} µm")
    scale = 4 * 0.01
    shown = plots[2].imshow(residual.mean(axis=2), cmap="RdBu", vmin=-scale, vmax=scale)
    plots[2].set_title(f"residual, mean of channels (rms {fit['rms_residual']:.4f})")
    plots[2].figure.colorbar(shown, ax=plots[2], fraction=0.046)
    for plot in plots:
        plot.set_axis_off()
    save(plots[0].figure, options.output, "fit_photo_residual.png")
    print(f"thickness {thickness:.3f} ± {sigma:.3f} µm (true {TRUE_THICKNESS_UM}); {fit['verdict']}")
    assert fit["acceptable"] and abs(thickness - TRUE_THICKNESS_UM) < 3 * sigma + 0.01 * TRUE_THICKNESS_UM


if __name__ == "__main__":
    main()
