"""The conoscope fit from Python: a photo made by the full renderer (not the fit's own model) through a
camera's tone curve gives back its thickness; bad photos are refused; a callback cancels."""
import numpy as np
import pytest

import petroscope


def camera_photo(thickness_um, size_px=96):
    figure = petroscope.conoscope(mineral="muscovite", thickness_um=thickness_um, size_px=size_px)
    return np.clip(figure.image, 0.0, 1.0) ** (1 / 2.2)  # gamma 2.2, as the fit's camera model starts


def test_the_thickness_comes_back_within_one_percent_and_two_sigma():
    # Checked as a Bayer sensor's photo: the demosaicing's shift is measured and joins the 1 sigma.
    fit = petroscope.fit_conoscope(camera_photo(40.0), mineral="muscovite", thickness_um=30.0, fixed={"field_radius_px": 48.0}, sensor="bayer")
    assert fit["acceptable"], fit["verdict"]
    thickness, sigma = fit["values"]["thickness_um"], fit["sigma"]["thickness_um"]
    assert abs(thickness - 40.0) < 0.4  # 1%
    assert sigma is not None and abs(thickness - 40.0) <= 2 * sigma
    shift = fit["mosaic_shift"]
    assert set(shift) == {name for name, free in fit["free"].items() if free}
    assert 0.0 < abs(shift["thickness_um"]) <= sigma
    assert fit["free"]["thickness_um"] and not fit["free"]["field_radius_px"]
    assert fit["model"].shape == (96, 96, 3)


def test_light_that_falls_off_is_fitted_with_the_figure():
    # The light fading about a point off the figure's centre, as uneven illumination does, before the camera.
    figure = np.clip(petroscope.conoscope(mineral="muscovite", thickness_um=40.0, size_px=96).image, 0.0, 1.0)
    y, x = np.mgrid[0:96, 0:96] + 0.5
    envelope = np.exp(-(np.hypot(x - 52.0, y - 44.0) / 40.0) ** 2.5)
    photo = (figure * envelope[:, :, None]) ** (1 / 2.2)
    fit = petroscope.fit_conoscope(photo, mineral="muscovite", thickness_um=30.0, fixed={"field_radius_px": 48.0}, illumination="falloff")
    assert fit["acceptable"], fit["verdict"]
    values = fit["values"]
    assert abs(values["thickness_um"] - 40.0) < 0.4  # 1%
    assert fit["free"]["envelope_radius_px"]
    assert abs(values["envelope_center_x_px"] - 52.0) < 2.0 and abs(values["envelope_center_y_px"] - 44.0) < 2.0
    assert abs(values["envelope_radius_px"] - 40.0) < 4.0
    assert fit["mosaic_shift"] is None  # a full-colour sensor, the default: nothing to check


def test_bad_photos_and_arguments_are_refused():
    with pytest.raises(TypeError, match="divide by 255"):
        petroscope.fit_conoscope(np.zeros((64, 64, 3), dtype=np.uint8))
    with pytest.raises(ValueError, match="height, width"):
        petroscope.fit_conoscope(np.zeros((64, 64, 4), dtype=np.float32))
    with pytest.raises(ValueError, match="unknown parameter 'thickness'"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), free=["thickness"])
    with pytest.raises(ValueError, match="starting thickness"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), thickness_um=-3.0)
    with pytest.raises(ValueError, match="unknown projection 'fisheye'"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), projection="fisheye")
    with pytest.raises(ValueError, match="unknown colour sensor 'rgb' \\(expected one of full-colour, bayer\\)"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), sensor="rgb")
    with pytest.raises(ValueError, match="extinction_ratio = 1.5 is outside 0 ... 0.2"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), fixed={"extinction_ratio": 1.5})
    with pytest.raises(ValueError, match="illumination is even"):
        petroscope.fit_conoscope(camera_photo(40.0, 64), free=["thickness_um", "envelope_radius_px"])
    with pytest.raises(petroscope.Cancelled):
        petroscope.fit_conoscope(camera_photo(40.0, 64), progress=lambda fraction: False)


def test_the_solver_prints_only_when_asked(capfd):
    # The switch is per call and process-wide (glog's settings are): off again after a verbose fit.
    photo = camera_photo(40.0, 64)
    settings = dict(mineral="muscovite", thickness_um=38.0, free=["thickness_um"], fixed={"field_radius_px": 32.0}, candidates=1)
    petroscope.fit_conoscope(photo, **settings)
    assert capfd.readouterr().err == ""
    petroscope.fit_conoscope(photo, verbose=True, **settings)
    assert "iter" in capfd.readouterr().err  # Ceres's progress per iteration
    petroscope.fit_conoscope(photo, **settings)
    assert capfd.readouterr().err == ""


def srgb_codes(linear):
    """Linear sRGB as a camera stores it: the sRGB transfer curve (IEC 61966-2-1), codes 0 to 1."""
    x = np.clip(linear, 0.0, 1.0)
    return np.where(x <= 0.0031308, 12.92 * x, 1.055 * x ** (1 / 2.4) - 0.055).astype(np.float32)


def grain_photos(thickness_um, euler_zyz_deg):
    """A one-grain quartz section rendered between crossed polars at stage 0 and 30 and with the gypsum plate.
    The stage turns the section: the photo's corners then show the empty field, so the fits read a region."""
    section = petroscope.Section(np.zeros((24, 24), dtype=np.uint8), [petroscope.Grain(0, "quartz", euler_zyz_deg=euler_zyz_deg)],
                                 thickness_um=thickness_um)
    shots = [dict(stage_deg=0), dict(stage_deg=30), dict(stage_deg=0, plate="gypsum")]
    return [srgb_codes(petroscope.orthoscope(section, **shot).image) for shot in shots]


def test_a_grains_thickness_comes_back_from_its_colours():
    photos = grain_photos(30.0, (20.0, 90.0, 0.0))  # the optic axis in the section's plane: maximum birefringence
    fit = petroscope.fit_orthoscope(photos, mineral="quartz", stage_deg=[0, 30, 0], plate=[None, None, "gypsum"], region=(4, 4, 16, 16))
    assert fit["acceptable"], fit["verdict"]
    thickness, sigma = fit["values"]["thickness_um"], fit["sigma"]["thickness_um"]
    assert abs(thickness - 30.0) < 0.01, fit  # the model is the renderer's own: only rounding separates them
    assert sigma is not None and sigma > 0
    assert [photo["pixels"] for photo in fit["photos"]] == [256, 256, 256]
    np.testing.assert_allclose(fit["photos"][0]["model_code"], fit["photos"][0]["mean_code"], atol=0.02)
    known = petroscope.fit_orthoscope(photos, mineral="quartz", stage_deg=[0, 30, 0], plate=[None, None, "gypsum"],
                                      region=(4, 4, 16, 16), orientation="known", euler_zyz_deg=(20.0, 90.0, 0.0))
    assert abs(known["values"]["thickness_um"] - 30.0) < 0.01, known["verdict"]


def test_a_hole_in_the_section_calibrates_the_camera():
    """A grain around a hole filled with balsam, photographed through a camera whose white balance is off. With
    the hole as the reference region the fit recovers the camera's red-to-blue balance and the thickness."""
    rows, columns = np.mgrid[0:32, 0:32]
    labels = ((rows - 15.5) ** 2 + (columns - 15.5) ** 2 < 36).astype(np.uint8)
    grains = [petroscope.Grain(0, "quartz", euler_zyz_deg=(20.0, 90.0, 0.0)), petroscope.Grain(1, "canada balsam")]
    section = petroscope.Section(labels, grains, thickness_um=30.0)
    white_balance = np.array([1.15, 1.0, 0.85], dtype=np.float32)
    shots = [dict(stage_deg=0), dict(stage_deg=30), dict(stage_deg=25, plate="gypsum")]  # the plate at the grain's 45-degree position
    photos = [srgb_codes(white_balance * petroscope.orthoscope(section, **shot).image) for shot in shots]
    settings = dict(mineral="quartz", stage_deg=[0, 30, 25], plate=[None, None, "gypsum"], region=(24, 13, 6, 6))
    fit = petroscope.fit_orthoscope(photos, reference_region=(13, 13, 6, 6), **settings)
    assert fit["acceptable"], fit["verdict"]
    assert abs(fit["values"]["thickness_um"] - 30.0) < 0.3, fit
    camera = fit["camera_calibration"]
    assert camera["gains_fitted_with_the_grain"] == ["G"]  # the plate's red has no green to calibrate it
    assert abs(camera["channel_gains"][0] / camera["channel_gains"][2] - 1.15 / 0.85) < 0.02 * 1.15 / 0.85, camera
    assert camera["reference_rms_code"] < 2.0 / 255.0
    assert fit["photos"][0]["reference"]["pixels"] == 36
    plain = petroscope.fit_orthoscope(photos, **settings)
    assert plain["camera_calibration"] is None and plain["photos"][0]["reference"] is None
    assert plain["rms_code"] > 2.0 * fit["rms_code"], (plain["rms_code"], fit["rms_code"])
    with pytest.raises(ValueError, match="dark in every photo"):
        petroscope.fit_orthoscope(photos, reference_region=[(13, 13, 6, 6), (13, 13, 6, 6), None], **settings)
    with pytest.raises(ValueError, match="reference_mask and reference_region: give one or the other"):
        petroscope.fit_orthoscope(photos, reference_region=(13, 13, 6, 6), reference_mask=np.ones((32, 32)), **settings)


def test_bad_grain_fits_are_refused():
    photos = grain_photos(30.0, (0.0, 90.0, 0.0))
    with pytest.raises(ValueError, match="stage_deg: give one value for all 3 photos or a list of one per photo \\(got 2\\)"):
        petroscope.fit_orthoscope(photos, mineral="quartz", stage_deg=[0, 30])
    with pytest.raises(TypeError, match="stage_deg: expected an angle in degrees .*, got str"):
        petroscope.fit_orthoscope(photos, mineral="quartz", stage_deg=[0, "thirty", 0])
    with pytest.raises(TypeError, match="plate: expected 'gypsum', 'mica', 'wedge' or None .*, got int"):
        petroscope.fit_orthoscope(photos, mineral="quartz", plate=3)
    with pytest.raises(ValueError, match="orientation 'known' needs the grain's Euler angles"):
        petroscope.fit_orthoscope(photos, mineral="quartz", orientation="known")
    with pytest.raises(ValueError, match="mask: expected an array \\(height, width\\) of the photo's size"):
        petroscope.fit_orthoscope(photos, mineral="quartz", mask=np.ones((5, 5)))
    with pytest.raises(ValueError, match="needs white light"):
        petroscope.fit_orthoscope(photos, mineral="quartz", light=589.0)
    with pytest.raises(ValueError, match="unknown mineral|not in the catalog|quarz"):
        petroscope.fit_orthoscope(photos, mineral="quarz")
    with pytest.raises(TypeError, match="photos\\[0\\]: expected float camera values"):
        petroscope.fit_orthoscope([np.zeros((8, 8, 3), dtype=np.uint8)], mineral="quartz")
    with pytest.raises(petroscope.Cancelled):
        petroscope.fit_orthoscope(photos, mineral="quartz", progress=lambda fraction: False)
