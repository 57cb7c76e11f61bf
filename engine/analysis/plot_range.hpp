// The input values a worked solution plots over: a revolution from the first
// requested value for a crank, the neighbourhood of it for a slider.
#pragma once

#include <vector>

#include "engine/constraint_system.hpp"

namespace kinema {

/// 181 values over one revolution (2 deg apart) from `first` for an angle input;
/// 201 values over one length scale centred on `first` for a length input. SI.
std::vector<double> plot_range(const ConstraintSystem& system, double first);

/// An angle's curve in degrees made continuous: each value moved by whole turns to within
/// 180 deg of the last finite one before it (a solver's atan2 wraps to +-180, a closed form's
/// to 0..360), then the whole curve by whole turns so its value at `reference` is in
/// (-180, 180]. Non-finite values stay (gaps) and are stepped over.
std::vector<double> unwrap_degrees(std::vector<double> degrees, std::size_t reference);

}  // namespace kinema
