// GiNaC expressions to the register tape: value numbering, one sincos per
// argument, instructions ordered by input level, products fused into sums.
#include "engine/numeric/tape.hpp"

#include "engine/base/work_count.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <tuple>
#include <vector>

namespace kinema {

using GiNaC::ex;

int CompiledExpressions::operand_count(Op op) {
  switch (op) {
#define KINEMA_TAPE_OPERANDS(name, operands, value, text, js) \
  case Op::name: return operands;
    KINEMA_TAPE_OPS(KINEMA_TAPE_OPERANDS)
#undef KINEMA_TAPE_OPERANDS
    case Op::sincos: return 1;
  }
  return 1;
}

class TapeBuilder {
 public:
  explicit TapeBuilder(CompiledExpressions& target) : t_(target) {}

  void add_input(const ex& symbol, int level) {
    if (!GiNaC::is_a<GiNaC::symbol>(symbol)) throw std::invalid_argument("input is not a symbol");
    memo_[symbol] = {new_register(0.0), false};
    level_.back() = level;
  }

  /// Level of each register: the highest input level it depends on.
  std::vector<int> level_;

  /// A register that holds e's value.
  std::uint32_t compile(const ex& e) { return value(compile_signed(e)); }

 private:
  using Op = CompiledExpressions::Op;
  /// A value as a register and a sign: the register's value, negated if `negated`.
  struct Signed {
    std::uint32_t reg;
    bool negated;
  };
  /// An expression's hash of structure and names, the same for e and -e, and the sign
  /// that tells them apart.
  struct Key {
    std::uint64_t magnitude;
    bool negated;
  };
  enum class Parity { odd, even, neither };

  CompiledExpressions& t_;
  std::map<ex, Signed, GiNaC::ex_is_less> memo_;
  std::map<ex, Key, GiNaC::ex_is_less> keys_;
  std::map<double, std::uint32_t> constants_;
  /// Value numbering: an instruction already on the tape is not emitted again, so
  /// sub-products that GiNaC's expression tree repeats (b*sin(theta3) inside several
  /// terms) are computed once.
  std::map<std::tuple<Op, std::uint32_t, std::uint32_t, int>, std::uint32_t> emitted_;
  std::map<std::uint32_t, std::pair<std::uint32_t, std::uint32_t>> sincos_of_;

  static Parity parity(const std::string& function) {
    if (function == "sin" || function == "tan" || function == "asin" || function == "atan") return Parity::odd;
    if (function == "cos" || function == "abs") return Parity::even;
    return Parity::neither;
  }
  /// A factor +1 or -1: a sign only, in a product's key and on the tape alike.
  static bool is_sign(const ex& factor) {
    return GiNaC::is_a<GiNaC::numeric>(factor) && GiNaC::abs(GiNaC::ex_to<GiNaC::numeric>(factor)).is_equal(1);
  }
  static std::uint64_t mix(std::uint64_t h, std::uint64_t v) { return (h ^ v) * 0x100000001b3ull + (h >> 29); }
  static std::uint64_t text_hash(std::uint64_t h, const std::string& text) {
    for (unsigned char c : text) h = mix(h, c);
    return h;
  }
  static std::string text_of(const ex& e) {
    std::ostringstream text;
    text << e;
    return text.str();
  }

  // GiNaC orders the operands of sums and products by hashes that include addresses
  // (of type information, which move between builds) and symbol serials, and writes a
  // difference either way round: sin(a - b) from one build, -sin(b - a) from another.
  // A tape that followed it added up in another order or with another sign, and the
  // last digits of the numbers and the exported code changed from build to build (issue
  // 9, finding 17). Operands are taken in the order of these keys instead, and every sum
  // is worked out the way round in which its term of the lowest key is positive.
  Key key(const ex& e) {
    using namespace GiNaC;
    auto found = keys_.find(e);
    if (found != keys_.end()) return found->second;
    const std::uint64_t seed = 0xcbf29ce484222325ull;
    Key k{seed, false};
    if (is_a<numeric>(e)) {
      const numeric& n = ex_to<numeric>(e);
      k.negated = n.is_real() && n.is_negative();
      k.magnitude = text_hash(seed, "n" + text_of(k.negated ? ex(-n) : e));
    } else if (is_a<symbol>(e) || is_a<constant>(e)) {
      k.magnitude = text_hash(seed, "s" + text_of(e));
    } else if (is_a<add>(e)) {
      std::vector<Key> terms;
      for (const ex& term : e) terms.push_back(key(term));
      const auto lowest = std::min_element(terms.begin(), terms.end(),
                                           [](const Key& x, const Key& y) { return x.magnitude < y.magnitude; });
      k.negated = lowest != terms.end() && lowest->negated;
      std::vector<std::uint64_t> parts;
      for (const Key& term : terms) parts.push_back(mix(term.magnitude, term.negated != k.negated));
      std::sort(parts.begin(), parts.end());
      k.magnitude = text_hash(seed, "+");
      for (std::uint64_t part : parts) k.magnitude = mix(k.magnitude, part);
    } else if (is_a<mul>(e)) {
      std::vector<std::uint64_t> parts;
      for (const ex& factor : e) {
        const Key f = key(factor);
        k.negated = k.negated != f.negated;
        if (!is_sign(factor)) parts.push_back(f.magnitude);
      }
      std::sort(parts.begin(), parts.end());
      if (parts.size() == 1) {
        k.magnitude = parts.front();  // -x: the key of x
      } else {
        k.magnitude = text_hash(seed, "*");
        for (std::uint64_t part : parts) k.magnitude = mix(k.magnitude, part);
      }
    } else if (is_a<power>(e)) {
      const Key base = key(e.op(0)), exponent = key(e.op(1));
      k.magnitude = mix(mix(text_hash(seed, "^"), base.magnitude), mix(exponent.magnitude, exponent.negated));
      if (is_a<numeric>(e.op(1)) && ex_to<numeric>(e.op(1)).is_integer())
        k.negated = base.negated && ex_to<numeric>(e.op(1)).is_odd();
      else
        k.magnitude = mix(k.magnitude, base.negated);  // (-x)^(1/2) is not -(x^(1/2))
    } else if (is_a<function>(e)) {
      const std::string name = ex_to<function>(e).get_name();
      k.magnitude = text_hash(seed, name);
      const Parity kind = e.nops() == 1 ? parity(name) : Parity::neither;
      for (const ex& argument : e) {
        const Key a = key(argument);
        k.magnitude = mix(k.magnitude, kind == Parity::neither ? mix(a.magnitude, a.negated) : a.magnitude);
        if (kind == Parity::odd) k.negated = a.negated;
      }
    } else {
      k.magnitude = text_hash(seed, "?" + text_of(e));
    }
    keys_.emplace(e, k);
    return k;
  }

  // The operands of a sum or product in the order of their keys.
  std::vector<ex> operands(const ex& e) {
    std::vector<ex> list(e.begin(), e.end());
    std::stable_sort(list.begin(), list.end(),
                     [&](const ex& a, const ex& b) { return key(a).magnitude < key(b).magnitude; });
    return list;
  }

  std::uint32_t new_register(double initial) {
    t_.initial_registers_.push_back(initial);
    level_.push_back(0);
    return static_cast<std::uint32_t>(t_.initial_registers_.size() - 1);
  }

  std::uint32_t constant_register(double value) {
    auto found = constants_.find(value);
    if (found != constants_.end()) return found->second;
    const std::uint32_t reg = new_register(value);
    constants_[value] = reg;
    return reg;
  }

  std::uint32_t emit(Op op, std::uint32_t a, std::uint32_t b = 0, int exponent = 0) {
    if ((op == Op::add || op == Op::mul) && b < a) std::swap(a, b);  // commutative: one key
    const auto key = std::make_tuple(op, a, b, exponent);
    auto found = emitted_.find(key);
    if (found != emitted_.end()) return found->second;
    const std::uint32_t out = new_register(0.0);
    t_.instructions_.push_back({op, out, a, b, exponent});
    level_[out] = CompiledExpressions::operand_count(op) >= 2 ? std::max(level_[a], level_[b]) : level_[a];
    emitted_[key] = out;
    return out;
  }

  std::uint32_t value(Signed s) { return s.negated ? emit(Op::neg, s.reg) : s.reg; }

  // e as a register and key(e)'s sign: the register holds the value of the way round
  // that the key takes for e and -e alike.
  Signed compile_signed(const ex& e) {
    auto found = memo_.find(e);
    if (found != memo_.end()) return found->second;
    const Signed s{compile_new(e), key(e).negated};
    memo_[e] = s;
    return s;
  }

  // The register of compile_signed.
  std::uint32_t compile_new(const ex& e) {
    using namespace GiNaC;
    if (is_a<numeric>(e)) {
      const numeric& n = ex_to<numeric>(e);
      if (!n.is_real()) throw std::invalid_argument("complex number in a compiled expression");
      return constant_register(std::fabs(n.to_double()));
    }
    if (is_a<GiNaC::constant>(e)) return constant_register(ex_to<numeric>(evalf(e)).to_double());
    if (is_a<symbol>(e)) throw std::invalid_argument("symbol " + text_of(e) + " is not an input of the compiled expressions");
    if (is_a<add>(e)) {
      // Terms negative in the way round taken become subtractions.
      const bool flipped = key(e).negated;
      std::uint32_t sum = 0;
      bool first = true;
      for (const ex& term : operands(e)) {
        const Signed t = compile_signed(term);
        const bool negative = t.negated != flipped;
        if (first) sum = negative ? emit(Op::neg, t.reg) : t.reg;
        else sum = emit(negative ? Op::sub : Op::add, sum, t.reg);
        first = false;
      }
      return sum;
    }
    if (is_a<mul>(e)) {
      std::uint32_t product = 0, divisor = 0;
      bool have_product = false, have_divisor = false;
      for (const ex& factor : operands(e)) {
        if (is_sign(factor)) continue;
        // Factors with negative integer powers go to one divisor.
        const bool reciprocal = is_a<power>(factor) && is_a<numeric>(factor.op(1)) &&
                                ex_to<numeric>(factor.op(1)).is_integer() && ex_to<numeric>(factor.op(1)).is_negative();
        const Signed f = compile_signed(reciprocal ? pow(factor.op(0), -factor.op(1)) : factor);
        std::uint32_t& into = reciprocal ? divisor : product;
        bool& have = reciprocal ? have_divisor : have_product;
        into = have ? emit(Op::mul, into, f.reg) : f.reg;
        have = true;
      }
      if (!have_product) product = constant_register(1.0);
      return have_divisor ? emit(Op::div, product, divisor) : product;
    }
    if (is_a<power>(e)) {
      const ex exponent = e.op(1);
      if (is_a<numeric>(exponent) && ex_to<numeric>(exponent).is_integer()) {
        const int k = ex_to<numeric>(exponent).to_int();
        const Signed base = compile_signed(e.op(0));
        if (k == 2) return emit(Op::square, base.reg);
        if (k == -1) return emit(Op::div, constant_register(1.0), base.reg);
        return emit(Op::powi, base.reg, 0, k);
      }
      const std::uint32_t base = compile(e.op(0));
      if (exponent.is_equal(numeric(1, 2))) return emit(Op::sqrt, base);
      return emit(Op::pow, base, compile(exponent));
    }
    if (is_a<function>(e)) {
      const std::string name = ex_to<function>(e).get_name();
      if (name == "sin" || name == "cos") {
        // One sincos for both; memoise the partner so it is never recomputed.
        const Signed argument = compile_signed(e.op(0));
        auto found = sincos_of_.find(argument.reg);
        if (found == sincos_of_.end()) {
          const std::uint32_t sin_reg = new_register(0.0);
          const std::uint32_t cos_reg = new_register(0.0);
          t_.instructions_.push_back({Op::sincos, sin_reg, argument.reg, cos_reg, 0});
          level_[sin_reg] = level_[cos_reg] = level_[argument.reg];
          found = sincos_of_.emplace(argument.reg, std::make_pair(sin_reg, cos_reg)).first;
        }
        const auto [sin_reg, cos_reg] = found->second;
        memo_[GiNaC::sin(e.op(0))] = {sin_reg, argument.negated};  // sin is odd, cos even
        memo_[GiNaC::cos(e.op(0))] = {cos_reg, false};
        return name == "sin" ? sin_reg : cos_reg;
      }
      if (name == "atan2") return emit(Op::atan2, compile(e.op(0)), compile(e.op(1)));
      static const std::map<std::string, Op> unary = {
          {"tan", Op::tan}, {"exp", Op::exp}, {"log", Op::log}, {"abs", Op::abs},
          {"asin", Op::asin}, {"acos", Op::acos}, {"atan", Op::atan}};
      auto found = unary.find(name);
      if (found == unary.end()) throw std::invalid_argument("function " + name + " cannot be compiled");
      // f(-x) = -f(x) or f(x): f of the argument's way round (the sign is the key's).
      return emit(found->second, parity(name) == Parity::neither ? compile(e.op(0)) : compile_signed(e.op(0)).reg);
    }
    throw std::invalid_argument("cannot compile " + text_of(e));
  }
};

CompiledExpressions::CompiledExpressions(const std::vector<GiNaC::ex>& inputs,
                                         const std::vector<GiNaC::ex>& outputs)
    : CompiledExpressions(inputs, std::vector<std::vector<GiNaC::ex>>{outputs}) {}

CompiledExpressions::CompiledExpressions(const std::vector<GiNaC::ex>& inputs,
                                         const std::vector<std::vector<GiNaC::ex>>& stages)
    : CompiledExpressions(inputs, std::vector<int>(inputs.size(), 0), stages) {}

CompiledExpressions::CompiledExpressions(const std::vector<GiNaC::ex>& inputs, const std::vector<int>& input_levels,
                                         const std::vector<std::vector<GiNaC::ex>>& stages) {
  build(inputs, input_levels, stages, stages.size());
}

CompiledExpressions::CompiledExpressions(const std::vector<GiNaC::ex>& inputs, const std::vector<int>& input_levels,
                                         const std::vector<std::vector<GiNaC::ex>>& stages,
                                         const std::vector<GiNaC::ex>& apart) {
  std::vector<std::vector<GiNaC::ex>> all(stages);
  all.push_back(apart);
  build(inputs, input_levels, all, stages.size());
}

void CompiledExpressions::build(const std::vector<GiNaC::ex>& inputs, const std::vector<int>& input_levels,
                                const std::vector<std::vector<GiNaC::ex>>& stages, std::size_t apart_from) {
  count_work(Work::tape_compile);
  if (input_levels.size() != inputs.size()) throw std::invalid_argument("one level per input");
  TapeBuilder builder(*this);
  input_count_ = inputs.size();
  for (int level : input_levels) levels_ = std::max(levels_, level + 1);
  for (std::size_t i = 0; i < inputs.size(); ++i) builder.add_input(inputs[i], input_levels[i]);
  stage_outputs_.push_back(0);
  std::size_t stage_begin = 0;
  for (const auto& stage : stages) {
    for (const ex& output : stage) output_registers_.push_back(builder.compile(output));
    // Lower levels first: an instruction's level is at least its operands', so a
    // stable sort keeps every operand ahead of its use.
    auto level_of = [&](const Instruction& in) { return builder.level_[in.out]; };
    std::stable_sort(instructions_.begin() + stage_begin, instructions_.end(),
                     [&](const Instruction& x, const Instruction& y) { return level_of(x) < level_of(y); });
    for (int level = 0; level <= levels_; ++level) {
      level_begin_.push_back(static_cast<std::size_t>(
          std::find_if(instructions_.begin() + stage_begin, instructions_.end(),
                       [&](const Instruction& in) { return level_of(in) >= level; }) -
          instructions_.begin()));
    }
    stage_begin = instructions_.size();
    stage_end_.push_back(stage_begin);
    stage_outputs_.push_back(output_registers_.size());
  }
  fuse_multiply_adds(builder.level_, apart_from);
}

void CompiledExpressions::fuse_multiply_adds(const std::vector<int>& register_levels, std::size_t apart_from) {
  const std::size_t registers = initial_registers_.size();
  // Stage of each instruction (fusing across stages would move work between them).
  std::vector<std::size_t> stage_of(instructions_.size());
  for (std::size_t stage = 0, k = 0; stage < stage_end_.size(); ++stage)
    for (; k < stage_end_[stage]; ++k) stage_of[k] = stage;
  std::vector<std::size_t> producer(registers, instructions_.size());
  for (std::size_t k = 0; k < instructions_.size(); ++k) producer[instructions_[k].out] = k;
  // A read from a stage apart of an earlier stage's register is noted, not counted.
  std::vector<int> uses(registers, 0);
  std::vector<bool> read_apart(registers, false);
  const auto read = [&](std::uint32_t reg, std::size_t stage, int count) {
    const std::size_t k = producer[reg];
    if (stage >= apart_from && k < instructions_.size() && stage_of[k] < apart_from)
      read_apart[reg] = true;
    else
      uses[reg] += count;
  };
  for (std::size_t k = 0; k < instructions_.size(); ++k) {
    const Instruction& in = instructions_[k];
    read(in.a, stage_of[k], 1);
    if (operand_count(in.op) >= 2) read(in.b, stage_of[k], 1);
    if (operand_count(in.op) >= 3) read(in.c, stage_of[k], 1);
  }
  for (std::size_t stage = 0; stage < stage_end_.size(); ++stage)  // outputs are read by the caller
    for (std::size_t k = stage_outputs_[stage]; k < stage_outputs_[stage + 1]; ++k) read(output_registers_[k], stage, 2);
  std::vector<bool> removed(instructions_.size(), false);
  auto fusable = [&](std::uint32_t reg, std::size_t user) {
    const std::size_t k = producer[reg];
    return k < user && !removed[k] && instructions_[k].op == Op::mul && uses[reg] == 1 &&
           stage_of[k] == stage_of[user] && register_levels[reg] == register_levels[instructions_[user].out];
  };
  for (std::size_t k = 0; k < instructions_.size(); ++k) {
    Instruction& in = instructions_[k];
    if (in.op != Op::add && in.op != Op::sub) continue;
    std::uint32_t product = 0, other = 0;
    Op fused;
    if (fusable(in.a, k)) {
      product = in.a;
      other = in.b;
      fused = in.op == Op::add ? Op::mul_add : Op::mul_sub;
    } else if (fusable(in.b, k)) {
      product = in.b;
      other = in.a;
      fused = in.op == Op::add ? Op::mul_add : Op::sub_mul;
    } else {
      continue;
    }
    const Instruction& multiply = instructions_[producer[product]];
    removed[producer[product]] = true;
    in = {fused, in.out, multiply.a, multiply.b, 0, other};
  }
  // A fused product that a stage apart reads is computed again there.
  std::vector<Instruction> recomputed;
  for (std::size_t k = 0; k < instructions_.size(); ++k)
    if (removed[k] && read_apart[instructions_[k].out]) recomputed.push_back(instructions_[k]);
  // Compact, moving the stage and level boundaries with it.
  std::vector<std::size_t> kept_before(instructions_.size() + 1, 0);
  for (std::size_t k = 0; k < instructions_.size(); ++k) kept_before[k + 1] = kept_before[k] + (removed[k] ? 0 : 1);
  std::size_t next = 0;
  for (std::size_t k = 0; k < instructions_.size(); ++k)
    if (!removed[k]) instructions_[next++] = instructions_[k];
  instructions_.resize(next);
  for (std::size_t& end : stage_end_) end = kept_before[end];
  for (std::size_t& begin : level_begin_) begin = kept_before[begin];
  if (recomputed.empty()) return;
  const std::size_t last = stage_end_.size() - 1;
  instructions_.insert(instructions_.begin() + static_cast<std::ptrdiff_t>(last == 0 ? 0 : stage_end_[last - 1]),
                       recomputed.begin(), recomputed.end());
  stage_end_[last] = instructions_.size();
  sort_last_stage(register_levels);
}

void CompiledExpressions::sort_last_stage(const std::vector<int>& register_levels) {
  const std::size_t last = stage_end_.size() - 1;
  const auto begin = instructions_.begin() + static_cast<std::ptrdiff_t>(last == 0 ? 0 : stage_end_[last - 1]);
  // Stable: what was put first stays first in its level, ahead of its readers.
  const auto level_of = [&](const Instruction& in) { return register_levels[in.out]; };
  std::stable_sort(begin, instructions_.end(),
                   [&](const Instruction& x, const Instruction& y) { return level_of(x) < level_of(y); });
  for (int level = 0; level <= levels_; ++level)
    level_begin_[last * static_cast<std::size_t>(levels_ + 1) + static_cast<std::size_t>(level)] = static_cast<std::size_t>(
        std::find_if(begin, instructions_.end(), [&](const Instruction& in) { return level_of(in) >= level; }) -
        instructions_.begin());
}


}  // namespace kinema
