#include "convert.hpp"

#include "petroscope/core/error.hpp"
#include "petroscope/io/data_files.hpp"

#include <algorithm>
#include <cstring>

namespace petroscope::python {

const MineralCatalog& catalog() {
    static const MineralCatalog minerals = load_mineral_catalog(minerals_directory());
    return minerals;
}

Image image_argument(const py::array& array, const std::string& argument) {
    if (array.dtype().kind() != 'f') {
        throw py::type_error(argument + ": expected float camera values 0 to 1 (for 8-bit codes, divide by 255), got dtype " +
                             std::string(py::str(array.dtype())));
    }
    const bool gray = array.ndim() == 2;
    if (!gray && !(array.ndim() == 3 && (array.shape(2) == 3 || array.shape(2) == 1))) {
        throw py::value_error(argument + ": expected an array (height, width, 3) or (height, width)");
    }
    const auto values = py::array_t<float, py::array::c_style | py::array::forcecast>::ensure(array);
    Image image(static_cast<int>(values.shape(1)), static_cast<int>(values.shape(0)), gray ? 1 : static_cast<int>(values.shape(2)));
    std::copy(values.data(), values.data() + values.size(), image.pixels.begin());
    return image;
}

py::array_t<float> to_numpy(const Image& image) {
    py::array_t<float> array({image.height, image.width, image.channels});
    std::memcpy(array.mutable_data(), image.pixels.data(), image.pixels.size() * sizeof(float));
    return array;
}

py::dict measurements_dict(const Measurements& measurements) {
    py::dict values;
    for (const Measurement& m : measurements) values[py::str(m.name)] = m.value ? py::object(py::float_(*m.value)) : py::object(py::none());
    return values;
}

Light light_argument(const py::object& light) {
    if (light.is_none()) return Light{};
    if (py::isinstance<Light>(light)) return light.cast<Light>();
    if (py::isinstance<py::float_>(light) || py::isinstance<py::int_>(light)) {
        if (py::isinstance<py::bool_>(light)) throw py::type_error("light: expected a Light, a wavelength in nm or None, not a bool");
        Light monochromatic;
        monochromatic.wavelength_nm = light.cast<double>();
        monochromatic.validate();
        return monochromatic;
    }
    throw py::type_error("light: expected a Light, a wavelength in nm or None, not " + std::string(py::str(py::type::of(light).attr("__name__"))));
}

CrystalOrientation orientation_argument(const std::optional<std::string>& cut, double azimuth_deg, double tilt_deg,
                                        const std::optional<std::array<double, 3>>& euler_zyz_deg) {
    CrystalOrientation orientation;
    if (euler_zyz_deg) {
        if (cut || azimuth_deg != 0.0 || tilt_deg != 0.0) throw py::value_error("euler_zyz_deg: give Euler angles or a cut with azimuth and tilt, not both");
        orientation.euler_zyz_deg = Eigen::Vector3d((*euler_zyz_deg)[0], (*euler_zyz_deg)[1], (*euler_zyz_deg)[2]);
        return orientation;
    }
    if (cut) orientation.cut = parse_cut(*cut);
    orientation.azimuth_deg = azimuth_deg;
    orientation.tilt_deg = tilt_deg;
    return orientation;
}

std::optional<PlateRequest> plate_argument(const std::optional<std::string>& plate, double slow_deg, double wedge_position) {
    if (!plate) return std::nullopt;
    return PlateRequest{parse_plate(*plate), slow_deg, wedge_position};
}

ProgressCallback PythonProgress::callback() {
    return [this](double fraction_done) {
        const py::gil_scoped_acquire gil;
        if (PyErr_CheckSignals() != 0) throw py::error_already_set();  // Ctrl-C: KeyboardInterrupt
        if (callback_.is_none()) return true;
        const py::object answer = callback_(fraction_done);
        return !(py::isinstance<py::bool_>(answer) && !answer.cast<bool>());
    };
}

void register_exceptions(py::module_& module) {
    static py::exception<Cancelled> cancelled(module, "Cancelled");
    cancelled.doc() = "Raised when a progress callback returned False: the computation stopped.";
    py::register_exception_translator([](std::exception_ptr error) {
        try {
            if (error) std::rethrow_exception(error);
        } catch (const InputError& input) {
            PyErr_SetString(PyExc_ValueError, input.what());
        } catch (const Cancelled& stop) {
            PyErr_SetString(cancelled.ptr(), stop.what());
        }
    });
}

}  // namespace petroscope::python
