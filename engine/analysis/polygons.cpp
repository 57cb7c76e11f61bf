#include "engine/analysis/polygons.hpp"

#include <algorithm>
#include <cmath>
#include <tuple>

#include "engine/base/work_count.hpp"

namespace kinema {

namespace {

using GiNaC::ex;
using Complex = std::complex<double>;
using Kind = PolygonArrow::Kind;

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

// A link vector at the state: where it points, its parts, its parts' lengths' formulas' values.
struct VectorValues {
  Complex position;
  std::array<Complex, kLinkVectorParts> part;
  std::array<double, kLinkVectorParts> formula;
  Complex velocity() const { return part[rotation] + part[sliding]; }
  Complex acceleration() const { return part[normal] + part[tangential] + part[coriolis] + part[relative]; }
};

struct Tolerances {
  double length = 0, velocity = 0, acceleration = 0;
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

// Every link vector's values off the model's drawing stage; nullopt where one is not a
// number (no figure of a number that is not one).
std::optional<std::vector<VectorValues>> vector_values(const Model& model, const MotionState& s) {
  const std::vector<double> values = model.kinematics.drawing_values(s);
  const TapeLayout& layout = model.kinematics.layout();
  if (values.empty()) return std::nullopt;
  std::vector<VectorValues> vectors(layout.link_vector_count);
  for (std::size_t k = 0; k < vectors.size(); ++k) {
    const double* v = values.data() + layout.link_vector_output(k);
    for (std::size_t i = 0; i < TapeLayout::kVectorGuideAt; ++i)
      if (!std::isfinite(v[i])) return std::nullopt;
    vectors[k].position = {v[TapeLayout::kVectorPositionAt], v[TapeLayout::kVectorPositionAt + 1]};
    for (std::size_t p = 0; p < kLinkVectorParts; ++p) {
      vectors[k].part[p] = {v[TapeLayout::kVectorPartsAt + 2 * p], v[TapeLayout::kVectorPartsAt + 2 * p + 1]};
      vectors[k].formula[p] = v[TapeLayout::kVectorMagnitudesAt + p];
    }
  }
  return vectors;
}

// Tolerances against the largest velocity and acceleration in play.
Tolerances tolerances_of(const std::vector<VectorValues>& vectors, double length_scale) {
  double fastest = 0, largest = 0;
  for (const VectorValues& v : vectors) {
    fastest = std::max({fastest, std::abs(v.part[rotation]), std::abs(v.part[sliding])});
    for (std::size_t p = normal; p < kLinkVectorParts; ++p) largest = std::max(largest, std::abs(v.part[p]));
  }
  return {1e-9 * length_scale, 1e-9 * std::max(fastest, 1e-300), 1e-9 * std::max(largest, 1e-300)};
}

// The images of the chains' points laid end to end from the pole, and the steps between them.
struct Walk {
  std::vector<Image> images{{0, 0, 0, "o", true}};
  std::vector<Step> steps;
};

// An image at these values: one already found, or a new one (fixed ones named "o").
std::size_t image_of(Walk& walk, const Image& at, const Tolerances& tolerance) {
  for (std::size_t i = 0; i < walk.images.size(); ++i) {
    const Image& image = walk.images[i];
    if (std::abs(image.position - at.position) <= tolerance.length &&
        std::abs(image.velocity - at.velocity) <= 1e3 * tolerance.velocity &&
        std::abs(image.acceleration - at.acceleration) <= 1e3 * tolerance.acceleration)
      return i;
  }
  walk.images.push_back(at);
  Image& added = walk.images.back();
  added.fixed = std::abs(at.velocity) <= tolerance.velocity && std::abs(at.acceleration) <= tolerance.acceleration;
  if (added.fixed) added.name = "o";
  return walk.images.size() - 1;
}

// The two ends of a vector that does not move (a fixed offset: x + I*e) have one image:
// one name, either way along the chain; the images still unnamed are J1, J2, ...
void name_images(Walk& walk, const std::vector<VectorValues>& vectors, const Tolerances& tolerance) {
  for (bool named = true; named;) {
    named = false;
    for (const Step& step : walk.steps) {
      const VectorValues& v = vectors[step.vector];
      if (std::abs(v.part[rotation]) + std::abs(v.part[sliding]) > tolerance.velocity) continue;
      Image &from = walk.images[step.from], &to = walk.images[step.to];
      if (to.name.empty() != from.name.empty()) {
        (to.name.empty() ? to.name : from.name) = to.name.empty() ? from.name : to.name;
        named = true;
      }
    }
  }
  int unnamed = 0;
  for (Image& image : walk.images)
    if (image.name.empty()) image.name = "J" + std::to_string(++unnamed);
}

void add_vertex(Polygon& polygon, const std::string& name, Complex at) {
  for (const PolygonVertex& v : polygon.vertices)
    if (v.name == name) return;
  polygon.vertices.push_back({name, at});
}

// Zero arrows are left out, except a link's turning: v_CB = 0 says the link does not turn.
void add_arrow(Polygon& polygon, const PolygonArrow& arrow, double tolerance) {
  if (arrow.length() <= tolerance && arrow.turning.is_zero()) return;
  // The same arrow twice is kept once, unless it is another link's turning (v_B = v_C
  // when the coupler translates: both are read off).
  for (const PolygonArrow& a : polygon.arrows)
    if (std::abs(a.from - arrow.from) <= tolerance && std::abs(a.to - arrow.to) <= tolerance &&
        (arrow.turning.is_zero() || a.turning.is_equal(arrow.turning)))
      return;
  polygon.arrows.push_back(arrow);
}

// An arrow named by its kind letter, superscript, point and relative-to: "v_BA", a^{n}_{BA}.
PolygonArrow make_arrow(Kind kind, const std::string& letter, const std::string& superscript, const std::string& point,
                        const std::string& base, Complex from, Complex to, const ex& f, double value) {
  PolygonArrow a;
  a.kind = kind;
  a.name = letter + superscript + "_" + point + base;
  a.latex = letter + (superscript.empty() ? "" : "^{" + superscript + "}") + "_{" + math_name(point) + math_name(base) + "}";
  a.from = from;
  a.to = to;
  a.formula = f;
  a.formula_value = std::fabs(value);
  return a;
}

// A link's turning: its rate and its vector as drawn (reversed with the arrow).
PolygonArrow with_turning(PolygonArrow a, const ex& turning, Complex link) {
  a.turning = turning;
  a.link = link;
  return a;
}

// The velocity and acceleration polygons being drawn, with their tolerances.
struct PolygonPair {
  Polygon velocity, acceleration;
  Tolerances tolerance;
};

// A point sliding along a turning line: P' is the point of the line under the sliding
// point P, the vector's end (or its start, drawn from the pole, when the end is the
// line's fixed pivot: P = P' + sliding).
void add_sliding_on_line(PolygonPair& out, const Image& start, const Image& end, const VectorValues& v,
                         const std::array<ex, kLinkVectorParts>& f, const ex& turning) {
  const bool reverse = end.fixed && !start.fixed;
  const double sign = reverse ? -1 : 1;
  const Image &base_image = reverse ? end : start, &point_image = reverse ? start : end;
  const std::string& point = point_image.name;
  const std::string line = point + "'";
  const std::string base = base_image.fixed ? "" : base_image.name;
  const Complex v_line = base_image.velocity + sign * v.part[rotation];
  const Complex a_line = base_image.acceleration + sign * (v.part[normal] + v.part[tangential]);
  add_vertex(out.velocity, line, v_line);
  add_vertex(out.acceleration, line, a_line);
  add_arrow(out.velocity,
            with_turning(make_arrow(base_image.fixed ? Kind::absolute : Kind::relative, "v", "", line, base,
                                    base_image.velocity, v_line, f[rotation], v.formula[rotation]),
                         turning, sign * v.position),
            out.tolerance.velocity);
  add_arrow(out.velocity,
            make_arrow(Kind::sliding, "v", "", point, line, v_line, point_image.velocity, f[sliding], v.formula[sliding]),
            out.tolerance.velocity);
  Complex a = base_image.acceleration;
  for (const auto& [p, kind, sup, to_point, from_point] :
       {std::tuple{normal, Kind::normal, "n", line, base}, std::tuple{tangential, Kind::tangential, "t", line, base},
        std::tuple{coriolis, Kind::coriolis, "c", point, line}, std::tuple{relative, Kind::sliding, "r", point, line}}) {
    add_arrow(out.acceleration,
              make_arrow(kind, "a", sup, to_point, from_point, a, a + sign * v.part[p], f[p], v.formula[p]),
              out.tolerance.acceleration);
    a += sign * v.part[p];
  }
}

// A turning link or a sliding vector of fixed direction: one relative motion of the end
// about the start, drawn from the pole when either is fixed.
void add_relative_motion(PolygonPair& out, const Image& start, const Image& end, const VectorValues& v,
                         const std::array<ex, kLinkVectorParts>& f, const ex& turning) {
  const bool turns = !f[rotation].is_zero();
  const bool reverse = end.fixed && !start.fixed;
  const std::string point = reverse ? start.name : end.name, base = start.fixed || end.fixed ? "" : start.name;
  const double sign = reverse ? -1 : 1;
  const Kind kind = start.fixed || end.fixed ? Kind::absolute : turns ? Kind::relative : Kind::sliding;
  const LinkVectorPart velocity_part = turns ? rotation : sliding;
  const Complex v_from = reverse ? end.velocity : start.velocity;
  const PolygonArrow velocity_arrow = make_arrow(kind, "v", "", point, base, v_from, v_from + sign * v.part[velocity_part],
                                                 f[velocity_part], v.formula[velocity_part]);
  add_arrow(out.velocity, turns ? with_turning(velocity_arrow, turning, sign * v.position) : velocity_arrow,
            out.tolerance.velocity);
  Complex a = reverse ? end.acceleration : start.acceleration;
  if (turns) {
    for (const auto& [p, k, sup] : {std::tuple{normal, Kind::normal, "n"}, std::tuple{tangential, Kind::tangential, "t"}}) {
      add_arrow(out.acceleration, make_arrow(k, "a", sup, point, base, a, a + sign * v.part[p], f[p], v.formula[p]),
                out.tolerance.acceleration);
      a += sign * v.part[p];
    }
  } else {
    add_arrow(out.acceleration,
              make_arrow(kind, "a", "", point, base, a, a + sign * v.part[relative], f[relative], v.formula[relative]),
              out.tolerance.acceleration);
  }
}

}  // namespace

PolygonBuilder::PolygonBuilder(const Model& model) : model_(&model) {
  count_work(Work::drawing);
  const PlanarLinkVectors& link_vectors = model.derivation.link_vectors;
  for (const LinkVectorMotion& m : link_vectors.vectors) {
    LinkVectorParts parts;
    for (std::size_t p = 0; p < kLinkVectorParts; ++p) parts.formulas[p] = positive_form(m.magnitudes[p]);
    if (m.textbook) parts.turning = m.angle_rate;
    parts_.push_back(parts);
  }
  // Points first: their chains name the images that the loops then reach. A vector GiNaC
  // could not differentiate leaves the document without polygons, not without its other pages.
  for (bool points : {true, false}) {
    for (const PlanarLinkVectors::Chain& chain : link_vectors.chains) {
      if (chain.point.has_value() != points || chain.vectors.empty()) continue;
      for (std::size_t v : chain.vectors)
        if (!link_vectors.vectors[v].derived) {
          chains_.clear();
          return;
        }
      chains_.push_back({points ? model.system.points[*chain.point].name : "", chain.vectors});
    }
  }
  if (model.kinematics.layout().link_vector_count != link_vectors.vectors.size()) chains_.clear();
}

std::optional<std::pair<Polygon, Polygon>> PolygonBuilder::polygons(const MotionState& s) const {
  if (chains_.empty() || s.status != Status::ok) return std::nullopt;
  const std::optional<std::vector<VectorValues>> vectors = vector_values(*model_, s);
  if (!vectors) return std::nullopt;
  PolygonPair out;
  out.velocity.order = 1;
  out.acceleration.order = 2;
  out.tolerance = tolerances_of(*vectors, model_->system.length_scale);
  Walk walk;
  for (const Chain& chain : chains_) {
    std::size_t at = 0;
    Complex velocity_sum = 0, acceleration_sum = 0;
    for (std::size_t k : chain.vectors) {
      const Image& start = walk.images[at];
      const VectorValues& v = (*vectors)[k];
      const Image end{start.position + v.position, start.velocity + v.part[rotation] + v.part[sliding],
                      start.acceleration + v.part[normal] + v.part[tangential] + v.part[coriolis] + v.part[relative],
                      "", false};
      velocity_sum += v.velocity();
      acceleration_sum += v.acceleration();
      const std::size_t next = image_of(walk, end, out.tolerance);
      walk.steps.push_back({at, next, k});
      at = next;
    }
    if (!chain.point.empty()) {
      if (!walk.images[at].fixed) walk.images[at].name = chain.point;
    } else {  // a loop: back where it started
      out.velocity.closure_error = std::max(out.velocity.closure_error, std::abs(velocity_sum));
      out.acceleration.closure_error = std::max(out.acceleration.closure_error, std::abs(acceleration_sum));
    }
  }
  name_images(walk, *vectors, out.tolerance);
  for (const Image& image : walk.images) {
    add_vertex(out.velocity, image.name, image.fixed ? 0 : image.velocity);
    add_vertex(out.acceleration, image.name, image.fixed ? 0 : image.acceleration);
  }
  for (const Step& step : walk.steps) {
    const auto& f = parts_[step.vector].formulas;
    const bool turns = !f[rotation].is_zero(), slides = !f[sliding].is_zero() || f[rotation].is_zero();
    const auto add = turns && slides && !f[coriolis].is_zero() ? add_sliding_on_line : add_relative_motion;
    add(out, walk.images[step.from], walk.images[step.to], (*vectors)[step.vector], f, parts_[step.vector].turning);
  }
  // Every named point's absolute velocity and acceleration from the pole.
  for (const PointObservable& point : model_->system.points) {
    for (const Image& image : walk.images) {
      if (image.name != point.name || image.fixed) continue;
      add_arrow(out.velocity, make_arrow(Kind::absolute, "v", "", point.name, "", 0, image.velocity, 0, 0),
                out.tolerance.velocity);
      add_arrow(out.acceleration, make_arrow(Kind::absolute, "a", "", point.name, "", 0, image.acceleration, 0, 0),
                out.tolerance.acceleration);
      break;
    }
  }
  for (Polygon* polygon : {&out.velocity, &out.acceleration})
    for (PolygonArrow& a : polygon->arrows)
      if (a.formula.is_zero()) a.formula_value = a.length();
  return std::pair{out.velocity, out.acceleration};
}

}  // namespace kinema
