// The numbers of the sketch: the file's parameters evaluated, joints' and lengths' values, and
// the parameters the loops need made for quantities written in place.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

void LinkageWriter::evaluate_parameters() {
  for (const Parameter& p : m_.parameters) taken_.insert(p.name);
  for (std::size_t k = 0; k < m_.parameters.size(); ++k) file_parameters_[m_.parameters[k].name] = k;
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
std::string LinkageWriter::add_parameter(const std::string& wanted, double value, Dimension dimension, const SourceLocation& where,
                                         const std::set<std::string>& follows) {
  const auto known = generated_.find(wanted);
  if (known != generated_.end() && values_.at(known->second) == value) {
    for (Parameter& p : m_.parameters) {
      if (p.name != known->second) continue;
      std::set<std::string> all(p.follows.begin(), p.follows.end());
      all.insert(follows.begin(), follows.end());
      p.follows.assign(all.begin(), all.end());
    }
    return known->second;
  }
  Parameter p;
  p.name = fresh_name(wanted);
  const double shown = dimension == Dimension::angle ? to_degrees(value) : value;
  p.text = format_round_trip(shown) + (dimension == Dimension::angle ? " deg" : " m");
  p.quantity = Quantity{value, dimension};
  p.where = where;
  p.generated = true;
  p.follows.assign(follows.begin(), follows.end());
  m_.parameters.push_back(p);
  values_[p.name] = value;
  if (known == generated_.end()) generated_[wanted] = p.name;
  return p.name;
}

// The file's parameters a text names (a quantity names none), and those each of them
// follows through its formula.
std::set<std::string> LinkageWriter::text_follows(const std::string& text) {
  std::set<std::string> found;
  if (text.empty() || looks_like_quantity(text)) return found;
  for (std::size_t k = 0; k < text.size();) {
    const unsigned char c = static_cast<unsigned char>(text[k]);
    if (std::isdigit(c) || c == '.') {  // a number, its exponent too ("2e-3" names no e)
      while (k < text.size() && (std::isalnum(static_cast<unsigned char>(text[k])) || text[k] == '.')) ++k;
      continue;
    }
    if (!std::isalpha(c) && c != '_') {
      ++k;
      continue;
    }
    std::size_t end = k;
    while (end < text.size() && (std::isalnum(static_cast<unsigned char>(text[end])) || text[end] == '_')) ++end;
    const std::string name = text.substr(k, end - k);
    k = end;
    auto known = parameter_follows_.find(name);
    if (known == parameter_follows_.end()) {
      std::set<std::string> follows;  // none for a name that is no parameter of the file (a function, the input)
      const auto parameter = file_parameters_.find(name);
      if (parameter != file_parameters_.end()) {
        follows = text_follows(m_.parameters[parameter->second].formula);  // earlier parameters only: no cycle
        follows.insert(name);
      }
      known = parameter_follows_.emplace(name, std::move(follows)).first;
    }
    found.insert(known->second.begin(), known->second.end());
  }
  return found;
}

// Those of a joint's place in the sketch (and a slider's line).
std::set<std::string> LinkageWriter::joint_follows(std::size_t j) {
  const Joint& joint = linkage_.joints[j];
  std::set<std::string> found;
  for (const std::string* text : {&joint.x, &joint.y, &joint.angle, &joint.through_x, &joint.through_y}) {
    const std::set<std::string> more = text_follows(*text);
    found.insert(more.begin(), more.end());
  }
  return found;
}

// Those of a body's numbers in the sketch: its joints' places, its angle in the sketch (a
// block's from its line and its guide's), the angles written on its link and, where a
// joint's offset is worked out from a triangle of given lengths (three joints or more), the
// lengths written on it.
std::set<std::string> LinkageWriter::body_follows(const Body& body, std::size_t depth) {
  std::set<std::string> found;
  const auto add = [&](const std::set<std::string>& more) { found.insert(more.begin(), more.end()); };
  for (std::size_t j : body.joints) add(joint_follows(j));
  if (body.link != nullptr) {
    for (const auto& angle : body.link->angles) add(text_follows(angle.second));
    if (body.joints.size() >= 3)
      for (const auto& length : body.link->lengths) add(text_follows(length.second));
  }
  for (std::size_t j = 0; j < linkage_.joints.size(); ++j) {
    const Joint& joint = linkage_.joints[j];
    if (joint.kind != Joint::Kind::slider) continue;
    const bool own = body.slider == static_cast<int>(j), guided = joint.guide == body.name && body.joints.size() < 2;
    if (!own && !guided) continue;
    add(joint_follows(j));
    const auto guide = body_index_.find(joint.guide);
    if (own && guide != body_index_.end() && guide->second != 0 && depth <= bodies_.size())
      add(body_follows(bodies_[guide->second], depth + 1));
  }
  return found;
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
