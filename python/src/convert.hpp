#pragma once
// What every binding of the Python package shares: images as numpy arrays, results as one Python type,
// the catalog, and progress callbacks that let Ctrl-C and the user's callback cancel a long call.
#include "petroscope/api/crystal_orientation.hpp"
#include "petroscope/api/light.hpp"
#include "petroscope/api/plate.hpp"
#include "petroscope/api/measurements.hpp"
#include "petroscope/core/image.hpp"
#include "petroscope/core/progress.hpp"
#include "petroscope/minerals/mineral_catalog.hpp"

#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>

#include <array>
#include <memory>
#include <tuple>
#include <utility>
#include <optional>
#include <string>
#include <vector>

namespace petroscope::python {

namespace py = pybind11;

/// The catalog of the repository's minerals (or of $PETROSCOPE_MINERALS), loaded at the first use.
const MineralCatalog& catalog();

/// Camera values 0 … 1 from a float array (height, width, 3) or (height, width) as an Image; TypeError or
/// ValueError naming `argument` otherwise.
Image image_argument(const py::array& array, const std::string& argument);

/// A float32 array H × W × C, a copy of `image`.
py::array_t<float> to_numpy(const Image& image);

/// A rendered image as Python sees it: the array, what its channels and values mean, the numbers
/// measured on it, notes for the user, and quantities particular to the computation.
struct Result {
    py::array_t<float> image;
    std::vector<std::string> channels;
    std::string pixel_values;
    py::dict measurements;
    std::vector<std::string> notes;
    py::dict details;
};
py::dict measurements_dict(const Measurements& measurements);

/// The light argument: a Light, a number (monochromatic light at that wavelength in nm) or None (white
/// light, D65); TypeError for anything else.
Light light_argument(const py::object& light);

/// The orientation arguments every figure takes: a cut name ("optic-axis", "acute-bisectrix",
/// "obtuse-bisectrix", "optic-normal"; None: the mineral's default) tilted and turned, or Euler angles.
CrystalOrientation orientation_argument(const std::optional<std::string>& cut, double azimuth_deg, double tilt_deg,
                                        const std::optional<std::array<double, 3>>& euler_zyz_deg);

/// The plate arguments: a plate name ('gypsum', 'mica', 'wedge') or None, its slow direction, the wedge's position.
std::optional<PlateRequest> plate_argument(const std::optional<std::string>& plate, double slow_deg, double wedge_position);

/// Runs `work` with the GIL released (other Python threads run meanwhile); exceptions pass through.
template <class Work>
auto without_gil(Work&& work) {
    const py::gil_scoped_release released;
    return work();
}

/// A long call's progress: the Python callback (None for none) called with the fraction done, under the
/// GIL; it cancels by returning False. Ctrl-C (a pending signal in the main thread) cancels too, raising
/// KeyboardInterrupt. Create it with the GIL held and keep it until the GIL is held again.
class PythonProgress {
public:
    explicit PythonProgress(py::object callback) : callback_(std::move(callback)) {}
    /// A ProgressCallback that refers to this object (the copies the library makes touch no Python object).
    ProgressCallback callback();

private:
    py::object callback_;
};

/// Runs `work(callback)` with the GIL released, `callback` reporting to the Python `progress` (None for
/// none) as PythonProgress does.
template <class Work>
auto with_progress(const py::object& progress, Work&& work) {
    PythonProgress reporter(progress);
    const ProgressCallback callback = reporter.callback();
    return without_gil([&] { return work(callback); });
}

/// Binds `function` as `name` with the keyword arguments in the tuple `arguments` (py::arg values shared by
/// several bindings), then `extra` (more arguments, a docstring).
template <class Function, class... Arguments, class... Extra>
void def_with_arguments(py::module_& module, const char* name, Function&& function, const std::tuple<Arguments...>& arguments,
                        Extra&&... extra) {
    std::apply([&](const auto&... argument) { module.def(name, std::forward<Function>(function), argument..., std::forward<Extra>(extra)...); },
               arguments);
}

/// A function of the request's arguments and then `progress` that makes the request with `make` and
/// computes it with `compute`: one parameter list for a computation (conoscope) and its request (sweeps).
template <class Request, class... Parameters>
auto make_then_compute(Request (*make)(Parameters...), Result (*compute)(const Request&, const py::object&)) {
    return [make, compute](Parameters... parameters, const py::object& progress) { return compute(make(parameters...), progress); };
}

/// Python's KeyboardInterrupt, ValueError (bad input) and petroscope.Cancelled for the library's errors.
void register_exceptions(py::module_& module);

}  // namespace petroscope::python
