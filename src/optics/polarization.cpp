#include "petroscope/optics/polarization.hpp"

namespace petroscope {

Eigen::Vector4d stokes_from_coherency(const CoherencyMatrix& c) {
    return {(c(0, 0) + c(1, 1)).real(), (c(0, 0) - c(1, 1)).real(), 2.0 * c(0, 1).real(), -2.0 * c(0, 1).imag()};
}

CoherencyMatrix coherency_from_stokes(const Eigen::Vector4d& s) {
    using complex = std::complex<double>;
    CoherencyMatrix c;
    c(0, 0) = 0.5 * (s[0] + s[1]);
    c(1, 1) = 0.5 * (s[0] - s[1]);
    c(0, 1) = 0.5 * complex(s[2], -s[3]);
    c(1, 0) = std::conj(c(0, 1));
    return c;
}

CoherencyMatrix coherency_from_jones(const JonesVector& jones) { return jones * jones.adjoint(); }

bool is_physical_stokes(const Eigen::Vector4d& stokes) {
    return stokes.allFinite() && stokes[0] > 0.0 && stokes.tail<3>().squaredNorm() <= stokes[0] * stokes[0] * (1.0 + 1e-12);
}

}  // namespace petroscope
