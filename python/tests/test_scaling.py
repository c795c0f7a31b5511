"""A sweep handed to an existing distributed engine: Dask's LocalCluster with 2 worker processes renders
the shards of a small sweep, and the merged frames equal the serial sweep's (docs/scaling.md)."""
import numpy as np
import pytest

import petroscope

# Tornado inside Dask 2022.12 warns of its own deprecated call; not ours to fix.
pytestmark = pytest.mark.filterwarnings("ignore:make_current is deprecated:DeprecationWarning")
distributed = pytest.importorskip("distributed", reason="Dask's python3-distributed is not installed")

VARY = {"thickness_um": [20, 30, 40], "stage_deg": [0, 30]}
FIXED = dict(mineral="muscovite", size_px=64, light=petroscope.Light(wavelengths_nm=(400, 700, 20)))


def render_shard(frames):
    # One frame at a time per task: the cluster's workers are the parallelism.
    return petroscope.sweep(petroscope.conoscope, VARY, frames=frames, jobs=1, **FIXED)


def test_a_local_cluster_renders_the_serial_frames():
    serial = petroscope.sweep(petroscope.conoscope, VARY, **FIXED)
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True, dashboard_address=None,
                                  silence_logs=50) as cluster, distributed.Client(cluster) as client:
        futures = client.map(render_shard, petroscope.shards(serial.frame_count, 3))
        merged = petroscope.Sweep.merge(client.gather(futures))
        workers = client.run(lambda: __import__("os").getpid())
    assert len(set(workers.values())) == 2
    assert merged.frames == serial.frames
    np.testing.assert_array_equal(merged.grid(), serial.grid())
    np.testing.assert_array_equal(merged.measurement("mean_luminance"), serial.measurement("mean_luminance"))
