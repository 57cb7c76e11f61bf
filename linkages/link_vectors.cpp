// Link vectors as loop terms: lengths as given or from the sketch, offsets of joints off a
// link's line, a joint's vector on its body, a slider's travel.
#include "linkages/linkage_writer.hpp"

namespace kinema::linkage_detail {

const std::string* LinkageWriter::given_length(const Body& body, const std::string& a, const std::string& b) const {
  if (body.link == nullptr) return nullptr;
  for (const auto& [pair, text] : body.link->lengths) {
    if ((pair.first == a && pair.second == b) || (pair.first == b && pair.second == a)) return &text;
  }
  return nullptr;
}

// The distance between two joints of a body: as given (checked against the sketch),
// else the sketch's.
double LinkageWriter::length_value(const Body& body, std::size_t ja, std::size_t jb) {
  const std::string& a = linkage_.joints[ja].name;
  const std::string& b = linkage_.joints[jb].name;
  const double sketch = std::abs(at_[jb] - at_[ja]);
  const std::string* text = given_length(body, a, b);
  if (text == nullptr) return sketch;
  const SourceLocation& where = body.link->where;
  const double given = value_of(*text, Dimension::length, where, "link " + body.name + " length " + a + "-" + b);
  if (!(given > 0)) fail(where, "link \"" + body.name + "\": the length " + a + "-" + b + " = \"" + *text + "\" is not positive");
  if (std::fabs(given - sketch) > kSketchTolerance * given) {
    fail(where, "link \"" + body.name + "\": the length " + a + "-" + b + " = \"" + *text + "\" is " +
                    format_significant(given) + " m, but the sketch puts " + a + " and " + b + " " +
                    format_significant(sketch) + " m apart (" +
                    format_significant(100 * std::fabs(given - sketch) / given, 3) + " %); correct the sketch or the length");
  }
  return given;
}

// The same distance as a factor of a term.
Operand LinkageWriter::length_factor(const Body& body, std::size_t ja, std::size_t jb) {
  const std::string& a = linkage_.joints[ja].name;
  const std::string& b = linkage_.joints[jb].name;
  const std::string pair = a < b ? a + b : b + a;
  const double value = length_value(body, ja, jb);
  if (const std::string* text = given_length(body, a, b)) {
    return as_factor(*text, pair, Dimension::length, body.link->where, "link " + body.name + " length");
  }
  std::set<std::string> follows = joint_follows(ja);
  const std::set<std::string> other = joint_follows(jb);
  follows.insert(other.begin(), other.end());
  return {add_parameter(pair, value, Dimension::length, body.link->where, follows)};
}

// The angle of the vector from the body's first joint to joint j, minus the body's
// angle: exact from three given lengths (side from the sketch), else the sketch's.
double LinkageWriter::offset(const Body& body, std::size_t j, double d_first_j) {
  const std::size_t first = body.joints[0];
  const Point2 v = at_[j] - at_[first];
  double beta = wrapped(std::arg(v) - body.angle0);
  if (body.link != nullptr) {
    for (const auto& [joint, text] : body.link->angles) {
      if (joint != linkage_.joints[j].name) continue;
      const double given = value_of(text, Dimension::angle, body.link->where, "link " + body.name + " angle at " + joint);
      if (std::fabs(wrapped(given - beta)) > kSketchTolerance) {
        fail(body.link->where, "link \"" + body.name + "\": the angle at " + linkage_.joints[first].name + " to " + joint +
                                   " = \"" + text + "\" is " + format_significant(to_degrees(given)) +
                                   " deg, but the sketch has " + format_significant(to_degrees(beta)) +
                                   " deg; correct the sketch or the angle");
      }
      return wrapped(given);
    }
  }
  if (body.slider < 0 && body.joints.size() >= 2 && j != body.joints[1]) {
    const std::size_t second = body.joints[1];
    const std::string& f = linkage_.joints[first].name;
    const std::string& s = linkage_.joints[second].name;
    const std::string& n = linkage_.joints[j].name;
    if (given_length(body, f, n) && given_length(body, s, n) && d_first_j > 0 && length_value(body, first, second) > 0) {
      const double a = length_value(body, first, second), c = length_value(body, second, j);
      double cosine = (a * a + d_first_j * d_first_j - c * c) / (2 * a * d_first_j);
      if (std::fabs(cosine) > 1 + kSketchTolerance) {
        fail(body.link->where, "link \"" + body.name + "\": the lengths of " + f + ", " + s + " and " + n +
                                   " do not make a triangle; correct them");
      }
      cosine = std::clamp(cosine, -1.0, 1.0);
      const double exact = std::fabs(cosine) > 1 - 1e-12 ? (cosine > 0 ? 0.0 : kPi) : std::acos(cosine);
      beta = (beta < 0 && exact != kPi ? -exact : exact);
    }
  } else if (body.joints.size() >= 2 && j == body.joints[1] && body.slider < 0) {
    beta = 0;
  }
  return beta;
}

// factor * e^{i(angle + beta)} as a term of a loop.
// An angle written as a formula (`beta`) stays that formula in the loop.
Term LinkageWriter::rotated(const Operand& factor, const std::string& angle, double beta,
                            const std::string& beta_name, const SourceLocation& where, const std::string& written,
                            const std::set<std::string>& follows) {
  const double tolerance = 1e-12;
  Term term{false, false, factor, {}};
  if (angle != "0") term.angle.push_back({angle});
  if (!written.empty()) {
    term.angle.push_back({written, !is_identifier(written)});
  } else if (std::fabs(beta) < tolerance) {
  } else if (std::fabs(std::fabs(beta) - kPi) < tolerance) {
    term.negative = true;
  } else if (std::fabs(beta - kPi / 2) < tolerance) {
    term.times_i = true;
  } else if (std::fabs(beta + kPi / 2) < tolerance) {
    term.times_i = true;
    term.negative = true;
  } else {
    term.angle.push_back({add_parameter(beta_name, beta, Dimension::angle, where, follows)});
  }
  return term;
}

// The vector from body b's first joint to joint j (empty when they coincide).
std::vector<Term> LinkageWriter::body_vector(std::size_t b, std::size_t j) {
  const Body& body = bodies_[b];
  const std::size_t first = body.joints[0];
  if (j == first || std::abs(at_[j] - at_[first]) <= 1e-12 * (1 + std::abs(at_[first]))) return {};
  const double beta = offset(body, j, length_value(body, first, j));
  std::string written;  // the angle as the file writes it, when a formula (and the body no block)
  if (body.link != nullptr && body.offset == 0) {
    for (const auto& [joint, text] : body.link->angles)
      if (joint == linkage_.joints[j].name && !looks_like_quantity(text)) written = text;
  }
  return {rotated(length_factor(body, first, j), body.angle, wrapped(beta + body.offset),
                  "beta_" + body.name + "_" + linkage_.joints[j].name, body.link->where, written, body_follows(body))};
}

// A point of ground as written: x + I*y.
std::vector<Term> LinkageWriter::ground_point(const std::string& x, const std::string& y, const std::string& name,
                                               const SourceLocation& where) {
  std::vector<Term> terms;
  const auto zero = [&](const std::string& text) {
    return looks_like_quantity(text) && value_of(text, Dimension::length, where, name) == 0;
  };
  const auto term = [&](const std::string& text, const std::string& wanted, bool times_i) {
    const bool negative = text.size() > 1 && text[0] == '-' && is_identifier(text.substr(1));  // "-Lc"
    return Term{negative, times_i, as_factor(negative ? text.substr(1) : text, wanted, Dimension::length, where, wanted), {}};
  };
  if (!zero(x)) terms.push_back(term(x, "x_" + name, false));
  if (!zero(y)) terms.push_back(term(y, "y_" + name, true));
  return terms;
}

// The point a slider's coordinate is measured from, on its guide, from the guide's first joint.
std::vector<Term> LinkageWriter::through_vector(std::size_t j) {
  const Joint& joint = linkage_.joints[j];
  const std::size_t g = body_index_.at(joint.guide);
  if (g == 0) {
    return joint.through_x.empty() ? ground_point(joint.x, joint.y, joint.name, joint.where)
                                   : ground_point(joint.through_x, joint.through_y, joint.name, joint.where);
  }
  const Body& guide = bodies_[g];
  const Point2 t = through0(j), first = at_[guide.joints[0]];
  if (std::abs(t - first) <= 1e-12 * (1 + std::abs(first))) return {};
  std::set<std::string> follows = body_follows(guide);
  const std::set<std::string> own = joint_follows(j);
  follows.insert(own.begin(), own.end());
  const std::string factor =
      add_parameter("r_" + guide.name + "_" + joint.name, std::abs(t - first), Dimension::length, joint.where, follows);
  const double beta = wrapped(std::arg(t - first) - guide.angle0 + guide.offset);
  return {rotated({factor}, guide.angle, beta, "beta_" + guide.name + "_" + joint.name, joint.where, "", follows)};
}

// s * e^{i(guide angle + line offset)}: the slider's travel along its line.
Term LinkageWriter::travel(std::size_t j) {
  const Joint& joint = linkage_.joints[j];
  const Body& guide = bodies_[body_index_.at(joint.guide)];
  const double beta = wrapped(slider_direction(j) - guide.angle0 + guide.offset);
  std::set<std::string> follows = body_follows(guide);
  const std::set<std::string> own = joint_follows(j);
  follows.insert(own.begin(), own.end());
  return rotated({slider_coordinate_[j]}, guide.angle, beta, "gamma_" + joint.name, joint.where, "", follows);
}

}  // namespace kinema::linkage_detail
