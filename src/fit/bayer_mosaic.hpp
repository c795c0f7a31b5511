#pragma once
// What a colour camera's Bayer sensor does to a photo: each pixel measures one channel and the other two are
// interpolated from its neighbours (docs/fitting.md, "The camera's sensor").
#include "petroscope/core/image.hpp"

namespace petroscope::detail {

/// `camera_values` (3 channels, camera values black + (gain·linear)^(1/γ)) as an RGGB Bayer sensor with bilinear
/// demosaicing would give them: the values made linear again, each pixel keeping its own channel of the mosaic (red at
/// even rows and columns, blue at odd ones, green elsewhere), the others interpolated bilinearly from the nearest
/// pixels that measured them (Ramanath et al. 2005, "Color image processing pipeline", IEEE Signal Processing
/// Magazine 22(1)), and the camera's curve applied again. The linear interpolation is done on the raw values, as
/// a camera does it, before the tone curve.
Image through_bayer_mosaic(const Image& camera_values, double black_level, double gamma);

}  // namespace petroscope::detail
