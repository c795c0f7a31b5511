#pragma once
// The conoscope through the whole thin-section stack (ConoscopeSettings::mounting): the slow, general path.
#include "petroscope/microscope/conoscope.hpp"

namespace petroscope::detail {

Image render_conoscope_through_stack(const ConoscopeSettings& settings, const PrincipalIndexFunction& principal_n,
                                     const SpectralIntegrator* integrator, const ProgressCallback& progress);

}  // namespace petroscope::detail
