// The tape's runners: one value at a time, and kBatchLanes values side by side.
#include "engine/numeric/tape.hpp"

#include <algorithm>
#include <cmath>

#include "engine/numeric/simd_math.hpp"

namespace kinema {

void CompiledExpressions::prepare(std::vector<double>& workspace) const {
  for (std::size_t stage = 0; stage < stage_count(); ++stage)
    run(level_begin(stage, 0), level_begin(stage, 1), workspace.data());
}

void CompiledExpressions::evaluate_stage_from(std::size_t stage, int level, std::vector<double>& workspace,
                                              double* outputs) const {
  double* r = workspace.data();
  run(level_begin(stage, std::min(level, levels_)), stage_end_[stage], r);
  for (std::size_t i = stage_outputs_[stage]; i < stage_outputs_[stage + 1]; ++i)
    *outputs++ = r[output_registers_[i]];
}

constexpr std::size_t kLanes = CompiledExpressions::kBatchLanes;

void CompiledExpressions::run(std::size_t begin, std::size_t end, double* r) const {
  for (std::size_t k = begin; k < end; ++k) {
    const Instruction& in = instructions_[k];
    switch (in.op) {
#define KINEMA_RUN_SCALAR(name, operands, value, text, js)                              \
  case Op::name: {                                                                 \
    [[maybe_unused]] const double A = r[in.a], B = r[in.b], C = r[in.c];           \
    [[maybe_unused]] const int E = in.exponent;                                    \
    r[in.out] = value;                                                             \
    break;                                                                         \
  }
      KINEMA_TAPE_OPS(KINEMA_RUN_SCALAR)
#undef KINEMA_RUN_SCALAR
      case Op::sincos: simd::sincos(r[in.a], r[in.out], r[in.b]); break;
    }
  }
}

void CompiledExpressions::evaluate_stage(std::size_t stage, std::vector<double>& workspace,
                                         double* outputs) const {
  evaluate_stage_from(stage, 0, workspace, outputs);  // level 0 starts the stage
}

std::vector<double> CompiledExpressions::make_batch_workspace() const {
  std::vector<double> registers(initial_registers_.size() * kBatchLanes);
  for (std::size_t r = 0; r < initial_registers_.size(); ++r)
    std::fill_n(registers.begin() + r * kBatchLanes, kBatchLanes, initial_registers_[r]);
  return registers;
}


// One loop of kLanes per instruction. Registers are written once (the tape is in
// SSA form), so an instruction's output never overlaps its operands.
template <typename Instruction, typename Op>
KINEMA_LANE_LOOPS static void run_batch(
    const Instruction* begin, const Instruction* end, double* registers) {
  for (const Instruction* in = begin; in != end; ++in) {
    double* __restrict out = registers + in->out * kLanes;
    const double* __restrict a = registers + in->a * kLanes;
    const double* __restrict b = registers + in->b * kLanes;
    const double* __restrict c = registers + in->c * kLanes;
    switch (in->op) {
#define KINEMA_RUN_LANES(name, operands, value, text, js)                               \
  case Op::name: {                                                                 \
    [[maybe_unused]] const int E = in->exponent;                                   \
    for (std::size_t l = 0; l < kLanes; ++l) {                                     \
      [[maybe_unused]] const double A = a[l], B = b[l], C = c[l];                  \
      out[l] = value;                                                              \
    }                                                                              \
    break;                                                                         \
  }
      KINEMA_TAPE_OPS(KINEMA_RUN_LANES)
#undef KINEMA_RUN_LANES
      case Op::sincos: {
        double* __restrict cos_out = registers + in->b * kLanes;
        int outside = 0;  // an integer sum vectorises; a bool reduction does not
        for (std::size_t l = 0; l < kLanes; ++l) outside += !(std::fabs(a[l]) <= simd::kSinCosLimit);
        if (outside == 0) {
          for (std::size_t l = 0; l < kLanes; ++l) simd::sincos_reduced(a[l], out[l], cos_out[l]);
        } else {
          for (std::size_t l = 0; l < kLanes; ++l) simd::sincos(a[l], out[l], cos_out[l]);
        }
        break;
      }
    }
  }
}

void CompiledExpressions::evaluate_stage_batch(std::size_t stage, double* workspace) const {
  evaluate_stage_batch_from(stage, 0, workspace);
}

void CompiledExpressions::evaluate_stage_batch_from(std::size_t stage, int level, double* workspace) const {
  run_batch<Instruction, Op>(instructions_.data() + level_begin(stage, std::min(level, levels_)),
                             instructions_.data() + stage_end_[stage], workspace);
}

void CompiledExpressions::prepare_batch(double* workspace) const {
  for (std::size_t stage = 0; stage < stage_count(); ++stage)
    run_batch<Instruction, Op>(instructions_.data() + level_begin(stage, 0), instructions_.data() + level_begin(stage, 1),
                               workspace);
}

void CompiledExpressions::evaluate(const double* inputs, double* outputs,
                                   std::vector<double>& workspace) const {
  double* r = workspace.data();
  for (std::size_t i = 0; i < input_count_; ++i) r[i] = inputs[i];
  run(0, instructions_.size(), r);
  for (std::size_t i = 0; i < output_registers_.size(); ++i) outputs[i] = r[output_registers_[i]];
}

}  // namespace kinema
