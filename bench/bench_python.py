#!/usr/bin/env python3
"""The cost of the Python package over the C++ library layer: the default 512² white-light conoscopic
figure (muscovite, 30 µm, D65), the call bench_conoscope's LibraryLayerDefaultFigure/512 times in C++.

    PYTHONPATH=build/python python3 bench/bench_python.py [REPETITIONS]

Prints the minimum and median wall time per call; compare with
`build/bench/bench_conoscope --benchmark_filter=LibraryLayer` on the same machine."""
import statistics
import sys
import time

import petroscope


def main():
    repetitions = int(sys.argv[1]) if len(sys.argv) > 1 else 10
    petroscope.conoscope(size_px=64)  # loads the catalog and the colour tables once, as the C++ benchmark's set-up does
    times_ms = []
    for _ in range(repetitions):
        started = time.perf_counter()
        petroscope.conoscope(size_px=512)
        times_ms.append(1000.0 * (time.perf_counter() - started))
    print(f"petroscope.conoscope(size_px=512): min {min(times_ms):.1f} ms, median {statistics.median(times_ms):.1f} ms over {repetitions} calls")


if __name__ == "__main__":
    main()
