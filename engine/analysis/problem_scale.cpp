#include "engine/analysis/problem_scale.hpp"

#include <algorithm>
#include <cmath>
#include <map>

#include "engine/base/number_format.hpp"
#include "engine/base/units.hpp"

namespace kinema {

ProblemScale::ProblemScale(const ConstraintSystem& system) {
  const OutputScale scale(system);
  double size = 0;
  for (const SystemParameter& p : system.parameters)
    if (p.dimension == Dimension::length && std::isfinite(p.value)) size = std::max(size, std::fabs(p.value));
  if (size == 0) size = 1;  // no length given: the metre
  length_ = size / scale.length;
  // A length driver's rate over the size is its angular rate.
  const Driver& input = system.input;
  const double per = input.dimension == Dimension::length ? 1 / size : 1;
  rate_ = std::fabs(input.rate_value) * per;
  second_rate_ = rate_ * rate_ + std::fabs(input.second_rate_value) * per;
  if (!(rate_ > 0) || !std::isfinite(rate_)) rate_ = 1;
  if (!(second_rate_ > 0) || !std::isfinite(second_rate_)) second_rate_ = 1;
}

double ProblemScale::of(Dimension dimension, int order) const {
  const double time = order == 0 ? 1 : order == 1 ? rate_ : second_rate_;
  switch (dimension) {
    case Dimension::length: return length_ * time;
    case Dimension::angle: return time * (order == 0 ? 180 / kPi : 1);  // values in deg, rates in rad/s
    default: return 0;
  }
}

RowScales::RowScales(const ConstraintSystem& system, const std::vector<ResultColumn>& columns) {
  const ProblemScale problem(system);
  for (const ResultColumn& column : columns) sizes_.push_back(problem.of(column));
  std::size_t at = kInputColumns;
  const auto add = [&](std::size_t count, std::vector<std::size_t> groups) {
    Section section{{}, std::move(groups)};
    std::size_t width = 0;
    for (std::size_t g : section.groups) width += g;
    for (std::size_t e = 0; e < count; ++e, at += width) section.entries.push_back(at);
    sections_.push_back(std::move(section));
  };
  add(system.unknowns.size(), {1, 1, 1});
  // Points: a column over the points of its dimension (the table's header runs), each of a
  // point's vectors with its magnitude.
  std::map<std::size_t, Section> points;  // by dimension
  for (const PointObservable& p : system.points) {
    const std::size_t d = p.components.size();
    Section& section = points.try_emplace(d, Section{{}, {d, d + 1, d + 1}}).first->second;
    section.entries.push_back(at);
    at += 3 * d + 2;
  }
  for (auto& [d, section] : points) sections_.push_back(std::move(section));
  add(system.frames.size(), {3, 3});
  add(block_links(system).size(), {1, 1, 1});
  if (system.plan) {
    add(system.plan->sliders.size(), {2, 2, 2});
    add(guide_points(system).size(), {2, 2});
    add(relative_turnings(system).size(), {1, 1});
  }
}

std::vector<double> RowScales::operator()(const double* row) const {
  std::vector<double> with = sizes_;
  for (const Section& section : sections_) {
    std::size_t offset = 0;
    for (std::size_t g : section.groups) {
      double largest = 0;
      for (std::size_t entry : section.entries) largest = std::max(largest, largest_magnitude(row + entry + offset, g));
      for (std::size_t entry : section.entries)
        for (std::size_t k = entry + offset; k < entry + offset + g; ++k) with[k] = std::max(with[k], largest);
      offset += g;
    }
  }
  return with;
}

}  // namespace kinema
