"""render_scene: the paper's scene, made small, gives the command line's image; its Stokes vectors are
physical; bad settings and files are refused naming the value."""
import json

import numpy as np
import pytest

import petroscope


@pytest.fixture
def small_scene(repository, tmp_path):
    scene = json.loads((repository / "scenes" / "calcite-box.json").read_text())
    scene["camera"]["width_px"], scene["camera"]["height_px"] = 48, 44
    path = tmp_path / "scene.json"
    path.write_text(json.dumps(scene))
    return path


def test_the_scene_equals_the_command_line(small_scene, run_cli):
    render = petroscope.render_scene(small_scene, samples_per_pixel=2, polarizer_deg=30)
    image, sidecar = run_cli(["render", "--scene", str(small_scene), "--spp", "2", "--polarizer-deg", "30"])
    assert render.image.shape == (44, 48, 3) and render.image.dtype == np.float32
    assert np.max(np.abs(render.image - image)) <= 1e-6
    statistics = render.details["statistics"]
    assert statistics["paths"] == sidecar["statistics"]["paths"] == 48 * 44 * 2
    assert statistics["crystal_interactions"] == sidecar["statistics"]["crystal_interactions"] > 0
    assert render.measurements["noise_median"] == pytest.approx(sidecar["estimated_noise"]["median"], rel=1e-12)


def test_the_stokes_vectors_are_physical(small_scene):
    render = petroscope.render_scene(small_scene, samples_per_pixel=2, no_polarizer=True)
    stokes_y = render.details["stokes_xyz"][:, :, [1, 4, 7, 10]].astype(np.float64)  # Y of S0, S1, S2, S3
    assert render.details["standard_error_y"].shape == (44, 48, 4)
    polarized = np.sqrt(np.sum(stokes_y[:, :, 1:] ** 2, axis=2))
    assert np.all(polarized <= stokes_y[:, :, 0] * (1 + 1e-5) + 1e-7)
    assert np.all(stokes_y[:, :, 0] >= 0)


def test_bad_renders_are_refused(small_scene, tmp_path):
    with pytest.raises(ValueError, match="samples per pixel: 0 is out of range"):
        petroscope.render_scene(small_scene, samples_per_pixel=0)
    with pytest.raises(ValueError, match="exclude each other"):
        petroscope.render_scene(small_scene, polarizer_deg=10, no_polarizer=True)
    with pytest.raises(ValueError, match="no-such-scene.json"):
        petroscope.render_scene(tmp_path / "no-such-scene.json")
    with pytest.raises(petroscope.Cancelled):
        petroscope.render_scene(small_scene, samples_per_pixel=2, progress=lambda fraction: False)
