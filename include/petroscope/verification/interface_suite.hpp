#pragma once
// petroscope's own sweeps of the interface model: closed forms over whole ranges of angles, laws over
// random crystals, energy conservation over random media, and agreement with the independent 4×4 solver.
#include "petroscope/verification/report.hpp"

#include <vector>

namespace petroscope {

struct InterfaceSuiteSize {
    int random_energy_cases = 100000;    // R + T = 1 over random media, orientations, incidences
    int near_axis_cases = 10000;         // incidence within 1e-9 rad of an optic axis, exactly on it included
    int berreman_cases = 2000;           // interface solver against the 4×4 transfer-matrix solver
    int optically_active_cases = 2000;   // optically active media: R + T = 1 and the 4×4 solver
    int uniaxial_cases = 2000;           // Snell's law of the ordinary wave, parallel exit from a slab
};

std::vector<VerificationTest> run_interface_suite(const InterfaceSuiteSize& size);

}  // namespace petroscope
