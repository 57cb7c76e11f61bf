#include "engine/analysis/polygons.hpp"

#include <algorithm>
#include <cmath>

#include "engine/base/work_count.hpp"
#include "engine/symbolic/complex_parts.hpp"
#include "engine/symbolic/derivation.hpp"
#include "engine/symbolic/expression_parts.hpp"

namespace kinema {

namespace {

using GiNaC::ex;
using Complex = std::complex<double>;

// The parts of a link vector in the order of the tape's outputs.
enum Part { rotation, sliding, normal, tangential, coriolis, relative, kParts };
constexpr std::size_t kOutputsPerVector = 2 + 2 * kParts + kParts;  // position, parts, formulas

// The image of a point: where it is, how fast it moves and accelerates (SI).
struct Image {
  Complex position, velocity, acceleration;
  std::string name;
  bool fixed = false;
};

// One link vector walked along a chain, from one image to another.
struct Step {
  std::size_t from = 0, to = 0, vector = 0;
};

// A point's name in math mode: identifiers may hold underscores (P_1), which would be
// subscripts there.
std::string math_name(const std::string& name) {
  if (name.find('_') == std::string::npos) return name;
  std::string escaped;
  for (char c : name) escaped += c == '_' ? std::string("\\_") : std::string(1, c);
  return "\\mathit{" + escaped + "}";
}

// A length's formula written positive where its sign is only the link vector's
// direction (-c*omega4 -> c*omega4): the polygon shows magnitudes.
ex positive_form(const ex& formula) {
  const ex e = formula.expand();
  const auto negative = [](const ex& term) {
    if (GiNaC::is_a<GiNaC::numeric>(term)) return term.info(GiNaC::info_flags::negative);
    if (!GiNaC::is_a<GiNaC::mul>(term)) return false;
    const ex coefficient = term.op(term.nops() - 1);
    return GiNaC::is_a<GiNaC::numeric>(coefficient) && coefficient.info(GiNaC::info_flags::negative);
  };
  if (negative(formula)) return -formula;  // -(CD + CE)*omega3 stays a product
  if (GiNaC::is_a<GiNaC::add>(e)) {
    for (const ex& term : e)
      if (!negative(term)) return formula;
    return -formula;
  }
  return negative(e) ? -e : formula;
}

}  // namespace

PolygonBuilder::PolygonBuilder(const ConstraintSystem& system) : system_(&system) {
  count_work(Work::drawing);
  if (!system.frames.empty()) return;
  std::vector<ex> inputs, outputs;
  for (const SystemParameter& parameter : system.parameters) {
    inputs.push_back(parameter.symbol);
    parameter_values_.push_back(parameter.value);
  }
  inputs.push_back(system.input.symbol);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.symbol);
  inputs.push_back(system.input.rate);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.rate);
  inputs.push_back(system.input.second_rate);
  for (const Coordinate& q : system.unknowns) inputs.push_back(q.second_rate);

  const auto add_vector = [&](const ex& term) {
    const LinkVector link = split_link_vector(term);
    std::array<ex, kParts> parts;
    LinkVectorParts formulas;
    if (link.polar && !link.length.has(GiNaC::I) && !link.angle.has(GiNaC::I)) {
      const ex& length = link.length;
      const ex length_rate = time_derivative(system, length), angle_rate = time_derivative(system, link.angle);
      const ex length_second_rate = time_derivative(system, length_rate);
      const ex angle_second_rate = time_derivative(system, angle_rate);
      const ex direction = GiNaC::exp(GiNaC::I * link.angle);
      parts = {GiNaC::I * angle_rate * length * direction,     length_rate * direction,
               -angle_rate * angle_rate * length * direction,  GiNaC::I * angle_second_rate * length * direction,
               2 * GiNaC::I * angle_rate * length_rate * direction, length_second_rate * direction};
      formulas.formulas = {angle_rate * length,     length_rate,          angle_rate * angle_rate * length,
                           angle_second_rate * length, 2 * angle_rate * length_rate, length_second_rate};
      formulas.turning = angle_rate;
    } else {  // a vector of fixed direction (x + I*e, I*r6) or of no link form: its derivatives whole
      const ex velocity = time_derivative(system, term);
      parts = {0, velocity, 0, 0, 0, time_derivative(system, velocity)};
      formulas.formulas = {0, 0, 0, 0, 0, 0};
    }
    outputs.push_back(real_part_of(term));
    outputs.push_back(imag_part_of(term));
    for (const ex& part : parts) {
      outputs.push_back(real_part_of(part));
      outputs.push_back(imag_part_of(part));
    }
    for (ex& formula : formulas.formulas) {
      outputs.push_back(formula.expand());
      formula = positive_form(formula);
    }
    parts_.push_back(formulas);
    return parts_.size() - 1;
  };
  // Points first: their chains name the images that the loops then reach. A formula GiNaC
  // cannot take apart term by term (a power of 0 in a derivative) leaves the document
  // without polygons, not without its other pages.
  try {
  for (const PointObservable& point : system.points) {
    if (point.written_terms.empty()) continue;
    Chain chain{point.name, {}};
    for (const ex& term : point.written_terms) chain.vectors.push_back(add_vector(term));
    chains_.push_back(chain);
  }
  for (const EquationGroup& group : system.groups) {
    if (!group.vector || group.terms.empty()) continue;
    Chain chain{"", {}};
    for (const ex& term : group.terms) chain.vectors.push_back(add_vector(term));
    chains_.push_back(chain);
  }
  if (!chains_.empty()) tape_ = CompiledExpressions(inputs, outputs);
  } catch (const std::exception&) {
    chains_.clear();
    parts_.clear();
  }
}

std::optional<std::pair<Polygon, Polygon>> PolygonBuilder::polygons(const MotionState& s) const {
  if (chains_.empty() || s.status != Status::ok) return std::nullopt;
  const ConstraintSystem& system = *system_;
  std::vector<double> inputs(parameter_values_);
  inputs.push_back(s.input);
  for (Eigen::Index i = 0; i < s.q.size(); ++i) inputs.push_back(s.q[i]);
  inputs.push_back(s.input_rate);
  for (Eigen::Index i = 0; i < s.qd.size(); ++i) inputs.push_back(s.qd[i]);
  inputs.push_back(s.input_second_rate);
  for (Eigen::Index i = 0; i < s.qdd.size(); ++i) inputs.push_back(s.qdd[i]);
  if (inputs.size() != tape_.input_count()) return std::nullopt;
  std::vector<double> values(tape_.output_count()), registers = tape_.make_workspace();
  tape_.evaluate(inputs.data(), values.data(), registers);
  for (double v : values)
    if (!std::isfinite(v)) return std::nullopt;  // no figure of a number that is not one
  const auto output = [&](std::size_t vector, std::size_t k) { return values[vector * kOutputsPerVector + k]; };
  const auto position = [&](std::size_t v) { return Complex(output(v, 0), output(v, 1)); };
  const auto part = [&](std::size_t v, int p) { return Complex(output(v, 2 + 2 * p), output(v, 3 + 2 * p)); };
  const auto formula = [&](std::size_t v, int p) { return output(v, 2 + 2 * kParts + p); };

  // Tolerances against the largest velocity and acceleration in play.
  double fastest = 0, largest = 0;
  for (std::size_t v = 0; v < parts_.size(); ++v) {
    fastest = std::max({fastest, std::abs(part(v, rotation)), std::abs(part(v, sliding))});
    for (int p = normal; p < kParts; ++p) largest = std::max(largest, std::abs(part(v, p)));
  }
  const double length_tolerance = 1e-9 * system.length_scale;
  const double velocity_tolerance = 1e-9 * std::max(fastest, 1e-300);
  const double acceleration_tolerance = 1e-9 * std::max(largest, 1e-300);
  const auto is_fixed = [&](const Image& i) {
    return std::abs(i.velocity) <= velocity_tolerance && std::abs(i.acceleration) <= acceleration_tolerance;
  };

  std::vector<Image> images{{0, 0, 0, "o", true}};
  std::vector<Step> steps;
  const auto image_of = [&](const Image& at) {
    for (std::size_t i = 0; i < images.size(); ++i) {
      if (std::abs(images[i].position - at.position) <= length_tolerance &&
          std::abs(images[i].velocity - at.velocity) <= 1e3 * velocity_tolerance &&
          std::abs(images[i].acceleration - at.acceleration) <= 1e3 * acceleration_tolerance)
        return i;
    }
    images.push_back(at);
    images.back().fixed = is_fixed(at);
    if (images.back().fixed) images.back().name = "o";
    return images.size() - 1;
  };
  Polygon velocity_polygon, acceleration_polygon;
  velocity_polygon.order = 1;
  acceleration_polygon.order = 2;
  for (const Chain& chain : chains_) {
    std::size_t at = 0;
    Complex velocity_sum = 0, acceleration_sum = 0;
    for (std::size_t v : chain.vectors) {
      const Image& start = images[at];
      Image end{start.position + position(v), start.velocity + part(v, rotation) + part(v, sliding),
                start.acceleration + part(v, normal) + part(v, tangential) + part(v, coriolis) + part(v, relative),
                "", false};
      velocity_sum += part(v, rotation) + part(v, sliding);
      acceleration_sum += part(v, normal) + part(v, tangential) + part(v, coriolis) + part(v, relative);
      const std::size_t next = image_of(end);
      steps.push_back({at, next, v});
      at = next;
    }
    if (!chain.point.empty()) {
      if (!images[at].fixed) images[at].name = chain.point;
    } else {  // a loop: back where it started
      velocity_polygon.closure_error = std::max(velocity_polygon.closure_error, std::abs(velocity_sum));
      acceleration_polygon.closure_error = std::max(acceleration_polygon.closure_error, std::abs(acceleration_sum));
    }
  }
  // The two ends of a vector that does not move (a fixed offset: x + I*e) have one image:
  // one name, either way along the chain.
  for (bool named = true; named;) {
    named = false;
    for (const Step& step : steps) {
      if (std::abs(part(step.vector, rotation)) + std::abs(part(step.vector, sliding)) > velocity_tolerance) continue;
      Image &from = images[step.from], &to = images[step.to];
      if (to.name.empty() != from.name.empty()) {
        (to.name.empty() ? to.name : from.name) = to.name.empty() ? from.name : to.name;
        named = true;
      }
    }
  }
  int unnamed = 0;
  for (Image& image : images)
    if (image.name.empty()) image.name = "J" + std::to_string(++unnamed);

  const auto add_vertex = [](Polygon& polygon, const std::string& name, Complex at) {
    for (const PolygonVertex& v : polygon.vertices)
      if (v.name == name) return;
    polygon.vertices.push_back({name, at});
  };
  // Zero arrows are left out, except a link's turning: v_CB = 0 says the link does not turn.
  const auto add_arrow = [&](Polygon& polygon, PolygonArrow arrow, double tolerance) {
    if (arrow.length() <= tolerance && arrow.turning.is_zero()) return;
    // The same arrow twice is kept once, unless it is another link's turning (v_B = v_C
    // when the coupler translates: both are read off).
    for (const PolygonArrow& a : polygon.arrows)
      if (std::abs(a.from - arrow.from) <= tolerance && std::abs(a.to - arrow.to) <= tolerance &&
          (arrow.turning.is_zero() || a.turning.is_equal(arrow.turning)))
        return;
    polygon.arrows.push_back(arrow);
  };
  // name_of(kind letter, superscript, point, relative-to): "v_BA", a^{n}_{BA}.
  const auto arrow = [](PolygonArrow::Kind kind, const std::string& letter, const std::string& superscript,
                        const std::string& point, const std::string& base, Complex from, Complex to, const ex& f,
                        double value) {
    PolygonArrow a;
    a.kind = kind;
    a.name = letter + superscript + "_" + point + base;
    a.latex = letter + (superscript.empty() ? "" : "^{" + superscript + "}") + "_{" + math_name(point) + math_name(base) + "}";
    a.from = from;
    a.to = to;
    a.formula = f;
    a.formula_value = std::fabs(value);
    return a;
  };
  // A link's turning: its rate and its vector as drawn (reversed with the arrow).
  const auto turning = [&](PolygonArrow a, std::size_t vector, double sign) {
    a.turning = parts_[vector].turning;
    a.link = sign * position(vector);
    return a;
  };
  for (const Image& image : images) {
    add_vertex(velocity_polygon, image.name, image.fixed ? 0 : image.velocity);
    add_vertex(acceleration_polygon, image.name, image.fixed ? 0 : image.acceleration);
  }
  using Kind = PolygonArrow::Kind;
  for (const Step& step : steps) {
    const Image &start = images[step.from], &end = images[step.to];
    const std::size_t v = step.vector;
    const auto& f = parts_[v].formulas;
    const std::string& S = start.name;
    const std::string& E = end.name;
    const bool turns = !f[rotation].is_zero(), slides = !f[sliding].is_zero() || f[rotation].is_zero();
    if (turns && slides && !f[coriolis].is_zero()) {
      // A point sliding along a turning line: P' is the point of the line under the
      // sliding point P, the vector's end (or its start, drawn from the pole, when the
      // end is the line's fixed pivot: P = P' + sliding).
      const bool reverse = end.fixed && !start.fixed;
      const double sign = reverse ? -1 : 1;
      const Image &base_image = reverse ? end : start, &point_image = reverse ? start : end;
      const std::string& point = point_image.name;
      const std::string line = point + "'";
      const std::string base = base_image.fixed ? "" : base_image.name;
      const Complex v_line = base_image.velocity + sign * part(v, rotation);
      const Complex a_line = base_image.acceleration + sign * (part(v, normal) + part(v, tangential));
      add_vertex(velocity_polygon, line, v_line);
      add_vertex(acceleration_polygon, line, a_line);
      add_arrow(velocity_polygon,
                turning(arrow(base_image.fixed ? Kind::absolute : Kind::relative, "v", "", line, base,
                              base_image.velocity, v_line, f[rotation], formula(v, rotation)),
                        v, sign),
                velocity_tolerance);
      add_arrow(velocity_polygon,
                arrow(Kind::sliding, "v", "", point, line, v_line, point_image.velocity, f[sliding], formula(v, sliding)),
                velocity_tolerance);
      Complex a = base_image.acceleration;
      for (const auto& [p, kind, sup, to_point, from_point] :
           {std::tuple{normal, Kind::normal, "n", line, base}, std::tuple{tangential, Kind::tangential, "t", line, base},
            std::tuple{coriolis, Kind::coriolis, "c", point, line}, std::tuple{relative, Kind::sliding, "r", point, line}}) {
        add_arrow(acceleration_polygon,
                  arrow(kind, "a", sup, to_point, from_point, a, a + sign * part(v, p), f[p], formula(v, p)),
                  acceleration_tolerance);
        a += sign * part(v, p);
      }
      continue;
    }
    // A turning link or a sliding vector of fixed direction: one relative motion of E
    // about S, drawn from the pole when S or E is fixed.
    const bool reverse = end.fixed && !start.fixed;
    const std::string point = reverse ? S : E, base = start.fixed || end.fixed ? "" : S;
    const double sign = reverse ? -1 : 1;
    const Kind kind = start.fixed || end.fixed ? Kind::absolute : turns ? Kind::relative : Kind::sliding;
    const int velocity_part = turns ? rotation : sliding;
    const Complex v_from = reverse ? end.velocity : start.velocity;
    PolygonArrow velocity_arrow = arrow(kind, "v", "", point, base, v_from, v_from + sign * part(v, velocity_part),
                                        f[velocity_part], formula(v, velocity_part));
    add_arrow(velocity_polygon, turns ? turning(velocity_arrow, v, sign) : velocity_arrow, velocity_tolerance);
    Complex a = reverse ? end.acceleration : start.acceleration;
    if (turns) {
      for (const auto& [p, k, sup] : {std::tuple{normal, Kind::normal, "n"}, std::tuple{tangential, Kind::tangential, "t"}}) {
        add_arrow(acceleration_polygon, arrow(k, "a", sup, point, base, a, a + sign * part(v, p), f[p], formula(v, p)),
                  acceleration_tolerance);
        a += sign * part(v, p);
      }
    } else {
      add_arrow(acceleration_polygon,
                arrow(kind, "a", "", point, base, a, a + sign * part(v, relative), f[relative], formula(v, relative)),
                acceleration_tolerance);
    }
  }
  // Every named point's absolute velocity and acceleration from the pole.
  for (const PointObservable& point : system.points) {
    for (const Image& image : images) {
      if (image.name != point.name || image.fixed) continue;
      add_arrow(velocity_polygon, arrow(Kind::absolute, "v", "", point.name, "", 0, image.velocity, 0, 0),
                velocity_tolerance);
      add_arrow(acceleration_polygon, arrow(Kind::absolute, "a", "", point.name, "", 0, image.acceleration, 0, 0),
                acceleration_tolerance);
      break;
    }
  }
  for (PolygonArrow& a : velocity_polygon.arrows)
    if (a.formula.is_zero()) a.formula_value = a.length();
  for (PolygonArrow& a : acceleration_polygon.arrows)
    if (a.formula.is_zero()) a.formula_value = a.length();
  return std::pair{velocity_polygon, acceleration_polygon};
}

}  // namespace kinema
