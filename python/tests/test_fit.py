"""The conoscope fit from Python: a photo made by the full renderer (not the fit's own model) through a
camera's tone curve gives back its thickness; bad photos are refused; a callback cancels."""
import numpy as np
import pytest

import petroscope


def camera_photo(thickness_um, size_px=96):
    figure = petroscope.conoscope(mineral="muscovite", thickness_um=thickness_um, size_px=size_px)
    return np.clip(figure.image, 0.0, 1.0) ** (1 / 2.2)  # gamma 2.2, as the fit's camera model starts


def test_the_thickness_comes_back_within_one_percent_and_two_sigma():
    fit = petroscope.fit_conoscope(camera_photo(40.0), mineral="muscovite", thickness_um=30.0, fixed={"field_radius_px": 48.0})
    assert fit["acceptable"], fit["verdict"]
    thickness, sigma = fit["values"]["thickness_um"], fit["sigma"]["thickness_um"]
    assert abs(thickness - 40.0) < 0.4  # 1%
    assert sigma is not None and abs(thickness - 40.0) <= 2 * sigma
    assert fit["free"]["thickness_um"] and not fit["free"]["field_radius_px"]
    assert fit["model"].shape == (96, 96, 3)


def test_bad_photos_and_arguments_are_refused():
    with pytest.raises(TypeError, match="divide by 255"):
        petroscope.fit_conoscope(np.zeros((64, 64, 3), dtype=np.uint8))
    with pytest.raises(ValueError, match="height, width"):
        petroscope.fit_conoscope(np.zeros((64, 64, 4), dtype=np.float32))
    with pytest.raises(ValueError, match="unknown parameter 'thickness'"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), free=["thickness"])
    with pytest.raises(ValueError, match="starting thickness"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), thickness_um=-3.0)
    with pytest.raises(petroscope.Cancelled):
        petroscope.fit_conoscope(camera_photo(40.0, 64), progress=lambda fraction: False)
