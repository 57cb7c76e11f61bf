// The numbers of the sketch: the file's parameters evaluated, joints' and lengths' values, and
// the parameters the loops need made for quantities written in place.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

void LinkageWriter::evaluate_parameters() {
  for (const Parameter& p : m_.parameters) taken_.insert(p.name);
  for (const Parameter& p : m_.parameters) {
    double value = 0;
    if (p.quantity) {
      value = p.quantity->si_value;
    } else {
      value = evaluate(p.formula, p.where, "parameter \"" + p.name + "\"");
    }
    values_[p.name] = value;
    const GiNaC::realsymbol symbol(p.name);
    reader_.define(p.name, symbol);
    symbol_values_[symbol] = value;
  }
}

double LinkageWriter::evaluate(const std::string& formula, const SourceLocation& where, const std::string& what) {
  // A parameter's name is its value: nothing to read.
  if (is_identifier(formula) && reader_.defined(formula) != nullptr) return values_.at(formula);
  const std::string context = where.str() + ": " + what;
  return formula_value(reader_.read(formula, context), symbol_values_, context, formula,
                       " once the parameters are put in");
}

// A length or angle as written: a quantity ("0.3 m") or a formula of the parameters.
double LinkageWriter::value_of(const std::string& text, Dimension dimension, const SourceLocation& where, const std::string& what) {
  if (!looks_like_quantity(text)) return evaluate(text, where, what);
  return quantity_of_dimension(text, dimension, where.str() + ": " + what);
}

std::string LinkageWriter::fresh_name(const std::string& wanted) {
  std::string name = wanted;
  for (int k = 2; taken_.count(name); ++k) name = wanted + "_" + std::to_string(k);
  taken_.insert(name);
  return name;
}

// A generated parameter with an SI value; asked again for the same name and value,
// the same parameter.
std::string LinkageWriter::add_parameter(const std::string& wanted, double value, Dimension dimension, const SourceLocation& where) {
  const auto known = generated_.find(wanted);
  if (known != generated_.end() && values_.at(known->second) == value) return known->second;
  Parameter p;
  p.name = fresh_name(wanted);
  const double shown = dimension == Dimension::angle ? to_degrees(value) : value;
  p.text = format_round_trip(shown) + (dimension == Dimension::angle ? " deg" : " m");
  p.quantity = Quantity{value, dimension};
  p.where = where;
  p.generated = true;
  m_.parameters.push_back(p);
  values_[p.name] = value;
  if (known == generated_.end()) generated_[wanted] = p.name;
  return p.name;
}

// A length or coordinate as a factor in a term: the parameter or formula as written,
// or a parameter made for a quantity.
Operand LinkageWriter::as_factor(const std::string& text, const std::string& wanted, Dimension dimension,
                                     const SourceLocation& where, const std::string& what) {
  if (is_identifier(text)) return {text};
  if (!looks_like_quantity(text)) return {text, true};
  return {add_parameter(wanted, value_of(text, dimension, where, what), dimension, where)};
}

}  // namespace kinema::linkage_detail
