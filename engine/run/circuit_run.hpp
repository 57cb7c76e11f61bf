// A circuit solved the one way every caller solves it (kinema eval --circuit, kinema page
// --circuit, the Python module's Model.circuit): its step read as the input's quantity, from
// the one value given (or the file's), refused with the reason when it cannot start, move or
// close. The words of a message name the caller's options.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/numeric/circuit.hpp"

namespace kinema {

/// How the caller asks for a circuit, as its messages name it: the step's option, a step
/// written as the caller writes one, and the start's option ("--circuit", "--circuit 1",
/// "--angle" on the command line), and the rows its output may hold (0: the circuit's own
/// bound; a page draws every row, so it holds fewer).
struct CircuitAsked {
  std::string step, example, start;
  std::size_t max_rows = 0;
  std::string rows_holder = "a circuit";  ///< What holds the rows, as the message says ("a page").
};

/// The whole circuit of a mechanism of joints and links solved in closed form, by `step_text`
/// (a quantity of the input's kind; a bare number in the file's output unit), from inputs[0]
/// (SI) or the file's value; InputError or AssemblyError saying why not.
Circuit solve_circuit_from(const Model& model, const std::string& step_text, const std::vector<double>& inputs,
                           const CircuitAsked& asked);

}  // namespace kinema
