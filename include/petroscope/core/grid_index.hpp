#pragma once
// Frames of a grid numbered row-major, the last axis fastest (sweeps: api/sweep.hpp, io/sweep_plan.hpp).
#include <cstddef>
#include <vector>

namespace petroscope {

/// The index along each axis of frame number `frame` of a grid with `counts` values per axis.
inline std::vector<std::size_t> grid_indices(std::size_t frame, const std::vector<std::size_t>& counts) {
    std::vector<std::size_t> indices(counts.size());
    for (std::size_t axis = counts.size(); axis-- > 0;) {
        indices[axis] = frame % counts[axis];
        frame /= counts[axis];
    }
    return indices;
}

}  // namespace petroscope
