// The input values a worked solution plots over: a revolution from the first
// requested value for a crank, the neighbourhood of it for a slider.
#pragma once

#include <vector>

#include <kinema/engine/constraint_system.hpp>

namespace kinema {

/// 181 values over one revolution (2 deg apart) from `first` for an angle input;
/// 201 values over one length scale centred on `first` for a length input. SI.
std::vector<double> plot_range(const ConstraintSystem& system, double first);

}  // namespace kinema
