"""Several Python threads compute at once and get what serial calls get; a progress callback reports and
cancels; Ctrl-C interrupts a long computation."""
import concurrent.futures
import os
import signal
import threading

import numpy as np
import pytest

import petroscope

CASES = [
    dict(mineral="muscovite", thickness_um=30, size_px=96, light=petroscope.Light(wavelengths_nm=(400, 700, 20))),
    dict(mineral="calcite", thickness_um=50, size_px=96, light=589.3),
    dict(mineral="aragonite", thickness_um=60, stage_deg=30, size_px=96, light=632.8),
    dict(mineral="topaz", thickness_um=300, size_px=96, plate="mica", light=petroscope.Light(wavelengths_nm=(400, 700, 20))),
]


def test_threads_give_the_serial_results():
    serial = [petroscope.conoscope(**case).image for case in CASES]
    with concurrent.futures.ThreadPoolExecutor(max_workers=4) as pool:
        parallel = list(pool.map(lambda case: petroscope.conoscope(**case).image, CASES * 2))
    for k, image in enumerate(parallel):
        np.testing.assert_array_equal(image, serial[k % len(CASES)])


def test_the_gil_is_released_while_computing():
    # A Python thread keeps counting while the main thread renders: it could not without the GIL.
    counted = 0
    done = threading.Event()

    def count():
        nonlocal counted
        while not done.is_set():
            counted += 1

    counter = threading.Thread(target=count)
    counter.start()
    before = counted
    petroscope.conoscope(size_px=256, light=petroscope.Light(wavelengths_nm=(400, 700, 10)))
    during = counted - before
    done.set()
    counter.join()
    assert during > 1000


def test_progress_reports_up_to_one_and_false_cancels():
    fractions = []
    petroscope.conoscope(size_px=64, light=589.3, progress=lambda fraction: fractions.append(fraction))
    assert fractions and fractions[-1] == 1.0
    assert all(0.0 < f <= 1.0 for f in fractions)
    with pytest.raises(petroscope.Cancelled):
        petroscope.conoscope(size_px=64, light=589.3, progress=lambda fraction: False)
    with pytest.raises(petroscope.Cancelled):  # wave optics: between the radii of the profile
        petroscope.conical(size_px=64, progress=lambda fraction: False)
    with pytest.raises(ZeroDivisionError):  # the callback's own error comes back
        petroscope.conical(optics="ray", size_px=64, progress=lambda fraction: 1 / 0)


def test_ctrl_c_interrupts_a_long_call():
    if threading.current_thread() is not threading.main_thread():
        pytest.skip("signals reach the main thread only")
    sent = []

    def interrupt_once(fraction):
        if not sent:
            sent.append(fraction)
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt):
        petroscope.conoscope(size_px=512, light=petroscope.Light(wavelengths_nm=(380, 780, 5)), progress=interrupt_once)
    assert sent and sent[0] < 1.0
