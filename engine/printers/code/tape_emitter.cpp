#include "engine/printers/code/tape_emitter.hpp"

#include "engine/base/number_format.hpp"

#include <stdexcept>

namespace kinema {
namespace {

using Op = CompiledExpressions::Op;

// The op table's text with A, B, C, E replaced by the operands.
std::string expand(const char* pattern, const std::string& a, const std::string& b, const std::string& c,
                   const std::string& e) {
  std::string text;
  for (const char* p = pattern; *p; ++p) {
    switch (*p) {
      case 'A': text += a; break;
      case 'B': text += b; break;
      case 'C': text += c; break;
      case 'E': text += e; break;
      default: text += *p;
    }
  }
  return text;
}

const char* op_text(Op op) {
  switch (op) {
#define KINEMA_OP_TEXT(name, operands, value, text, js) \
  case Op::name: return text;
    KINEMA_TAPE_OPS(KINEMA_OP_TEXT)
#undef KINEMA_OP_TEXT
    case Op::sincos: break;
  }
  return "";
}

}  // namespace

void write_tape_runner_js(std::ostream& out) {
  out << "// The tape's runner, written by kinema from its one op table (engine/numeric/tape_ops.hpp).\n"
         "const kinemaTapeRunner = (function () {\n"
         "  'use strict';\n"
         "  // base^exponent by squaring, as the tape's integer powers (kinema::integer_power).\n"
         "  function integerPower(base, exponent) {\n"
         "    let result = 1;\n"
         "    for (let e = Math.abs(exponent); e; e >>= 1, base *= base) if (e & 1) result *= base;\n"
         "    return exponent < 0 ? 1 / result : result;\n"
         "  }\n"
         "  // Instructions [begin, end) of a tape (arrays op, out, a, b, c, e) on the registers r.\n"
         "  function run(tape, r, begin, end) {\n"
         "    const op = tape.op, out = tape.out, a = tape.a, b = tape.b, c = tape.c, e = tape.e;\n"
         "    for (let k = begin; k < end; ++k) {\n"
         "      const A = r[a[k]], B = r[b[k]], C = r[c[k]];\n"
         "      switch (op[k]) {\n";
  std::string names;
#define KINEMA_OP_JS(name, operands, value, text, js)                                                      \
  out << "        case " << static_cast<int>(Op::name) << ": r[out[k]] = " << expand(js, "A", "B", "C", "e[k]") \
      << "; break;  // " #name "\n";                                                                        \
  names += "'" #name "', ";
  KINEMA_TAPE_OPS(KINEMA_OP_JS)
#undef KINEMA_OP_JS
  out << "        case " << static_cast<int>(Op::sincos) << ": r[out[k]] = Math.sin(A); r[b[k]] = Math.cos(A); break;  // sincos\n"
         "        default: throw new Error('kinema tape: no operation ' + op[k]);\n"
         "      }\n"
         "    }\n"
         "  }\n"
         "  return { run: run, operations: ["
      << names << "'sincos'] };\n})();\n";
}

std::string cpp_double_literal(double value) {
  std::string text = format_round_trip(value);
  if (text.find_first_of(".eEn") == std::string::npos) text += ".0";
  return text;
}

void write_tape_stage_cpp(std::ostream& out, const CompiledExpressions& tape,
                          const std::vector<std::string>& input_names, std::size_t stage,
                          const std::vector<std::string>& output_targets, const std::string& indent) {
  if (input_names.size() != tape.input_count() || output_targets.size() != tape.stage_output_count(stage)) {
    throw std::invalid_argument("write_tape_stage_cpp: wrong number of input names or output targets");
  }
  const auto& instructions = tape.instructions();
  const auto& initial = tape.initial_registers();
  const std::size_t end = tape.stage_end(stage);
  // Backward liveness from this stage's outputs selects the instructions to write.
  std::vector<bool> live(initial.size(), false);
  for (std::size_t k = 0; k < output_targets.size(); ++k) live[tape.output_register(stage, k)] = true;
  std::vector<bool> needed(instructions.size(), false);
  for (std::size_t k = end; k-- > 0;) {
    const auto& in = instructions[k];
    if (!live[in.out] && !(in.op == Op::sincos && live[in.b])) continue;
    needed[k] = true;
    const int operands = CompiledExpressions::operand_count(in.op);
    live[in.a] = true;
    if (operands >= 2) live[in.b] = true;
    if (operands >= 3) live[in.c] = true;
  }
  std::vector<bool> computed(initial.size(), false);
  for (const auto& in : instructions) {
    computed[in.out] = true;
    if (in.op == Op::sincos) computed[in.b] = true;
  }
  auto operand = [&](std::uint32_t r) {
    if (r < tape.input_count()) return input_names[r];
    if (computed[r]) return "r" + std::to_string(r);
    const std::string text = cpp_double_literal(initial[r]);
    return initial[r] < 0 ? "(" + text + ")" : text;
  };
  auto define = [&](std::uint32_t r, const std::string& value) {
    out << indent << "[[maybe_unused]] const double r" << r << " = " << value << ";\n";
  };
  for (std::size_t k = 0; k < end; ++k) {
    if (!needed[k]) continue;
    const auto& in = instructions[k];
    if (in.op == Op::sincos) {
      define(in.out, "std::sin(" + operand(in.a) + ")");
      define(in.b, "std::cos(" + operand(in.a) + ")");
      continue;
    }
    define(in.out, expand(op_text(in.op), operand(in.a), operand(in.b), operand(in.c), std::to_string(in.exponent)));
  }
  for (std::size_t k = 0; k < output_targets.size(); ++k) {
    out << indent << output_targets[k] << " = " << operand(tape.output_register(stage, k)) << ";\n";
  }
}

}  // namespace kinema
