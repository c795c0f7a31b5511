"""Bad input raises ValueError or TypeError naming the argument and what was expected: never a crash
and never a silent conversion."""
import numpy as np
import pytest

import petroscope


@pytest.mark.parametrize(
    "arguments, error, words",
    [
        (dict(thickness_um=-5), ValueError, "thickness"),
        (dict(thickness_um=float("nan")), ValueError, "thickness"),
        (dict(thickness_um="thick"), TypeError, "thickness_um"),
        (dict(mineral="unobtainium"), ValueError, "unobtainium"),
        (dict(size_px=32), ValueError, "64 to 4096"),
        (dict(numerical_aperture=1.2), ValueError, "numerical aperture"),
        (dict(cut="sideways"), ValueError, "sideways"),
        (dict(mineral="calcite", cut="acute-bisectrix"), ValueError, "acute-bisectrix"),
        (dict(cut="optic-axis", euler_zyz_deg=(1, 2, 3)), ValueError, "euler_zyz_deg"),
        (dict(euler_zyz_deg=(1, 2)), TypeError, "euler_zyz_deg"),
        (dict(mounting="glued"), ValueError, "immersed, thin-section or thin-section-exact"),
        (dict(plate="lambda"), ValueError, "gypsum"),
        (dict(plate="wedge", wedge_position=1.5), ValueError, "0 to 1"),
        (dict(light=True), TypeError, "light"),
        (dict(light="white"), TypeError, "light"),
        (dict(light=-589.0), ValueError, "wavelength"),
    ],
)
def test_conoscope_refuses(arguments, error, words):
    with pytest.raises(error, match=words):
        petroscope.conoscope(**{"size_px": 64, **arguments})


@pytest.mark.parametrize(
    "arguments, error, words",
    [
        (dict(wavelengths_nm=(700, 400, 5)), ValueError, "START <= END"),
        (dict(wavelengths_nm=(400, 700, 0)), ValueError, "STEP"),
        (dict(exposure=0), ValueError, "exposure"),
        (dict(illuminant="moonlight"), ValueError, "moonlight"),
    ],
)
def test_light_refuses(arguments, error, words):
    with pytest.raises(error, match=words):
        petroscope.conoscope(size_px=64, light=petroscope.Light(**arguments))


def test_sections_refuse_wrong_arrays_and_grains():
    grains = [petroscope.Grain(1, "quartz")]
    with pytest.raises(TypeError, match="labels: expected an array of integers"):
        petroscope.Section(np.ones((4, 4), dtype=np.float32), grains)
    with pytest.raises(ValueError, match="2-D"):
        petroscope.Section(np.ones((4, 4, 3), dtype=np.uint16), grains)
    with pytest.raises(ValueError, match="65535"):
        petroscope.Section(np.full((4, 4), 70000, dtype=np.int32), grains)
    with pytest.raises(ValueError, match="label"):
        petroscope.Section(np.full((4, 4), 2, dtype=np.uint16), grains)  # no grain for label 2
    with pytest.raises(ValueError, match="unobtainium"):
        petroscope.Section(np.ones((4, 4), dtype=np.uint16), [petroscope.Grain(1, "unobtainium")])
    with pytest.raises(ValueError, match="euler_zyz_deg"):
        petroscope.Grain(1, "quartz", euler_zyz_deg=(0, float("inf"), 0))
    section = petroscope.Section(np.ones((4, 4), dtype=np.int64), grains)
    with pytest.raises(ValueError, match="thickness"):
        petroscope.orthoscope(section, thickness_um=-1)
    with pytest.raises(TypeError):
        petroscope.orthoscope("thin_sections/granite")


def test_conical_and_files_refuse():
    with pytest.raises(ValueError, match="biaxial"):
        petroscope.conical(crystal="calcite", size_px=64)
    with pytest.raises(ValueError, match="expected wave or ray"):
        petroscope.conical(optics="particle", size_px=64)
    with pytest.raises(ValueError, match="linear:ANGLE"):
        petroscope.conical(polarization="sideways", size_px=64)
    with pytest.raises(ValueError, match="rays"):
        petroscope.conical(optics="ray", rays=0, size_px=64)
    with pytest.raises(ValueError, match="no-such-folder"):
        petroscope.read_section("no-such-folder")
    with pytest.raises(ValueError, match="missing.exr"):
        petroscope.read_image("missing.exr")
    with pytest.raises(TypeError):
        petroscope.read_image(42)


def test_bad_bytes_in_a_section_file_are_quoted_safely(tmp_path):
    description = tmp_path / "section.json"
    description.write_bytes(b'{"name": "\x1b[31mred\x07", "labels": 5}')
    with pytest.raises(ValueError) as raised:
        petroscope.read_section(description)
    message = str(raised.value)
    assert "\x1b" not in message and "\x07" not in message
