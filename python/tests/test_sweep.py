"""petroscope.sweep: every frame equals the single call with the frame's values, however the frames are
split (jobs, shards merged); bad sweeps fail naming the argument; a sweep cancels."""
import pickle

import numpy as np
import pytest

import petroscope

GRID = {"tilt_deg": [0, 15], "azimuth_deg": np.array([0.0, 45.0, 90.0])}
FIXED = dict(mineral="aragonite", thickness_um=40, size_px=64, light=589.3)


@pytest.fixture(scope="module")
def whole():
    return petroscope.sweep(petroscope.conoscope, GRID, jobs=2, **FIXED)


def test_each_frame_is_the_single_call_with_its_values(whole):
    assert whole.shape == (2, 3) and whole.frame_count == 6 and len(whole) == 6
    assert whole.grid().shape == (2, 3, 64, 64, 3) and whole.images.dtype == np.float32
    for frame, result in zip(whole.frames, whole.results):
        values = whole.values(frame)
        assert values == {"tilt_deg": GRID["tilt_deg"][frame // 3], "azimuth_deg": GRID["azimuth_deg"][frame % 3]}
        np.testing.assert_array_equal(result.image, petroscope.conoscope(**FIXED, **values).image)
    # The tilt moves the figure: the frames are not all the same picture.
    assert not np.array_equal(whole.results[0].image, whole.results[3].image)


def test_one_job_shards_and_merging_give_the_same_frames(whole):
    serial = petroscope.sweep("conoscope", GRID, jobs=1, **FIXED)
    np.testing.assert_array_equal(serial.images, whole.images)
    parts = [petroscope.sweep(petroscope.conoscope, GRID, frames=shard, **FIXED) for shard in petroscope.shards(6, 4)]
    assert [part.frames for part in parts] == [[0], [1, 2], [3], [4, 5]]
    merged = petroscope.Sweep.merge(reversed(parts))
    assert merged.frames == list(range(6))
    np.testing.assert_array_equal(merged.grid(), whole.grid())
    with pytest.raises(ValueError, match="holds 2 of the grid's 6 frames"):
        parts[1].grid()
    with pytest.raises(ValueError, match="more than one part"):
        petroscope.Sweep.merge([parts[0], parts[0]])


def test_measurements_and_results_travel(whole):
    luminance = whole.measurement("mean_luminance")
    assert luminance.shape == (6,) and np.all(np.isfinite(luminance))
    np.testing.assert_array_equal(luminance, [r.measurements["mean_luminance"] for r in whole.results])
    copy = pickle.loads(pickle.dumps(whole.results[4]))
    np.testing.assert_array_equal(copy.image, whole.results[4].image)
    assert copy.measurements == whole.results[4].measurements and copy.channels == ["R", "G", "B"]
    with pytest.raises(ValueError, match="these are: mean_r"):
        whole.measurement("retardation")


def test_orthoscope_and_conical_sweep(repository):
    labels = np.zeros((32, 48), dtype=np.uint8)
    labels[:, 24:] = 1
    section = petroscope.Section(labels, [petroscope.Grain(0, "quartz", euler_zyz_deg=(0, 90, 0)), petroscope.Grain(1, "calcite")])
    stages = petroscope.sweep(petroscope.orthoscope, {"stage_deg": [0, 30, 45]}, section=section, light=550)
    for frame, result in enumerate(stages.results):
        np.testing.assert_array_equal(result.image, petroscope.orthoscope(section, stage_deg=[0, 30, 45][frame], light=550).image)
    rings = petroscope.sweep(petroscope.conical, {"z": [0.0, 1.0]}, size_px=64)
    np.testing.assert_array_equal(rings.results[1].image, petroscope.conical(z=1.0, size_px=64).image)
    assert "length_um" in petroscope.sweep_fields(petroscope.conical)


def test_bad_sweeps_name_what_is_wrong():
    with pytest.raises(ValueError, match="'thickness' is not a numeric field of conoscope; these can be swept: thickness_um"):
        petroscope.sweep(petroscope.conoscope, {"thickness": [10]}, **FIXED)
    with pytest.raises(ValueError, match=r"frame 1 \(thickness_um -5\): thickness"):
        petroscope.sweep(petroscope.conoscope, {"thickness_um": [10, -5]}, mineral="calcite", size_px=64)
    with pytest.raises(ValueError, match="'tilt_deg' has no values|non-empty"):
        petroscope.sweep(petroscope.conoscope, {"tilt_deg": []})
    with pytest.raises(TypeError, match="vary: expected a dict"):
        petroscope.sweep(petroscope.conoscope, [("tilt_deg", [1])])
    with pytest.raises(TypeError, match=r"vary\['tilt_deg'\]: expected a sequence of numbers"):
        petroscope.sweep(petroscope.conoscope, {"tilt_deg": ["ten"]})
    with pytest.raises(ValueError, match="frames: expected frame numbers 0 to 1, got 2"):
        petroscope.sweep(petroscope.conoscope, {"tilt_deg": [0, 10]}, frames=[2], **FIXED)
    with pytest.raises(TypeError, match="compute: expected petroscope.conoscope"):
        petroscope.sweep(print, {"tilt_deg": [0]})
    with pytest.raises(ValueError, match="plate_slow_deg is swept, but there is no plate"):
        petroscope.sweep(petroscope.conoscope, {"plate_slow_deg": [0, 45]}, **FIXED)
    with pytest.raises(ValueError, match="jobs: expected 0"):
        petroscope.sweep(petroscope.conoscope, {"tilt_deg": [0]}, jobs=-1, **FIXED)
    with pytest.raises(TypeError):  # an argument conoscope does not take
        petroscope.sweep(petroscope.conoscope, {"tilt_deg": [0]}, colour="red")


def test_a_sweep_reports_and_cancels():
    fractions = []
    petroscope.sweep(petroscope.conoscope, {"tilt_deg": [0, 5, 10]}, progress=fractions.append, **FIXED)
    assert fractions and fractions[-1] == 1.0
    with pytest.raises(petroscope.Cancelled):
        petroscope.sweep(petroscope.conoscope, {"tilt_deg": [0, 5, 10]}, progress=lambda fraction: False, **FIXED)
