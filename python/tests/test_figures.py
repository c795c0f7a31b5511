"""The Python functions give what the command line gives for the same parameters (its float EXR output
against the array, to 1e-6), with the same measurements, and what the physics says."""
import math

import numpy as np
import pytest

import petroscope


def assert_same_image(array, cli_image):
    assert array.dtype == np.float32
    assert array.shape == cli_image.shape
    assert np.max(np.abs(array - cli_image)) <= 1e-6


def assert_same_measurements(measurements, sidecar):
    # The ray tracer merges its threads' float32 screens in no fixed order: their sums agree to float32
    # rounding (1e-6 relative), as the images do.
    assert set(measurements) == set(sidecar["measurements"])
    for name, value in sidecar["measurements"].items():
        if value is None:
            assert measurements[name] is None, name
        else:
            assert measurements[name] == pytest.approx(value, rel=1e-6, abs=1e-15), name


def test_conoscope_equals_the_command_line_in_white_and_monochromatic_light(run_cli):
    white = petroscope.conoscope(mineral="aragonite", thickness_um=40, stage_deg=20, size_px=96, plate="gypsum",
                                 light=petroscope.Light(wavelengths_nm=(400, 700, 10), illuminant="A"))
    image, sidecar = run_cli(["conoscope", "--mineral", "aragonite", "--thickness", "40um", "--stage-deg", "20", "--size", "96",
                              "--plate", "gypsum", "--wavelengths", "400:700:10", "--illuminant", "A"])
    assert_same_image(white.image, image)
    assert_same_measurements(white.measurements, sidecar)
    assert white.channels == ["R", "G", "B"]
    assert white.details["illuminant"] == sidecar["light"]["illuminant"]

    exact = petroscope.conoscope(mineral="aragonite", thickness_um=40, stage_deg=20, size_px=96, plate="gypsum",
                                 light=petroscope.Light(wavelengths_nm=(400, 700, 10), illuminant="A"), exact_spectrum=True)
    image, sidecar = run_cli(["conoscope", "--mineral", "aragonite", "--thickness", "40um", "--stage-deg", "20", "--size", "96",
                              "--plate", "gypsum", "--wavelengths", "400:700:10", "--illuminant", "A", "--exact-spectrum"])
    assert_same_image(exact.image, image)
    # Every wavelength solved against 8 interpolated (the library's tests measure at most dE00 = 6e-3).
    assert np.max(np.abs(exact.image - white.image)) < 1e-4


    mono = petroscope.conoscope(mineral="calcite", thickness_um=100, tilt_deg=10, azimuth_deg=30, size_px=64, light=589.3)
    image, sidecar = run_cli(["conoscope", "--mineral", "calcite", "--thickness", "100um", "--tilt-deg", "10", "--azimuth-deg", "30",
                              "--size", "64", "--wavelength", "589.3nm"])
    assert_same_image(mono.image, image)
    assert_same_measurements(mono.measurements, sidecar)
    assert mono.details["cut"] == "optic-axis" == sidecar["orientation"]["cut"]


def test_conoscope_handedness_matches_the_cli_and_mirrors_quartz(run_cli):
    left = petroscope.conoscope(mineral="quartz", thickness_um=1000, size_px=64, light=589.3, handedness="left")
    image, _ = run_cli(["conoscope", "--mineral", "quartz", "--thickness", "1mm", "--size", "64", "--wavelength", "589.3nm",
                        "--handedness", "left"])
    assert_same_image(left.image, image)
    # Crossed polars: the two forms give the same figure, mirrored in the polarizer's (E-W) direction.
    right = petroscope.conoscope(mineral="quartz", thickness_um=1000, size_px=64, light=589.3)
    assert np.max(np.abs(right.image - left.image[::-1, :, :])) < 1e-6
    assert right.image[32, 32, 0] > 0.1  # the centre is lit: sin^2(21.7 deg) = 0.137
    with pytest.raises(ValueError, match="expected right or left"):
        petroscope.conoscope(mineral="quartz", size_px=64, handedness="up")


def test_orthoscope_of_a_section_file_equals_the_command_line(run_cli, repository):
    section = petroscope.read_section(repository / "thin_sections" / "granite")
    result = petroscope.orthoscope(section, stage_deg=30, plate="gypsum", light=petroscope.Light(wavelengths_nm=(400, 700, 10)))
    image, sidecar = run_cli(["orthoscope", "--section", "thin_sections/granite", "--stage-deg", "30", "--plate", "gypsum",
                              "--wavelengths", "400:700:10"])
    assert_same_image(result.image, image)
    assert_same_measurements(result.measurements, sidecar)


@pytest.mark.parametrize("optics", ["wave", "ray"])
def test_conical_equals_the_command_line(run_cli, optics):
    arguments = dict(crystal="KGW", length_um=20000, wavelength_nm=633, optics=optics, size_px=128, rays=20000, filter_um=50000)
    result = petroscope.conical(**arguments)
    image, sidecar = run_cli(["conical", "--crystal", "KGW", "--length", "20mm", "--wavelength", "633nm", "--mode", optics,
                              "--size", "128", "--rays", "20000", "--filter", "50mm"])
    assert_same_image(result.image, image)
    assert_same_measurements(result.measurements, sidecar)
    assert result.details["ring_radius_um"] == pytest.approx(sidecar["R0_um"], rel=1e-12)


def test_a_section_from_arrays_shows_extinction_and_the_plate():
    # Two quartz grains with the optic axis in the section's plane, at 0° and 45° to the polarizer: the
    # first is at extinction between crossed polars, the second bright (sin² 2θ = 1).
    labels = np.zeros((16, 32), dtype=np.uint16)
    labels[:, 16:] = 1
    grains = [petroscope.Grain(0, "quartz", euler_zyz_deg=(0, 90, 0)), petroscope.Grain(1, "quartz", euler_zyz_deg=(45, 90, 0))]
    section = petroscope.Section(labels, grains, thickness_um=30)
    image = petroscope.orthoscope(section, light=550.0).image
    assert image.shape == (16, 32, 3)
    # Γ = 30 µm × (nε − nω) at 550 nm: a uniaxial plate at 45° between crossed polars transmits
    # sin²(πΓ/λ), times the Fresnel losses of the stack (a few per cent).
    quartz = petroscope.mineral("quartz").principal_n(550.0)
    expected = math.sin(math.pi * 30000.0 * (quartz[2] - quartz[0]) / 550.0) ** 2
    assert image[:, 16:].mean() == pytest.approx(expected, rel=0.1)
    # Quartz is optically active: across its axis its waves are ellipses with tan 2χ = 2γ/(1/n_o² − 1/n_e²),
    # γ = g₁₁/n³ (docs/theory.md §9), so at extinction it keeps sin²2χ of that light.
    g11 = petroscope.Medium.of_mineral("quartz", 550.0).gyration[0, 0]
    n = (quartz[0] + quartz[2]) / 2
    tan_2chi = 2 * g11 / n ** 3 / (1 / quartz[0] ** 2 - 1 / quartz[2] ** 2)
    leak = tan_2chi ** 2 / (1 + tan_2chi ** 2) * expected
    assert 0.8 * leak < image[:, :16].max() < leak + 1e-6
    np.testing.assert_array_equal(section.labels, labels)


def test_the_optic_axis_is_imaged_where_the_indicatrix_puts_it():
    axes = petroscope.indicatrix_axes("calcite", tilt_deg=12, azimuth_deg=40)
    optic_axis = axes[:, 2]
    assert optic_axis[2] == pytest.approx(math.cos(math.radians(12)))
    result = petroscope.conoscope(mineral="calcite", thickness_um=200, tilt_deg=12, azimuth_deg=40, size_px=128, light=589.3)
    n_o = petroscope.mineral("calcite").principal_n(589.3)[0]
    # The ordinary wave along the optic axis keeps its tangential wavevector n_o (b_x, b_y) into air:
    # imaged at n_o (b_x, b_y) / NA.
    predicted = n_o * optic_axis[:2] / 0.85
    assert result.measurements["optic_axis_1_x"] == pytest.approx(predicted[0], abs=1e-9)
    assert result.measurements["optic_axis_1_y"] == pytest.approx(predicted[1], abs=1e-9)
    assert math.hypot(result.measurements["melatope_1_x"] - predicted[0], result.measurements["melatope_1_y"] - predicted[1]) < 2 / 64


def test_the_michel_levy_chart_equals_the_command_line(run_cli, tmp_path):
    light = petroscope.Light(wavelengths_nm=(400, 700, 10))
    chart = petroscope.michel_levy_chart(max_retardation_nm=1000, step_nm=5, light=light)
    image, sidecar = run_cli(["chart", "--max-retardation", "1000", "--step", "5", "--wavelengths", "400:700:10",
                              "--csv", str(tmp_path / "chart.csv")])
    assert_same_image(chart, image)
    colours = petroscope.michel_levy_colours(max_retardation_nm=1000, step_nm=5, light=light)
    rows = np.loadtxt(tmp_path / "chart.csv", delimiter=",", skiprows=1)
    np.testing.assert_allclose(colours["retardation_nm"], rows[:, 0], atol=5e-4)  # the CSV prints 3 decimals
    np.testing.assert_allclose(colours["xyz"], rows[:, 2:5], atol=5e-9)           # and 8
    assert colours["birefringence"] == pytest.approx(sidecar["plate"]["birefringence"], rel=1e-12)
    # Γ = 0 is black; Y = 1 would be the light itself.
    assert colours["xyz"][0, 1] < 1e-6


def test_a_grains_form_is_checked():
    assert petroscope.Grain(0, "quartz", euler_zyz_deg=(0, 90, 0), handedness="left").handedness == "left"
    assert petroscope.Grain(0, "quartz", euler_zyz_deg=(0, 90, 0)).handedness is None  # right when rendered
    with pytest.raises(ValueError, match="calcite is not optically active"):
        petroscope.Grain(0, "calcite", handedness="left")
    with pytest.raises(ValueError, match="expected right or left"):
        petroscope.Grain(0, "quartz", handedness="sideways")
