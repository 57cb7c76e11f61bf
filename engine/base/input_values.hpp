// The input values of a run: a list, or a sweep whose values are computed when
// asked, so that a run of 10^7 values holds none of them.
#pragma once

#include <cstddef>
#include <utility>
#include <vector>

namespace kinema {

class InputValues {
 public:
  InputValues() = default;
  InputValues(std::vector<double> list) : list_(std::move(list)), count_(list_.size()) {}  // NOLINT: a list is a run
  /// (start + i * step) * unit for i = 0 .. count - 1 (start and step in the user's unit).
  static InputValues sweep(double start, double step, std::size_t count, double unit) {
    InputValues values;
    values.sweep_ = true;
    values.start_ = start;
    values.step_ = step;
    values.unit_ = unit;
    values.count_ = count;
    return values;
  }

  std::size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  bool is_sweep() const { return sweep_; }
  double operator[](std::size_t i) const {
    return sweep_ ? (start_ + static_cast<double>(i) * step_) * unit_ : list_[i];
  }
  std::vector<double> to_vector() const {
    if (!sweep_) return list_;
    std::vector<double> values(count_);
    for (std::size_t i = 0; i < count_; ++i) values[i] = (*this)[i];
    return values;
  }

 private:
  std::vector<double> list_;
  bool sweep_ = false;
  double start_ = 0, step_ = 0, unit_ = 1;
  std::size_t count_ = 0;
};

}  // namespace kinema
