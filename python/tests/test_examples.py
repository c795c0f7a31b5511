"""The examples in docs/examples run as a user runs them (small images, to a scratch folder): each exits
cleanly, checks its own physics (the scripts assert what they show) and writes its picture."""
import os
import subprocess
import sys

import pytest

pytest.importorskip("matplotlib", reason="the examples draw with matplotlib (python3-matplotlib)")

EXAMPLES = ["conoscope_optic_axes", "retardation_vs_thickness", "fit_photo_residual", "sweep_tilt_azimuth"]


@pytest.mark.parametrize("name", EXAMPLES)
def test_the_example_runs_and_draws(name, repository, tmp_path):
    import matplotlib.image

    script = repository / "docs" / "examples" / (name + ".py")
    run = subprocess.run([sys.executable, str(script), "--output", str(tmp_path), "--size", "96"], capture_output=True, text=True,
                         env=os.environ, timeout=300)
    assert run.returncode == 0, run.stderr
    picture = matplotlib.image.imread(tmp_path / (name + ".png"))
    assert picture.ndim == 3 and picture.shape[0] > 200 and picture.shape[1] > 200
    assert picture[..., :3].std() > 0.05  # a drawing, not a blank page
    assert sorted(path.name for path in tmp_path.iterdir()) == [name + ".png"]  # no partial file left
