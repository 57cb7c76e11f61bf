// The compiled tape written as straight-line C++ (for the generated header), and its
// runner as JavaScript (for the web page): the operations' text comes from the tape's
// one op table (tape_ops.hpp).
#pragma once

#include <ostream>
#include <string>
#include <vector>

#include "engine/numeric/tape.hpp"

namespace kinema {

/// Writes stage `stage` of the tape as C++ statements: inputs are read from
/// input_names[i], output k is assigned to output_targets[k] (each a C++ lvalue).
/// Only what the stage's outputs need is written (recomputing what they take from
/// earlier stages), so each stage becomes a self-contained function.
void write_tape_stage_cpp(std::ostream& out, const CompiledExpressions& tape,
                          const std::vector<std::string>& input_names, std::size_t stage,
                          const std::vector<std::string>& output_targets, const std::string& indent);

/// The tape's runner in JavaScript (for the web page): `kinemaTapeRunner.run(tape, r, begin,
/// end)` runs instructions [begin, end) of a tape given as arrays op, out, a, b, c, e (the
/// Instruction fields, op as the Op's number) on the registers r, each operation's case
/// expanded from the op table's JavaScript text; `kinemaTapeRunner.operations` names them
/// by number.
void write_tape_runner_js(std::ostream& out);

/// A double as a C++ literal that reads back to the same value ("1.0", "0.10000000000000001").
std::string cpp_double_literal(double value);

}  // namespace kinema
