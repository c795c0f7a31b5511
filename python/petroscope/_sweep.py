"""petroscope.sweep and its result, Sweep. Imported on the first sweep: it needs numpy, which
`import petroscope` does not load."""
import numpy as np

from . import _petroscope

_REQUESTS = {
    "conoscope": _petroscope._conoscope_request,
    "orthoscope": _petroscope._orthoscope_request,
    "conical": _petroscope._conical_request,
}


def _kind(compute):
    if isinstance(compute, str) and compute in _REQUESTS:
        return compute
    for name in _REQUESTS:
        if compute is getattr(_petroscope, name):
            return name
    raise TypeError(
        "compute: expected petroscope.conoscope, petroscope.orthoscope or petroscope.conical (or its name), got "
        + repr(compute)[:80]
    )


def _axes(vary):
    if not isinstance(vary, dict) or not vary:
        raise TypeError("vary: expected a dict {field: values}, e.g. {'tilt_deg': [0, 10, 20]}, got " + repr(vary)[:80])
    axes = []
    for field, values in vary.items():
        if not isinstance(field, str):
            raise TypeError("vary: the keys are field names (str), got " + repr(field)[:80])
        try:
            array = np.asarray(values, dtype=np.float64)
        except (TypeError, ValueError):
            raise TypeError("vary[" + repr(field)[:80] + "]: expected a sequence of numbers, got " + repr(values)[:80]) from None
        if array.ndim != 1 or array.size == 0:
            raise ValueError("vary[" + repr(field)[:80] + "]: expected a non-empty 1-D sequence of numbers, got shape " + str(array.shape))
        axes.append((field, array.tolist()))
    return axes


def shards(frame_count, count):
    """The frames 0 … frame_count−1 in `count` contiguous parts, as the command line's --shard K/N splits
    them: part K holds frames ⌊(K−1)F/N⌋ to ⌊KF/N⌋−1."""
    if not isinstance(frame_count, int) or frame_count < 0:
        raise ValueError("frame_count: expected a whole number >= 0, got " + repr(frame_count)[:80])
    if not isinstance(count, int) or count < 1:
        raise ValueError("count: expected a whole number >= 1, got " + repr(count)[:80])
    return [list(range(frame_count * k // count, frame_count * (k + 1) // count)) for k in range(count)]


class Sweep:
    """The frames of a sweep, in the order asked for.

    kind: 'conoscope', 'orthoscope' or 'conical'. axes: {field: values} in the order given (the last runs
    fastest). frames: the frame numbers in the grid. results: a Result per frame.
    """

    def __init__(self, kind, axes, frames, results):
        self.kind = kind
        self.axes = {field: np.asarray(values, dtype=np.float64) for field, values in axes}
        self.frames = list(frames)
        self.results = list(results)

    @property
    def shape(self):
        """The grid's shape: the number of values of each axis."""
        return tuple(len(values) for values in self.axes.values())

    @property
    def frame_count(self):
        """The number of frames of the whole grid (not only of those here)."""
        return int(np.prod(self.shape))

    def values(self, frame):
        """{field: value} of a frame number of the grid."""
        if not 0 <= frame < self.frame_count:
            raise ValueError("frame: expected 0 to " + str(self.frame_count - 1) + ", got " + repr(frame)[:80])
        index = np.unravel_index(frame, self.shape)
        return {field: float(values[i]) for (field, values), i in zip(self.axes.items(), index)}

    @property
    def images(self):
        """float32 array (frames, height, width, channels): every frame's image, in the order of `frames`."""
        return np.stack([result.image for result in self.results])

    def grid(self):
        """float32 array shape + (height, width, channels): the images on the grid. Needs every frame."""
        if self.frames != list(range(self.frame_count)):
            raise ValueError("grid(): this sweep holds " + str(len(self.frames)) + " of the grid's " + str(self.frame_count) + " frames (merge the parts first)")
        images = self.images
        return images.reshape(self.shape + images.shape[1:])

    def measurement(self, name):
        """float64 array: the measurement `name` of every frame (NaN where there was nothing to measure)."""
        if self.results and name not in self.results[0].measurements:
            raise ValueError("measurement: " + repr(name)[:80] + " is not measured; these are: " + ", ".join(self.results[0].measurements))
        values = [result.measurements.get(name) for result in self.results]
        return np.array([np.nan if value is None else value for value in values], dtype=np.float64)

    @staticmethod
    def merge(parts):
        """One Sweep of the parts of a sweep (shards rendered apart), its frames in order."""
        parts = list(parts)
        if not parts:
            raise ValueError("merge: no parts")
        first = parts[0]
        for part in parts[1:]:
            if part.kind != first.kind or list(part.axes) != list(first.axes) or any(
                not np.array_equal(part.axes[f], first.axes[f]) for f in first.axes
            ):
                raise ValueError("merge: the parts are of different sweeps")
        pairs = sorted(
            [(frame, result) for part in parts for frame, result in zip(part.frames, part.results)], key=lambda pair: pair[0]
        )
        frames = [frame for frame, _ in pairs]
        if len(set(frames)) != len(frames):
            raise ValueError("merge: a frame is in more than one part")
        return Sweep(first.kind, first.axes.items(), frames, [result for _, result in pairs])

    def __len__(self):
        return len(self.frames)

    def __repr__(self):
        axes = ", ".join(field + " × " + str(len(values)) for field, values in self.axes.items())
        return "<petroscope.Sweep " + self.kind + ": " + axes + "; " + str(len(self.frames)) + " frames>"


def run(compute, vary, frames, jobs, progress, arguments):
    kind = _kind(compute)
    request = _REQUESTS[kind](**arguments)
    axes = _axes(vary)
    if frames is not None:
        frames = list(frames)
    results = _petroscope._sweep(request, axes, frames, jobs, progress)
    if frames is None:
        frames = range(len(results))
    return Sweep(kind, axes, frames, results)
