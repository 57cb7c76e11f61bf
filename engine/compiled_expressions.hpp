// Expressions compiled once into a register tape and evaluated many times
// without GiNaC (in the spirit of SymEngine's LambdaDouble): common
// subexpressions are shared across all outputs, and sin/cos of one argument
// are computed together by one sincos.
#pragma once

#include <ginac/ginac.h>

#include <cstdint>
#include <ostream>
#include <string>
#include <vector>

namespace kinema {

class CompiledExpressions {
 public:
  CompiledExpressions() = default;
  /// inputs: the symbols, in the order of the values passed to evaluate().
  /// Throws std::invalid_argument for a symbol that is not an input or a complex number.
  CompiledExpressions(const std::vector<GiNaC::ex>& inputs, const std::vector<GiNaC::ex>& outputs);

  /// Register buffer with the constants in place; reuse it across calls.
  std::vector<double> make_workspace() const { return initial_registers_; }

  /// Evaluates all outputs: inputs[i] is the value of the i-th input symbol.
  void evaluate(const double* inputs, double* outputs, std::vector<double>& workspace) const;

  /// Writes the tape as straight-line C++ statements: inputs are read from
  /// input_names[i], output k is assigned to output_targets[k] (each a C++ lvalue).
  void write_cpp(std::ostream& out, const std::vector<std::string>& input_names,
                 const std::vector<std::string>& output_targets, const std::string& indent) const;

  std::size_t input_count() const { return input_count_; }
  std::size_t output_count() const { return output_registers_.size(); }
  std::size_t instruction_count() const { return instructions_.size(); }

 private:
  enum class Op : std::uint8_t {
    add, sub, mul, div, neg, square, powi, pow, sincos, tan, exp, log, sqrt, abs, atan2,
    asin, acos, atan
  };
  struct Instruction {
    Op op;
    std::uint32_t out, a, b;  ///< Registers; sincos writes out (sin) and b (cos) from a.
    int exponent;             ///< powi only.
  };
  friend class TapeBuilder;

  std::size_t input_count_ = 0;
  std::vector<Instruction> instructions_;
  std::vector<std::uint32_t> output_registers_;
  std::vector<double> initial_registers_;  ///< Inputs (overwritten), constants, temporaries.
};

}  // namespace kinema
