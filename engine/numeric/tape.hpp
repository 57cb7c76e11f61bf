// Expressions compiled once into a register tape (built by tape_builder.cpp,
// run by tape_run.cpp) and evaluated many times
// without GiNaC (in the spirit of SymEngine's LambdaDouble): common
// subexpressions are shared across all outputs, and sin/cos of one argument
// are computed together by one sincos.
#pragma once

#include <ginac/ginac.h>

#include <cstdint>
#include <string>
#include <vector>

#include "engine/numeric/tape_ops.hpp"

namespace kinema {

class CompiledExpressions {
 public:
  CompiledExpressions() = default;
  /// inputs: the symbols, in the order of the values passed to evaluate().
  /// Throws std::invalid_argument for a symbol that is not an input or a complex number.
  CompiledExpressions(const std::vector<GiNaC::ex>& inputs, const std::vector<GiNaC::ex>& outputs);

  /// Staged form: stage k may use inputs that are known only after stage k-1 has been
  /// evaluated (e.g. qd after solving with stage 0's Jacobian). Subexpressions are
  /// shared across stages: a later stage reuses the registers of earlier ones.
  CompiledExpressions(const std::vector<GiNaC::ex>& inputs,
                      const std::vector<std::vector<GiNaC::ex>>& stages);

  /// With input levels (how often each input changes: 0 = fixed, e.g. parameters;
  /// higher = more often). Each stage's instructions are ordered by level (the
  /// highest level among what they depend on), so a caller that changed only inputs
  /// of level >= L reruns just the instructions of level >= L (evaluate_stage_from),
  /// and those of level 0 run once (prepare).
  CompiledExpressions(const std::vector<GiNaC::ex>& inputs, const std::vector<int>& input_levels,
                      const std::vector<std::vector<GiNaC::ex>>& stages);
  /// The same with a last stage apart: it reads the earlier stages' registers but changes
  /// none of their instructions (they are those of the tape without it), so what only a
  /// view needs rides on the tape without costing the solvers anything.
  CompiledExpressions(const std::vector<GiNaC::ex>& inputs, const std::vector<int>& input_levels,
                      const std::vector<std::vector<GiNaC::ex>>& stages, const std::vector<GiNaC::ex>& apart);

  /// Runs every level-0 instruction of every stage (once the level-0 inputs are set).
  void prepare(std::vector<double>& workspace) const;
  /// Runs the instructions of one stage whose level is >= level; lower levels must
  /// hold their values from an earlier run with the same inputs.
  void evaluate_stage_from(std::size_t stage, int level, std::vector<double>& workspace, double* outputs) const;
  /// The same on the batch workspace.
  void evaluate_stage_batch_from(std::size_t stage, int level, double* workspace) const;
  /// prepare() on a batch workspace.
  void prepare_batch(double* workspace) const;

  /// Runs one stage on a workspace whose first input_count() registers hold the
  /// inputs and whose earlier stages were run with the same values of their inputs.
  void evaluate_stage(std::size_t stage, std::vector<double>& workspace, double* outputs) const;
  std::size_t stage_count() const { return stage_end_.size(); }

  /// Batch form: kBatchLanes values of every register side by side (register r of
  /// lane l at r * kBatchLanes + l), so each instruction is one fixed-length loop
  /// that the compiler vectorises (AVX2 where the processor has it, chosen at load
  /// time), sin/cos included. Inputs go in registers [0, input_count()) of each lane.
  static constexpr std::size_t kBatchLanes = 32;
  std::vector<double> make_batch_workspace() const;
  void evaluate_stage_batch(std::size_t stage, double* workspace) const;
  /// Register holding output k (global numbering over all stages).
  std::uint32_t output_register(std::size_t stage, std::size_t k) const {
    return output_registers_[stage_outputs_[stage] + k];
  }
  std::size_t stage_output_count(std::size_t stage) const {
    return stage_outputs_[stage + 1] - stage_outputs_[stage];
  }

  /// Register buffer with the constants in place; reuse it across calls.
  std::vector<double> make_workspace() const { return initial_registers_; }

  /// Evaluates all outputs: inputs[i] is the value of the i-th input symbol.
  void evaluate(const double* inputs, double* outputs, std::vector<double>& workspace) const;

  std::size_t input_count() const { return input_count_; }
  std::size_t output_count() const { return output_registers_.size(); }
  std::size_t instruction_count() const { return instructions_.size(); }

#define KINEMA_TAPE_OP_NAME(name, operands, value, text, js) name,
  enum class Op : std::uint8_t { KINEMA_TAPE_OPS(KINEMA_TAPE_OP_NAME) sincos };
#undef KINEMA_TAPE_OP_NAME
  struct Instruction {
    Op op;
    std::uint32_t out, a, b;  ///< Registers; sincos writes out (sin) and b (cos) from a.
    int exponent;             ///< powi only.
    std::uint32_t c = 0;      ///< Third operand of the fused multiply-adds.
  };
  /// Register operands an instruction reads (sincos reads a and writes b).
  static int operand_count(Op op);

  /// Read-only views for exporters (the C++ emitter).
  const std::vector<Instruction>& instructions() const { return instructions_; }
  const std::vector<double>& initial_registers() const { return initial_registers_; }
  std::size_t stage_end(std::size_t stage) const { return stage_end_[stage]; }
  std::size_t stage_output_begin(std::size_t stage) const { return stage_outputs_[stage]; }
  /// Distinct input levels, and the first instruction of level L (0..levels()) of a stage.
  int levels() const { return levels_; }
  std::size_t level_begin(std::size_t stage, int level) const {
    return level_begin_[stage * (levels_ + 1) + static_cast<std::size_t>(level)];
  }

 private:
  /// Fuses a product used only by the sum right after it in the same stage and level
  /// into one instruction (fewer dispatches for the interpreter).
  /// Compiles `stages`, those from `apart_from` on apart (see the constructor with `apart`).
  void build(const std::vector<GiNaC::ex>& inputs, const std::vector<int>& input_levels,
             const std::vector<std::vector<GiNaC::ex>>& stages, std::size_t apart_from);
  /// Stages from `apart_from` on do not keep an earlier stage's product from being fused:
  /// a product they read is computed again at the start of its level in the last stage.
  void fuse_multiply_adds(const std::vector<int>& register_levels, std::size_t apart_from);
  /// Puts the last stage's instructions in level order again (after fusing moved some in).
  void sort_last_stage(const std::vector<int>& register_levels);
  friend class TapeBuilder;
  void run(std::size_t begin, std::size_t end, double* registers) const;

  std::size_t input_count_ = 0;
  std::vector<Instruction> instructions_;
  std::vector<std::uint32_t> output_registers_;
  std::vector<std::size_t> stage_end_;      ///< One past each stage's last instruction.
  int levels_ = 1;                          ///< Distinct input levels (max level + 1).
  /// First instruction of level L in stage s at level_begin_[s * (levels_ + 1) + L];
  /// [.. + levels_] is the stage's end.
  std::vector<std::size_t> level_begin_;
  std::vector<std::size_t> stage_outputs_;  ///< Output index where each stage starts (+ end).
  std::vector<double> initial_registers_;  ///< Inputs (overwritten), constants, temporaries.
};

}  // namespace kinema
