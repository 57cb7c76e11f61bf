#include "engine/printers/web/page_constructions.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <map>
#include <string>

#include "engine/base/number_format.hpp"

namespace kinema {
namespace {

using json = nlohmann::ordered_json;

// Five significant digits: a hundredth of a pixel on any panel the page draws them in.
double drawn(double value) { return std::isfinite(value) ? round_significant(value, 5) : value; }

// Rounding noise of a construction (5.6e-17 for a zero) written as the zero it is, at the
// scale `size` (the unit of z).
void push_point(json& out, std::complex<double> z, double per_unit, double size = 0) {
  for (double part : {z.real(), z.imag()}) out.push_back(drawn(zero_at_scale(part, size) / per_unit));
}

const char* kind_name(PolygonArrow::Kind kind) {
  switch (kind) {
    case PolygonArrow::Kind::absolute: return "absolute";
    case PolygonArrow::Kind::relative: return "relative";
    case PolygonArrow::Kind::sliding: return "sliding";
    case PolygonArrow::Kind::normal: return "normal";
    case PolygonArrow::Kind::tangential: return "tangential";
    case PolygonArrow::Kind::coriolis: return "coriolis";
  }
  return "absolute";
}

// Structures in order of first use; a row names its structure by index.
class Structures {
 public:
  std::size_t index(json structure) {
    const std::string key = structure.dump();
    const auto found = index_.find(key);
    if (found != index_.end()) return found->second;
    list_.push_back(std::move(structure));
    return index_[key] = list_.size() - 1;
  }
  json list() const { return list_; }

 private:
  json list_ = json::array();
  std::map<std::string, std::size_t> index_;
};

// A vertex is written as where the row's numbers have it: the pole at 0; a named point's
// image in the velocity (acceleration) polygon is the point's velocity (acceleration), a
// CSV field of the row already ("field": its x); any other vertex by its coordinates here.
// An arrow's ends are indices into the vertices, then the points a construction adds (a
// normal part's tip, where the tangential part starts), given after the vertices.
json polygon_json(const Polygon& polygon, double per_unit, const PointFields& fields, Structures& structures) {
  json structure = {{"order", polygon.order}, {"vertices", json::array()}, {"arrows", json::array()}};
  json row = json::array({0});
  double size = 0;
  for (const PolygonVertex& v : polygon.vertices) size = std::max(size, std::abs(v.at));
  for (const PolygonVertex& v : polygon.vertices) {
    json vertex = {{"name", v.name}};
    const auto field = fields.find(v.name);
    if (std::abs(v.at) <= 1e-12 * size && v.name == "o") {
      vertex["pole"] = true;
    } else if (field != fields.end()) {
      vertex["field"] = polygon.order == 1 ? field->second.first : field->second.second;
    } else {
      push_point(row, v.at, per_unit, size);
    }
    structure["vertices"].push_back(vertex);
  }
  std::vector<std::complex<double>> ends;
  for (const PolygonVertex& v : polygon.vertices) ends.push_back(v.at);
  const auto end = [&](std::complex<double> z) -> std::size_t {
    for (std::size_t k = 0; k < ends.size(); ++k)
      if (std::abs(ends[k] - z) <= 1e-12 * size) return k;
    push_point(row, z, per_unit, size);
    ends.push_back(z);
    return ends.size() - 1;
  };
  for (const PolygonArrow& a : polygon.arrows) {
    const std::size_t from = end(a.from);
    const std::size_t to = end(a.to);
    structure["arrows"].push_back(json::array({kind_name(a.kind), a.name, from, to}));
  }
  row[0] = structures.index(std::move(structure));
  return row;
}

std::string centre_name(const InstantCentres& centres, const InstantCentre& c) {
  return "I" + centres.bodies[c.a] + centres.bodies[c.b];
}

// A centre at a joint (a pin's, and any Kennedy finds there) is named by the joint: the
// drawing's row has its place already.
// The Kennedy lines are a list of their own (one entry per centre): they change with the
// row far more often than the rest of the structure, which then stays shared.
// For a page whose sliders solve again, where a centre's values are among the drawing
// stage's outputs (InstantCentres::tape_bodies, TapeLayout::centre_pair_output): its pair's
// N and D, the sign to read them with (the tape's pair the other way round), each body's
// angular velocity (-1: ground's, 0), then the points it is seen from (x, then y; -1: the
// origin). Null where the centres are not the tape's.
json centre_tape_json(const InstantCentres& centres, const InstantCentre& c, const TapeLayout* layout) {
  if (!layout || centres.tape_bodies.size() != centres.bodies.size()) return nullptr;
  const std::size_t ta = centres.tape_bodies[c.a], tb = centres.tape_bodies[c.b];
  const auto omega = [&](std::size_t t) -> long long { return t == 0 ? -1 : static_cast<long long>(layout->centre_body_output(t)); };
  const auto point = [&](std::size_t t) -> long long { return t == 0 ? -1 : static_cast<long long>(layout->centre_body_output(t) + 1); };
  json seen = json::array();
  for (std::size_t b : c.seen_bodies) seen.push_back(point(centres.tape_bodies[b]));
  return json::array({layout->centre_pair_output(std::min(ta, tb), std::max(ta, tb)), ta < tb ? 1 : -1, omega(ta), omega(tb), seen});
}

json centres_json(const InstantCentres& centres, const std::vector<double>& joints, double per_unit, Structures& structures,
                  Structures& kennedy_sets, const TapeLayout* layout, double mechanism_size) {
  json structure = {{"bodies", centres.bodies}, {"centres", json::array()}};
  json kennedy = json::array();
  json row = json::array({0, 0});
  std::map<std::pair<std::size_t, std::size_t>, std::size_t> index;
  for (std::size_t k = 0; k < centres.centres.size(); ++k) index[{centres.centres[k].a, centres.centres[k].b}] = k;
  const auto find = [&index](std::pair<std::size_t, std::size_t> bodies) -> json {
    if (bodies.first > bodies.second) std::swap(bodies.first, bodies.second);
    const auto found = index.find(bodies);
    return found == index.end() ? json(nullptr) : json(found->second);
  };
  double joints_size = 0;
  for (std::size_t j = 0; j + 1 < joints.size(); j += 2) joints_size = std::max(joints_size, std::hypot(joints[j], joints[j + 1]));
  const double size = std::max(joints_size, mechanism_size);  // what a centre's coordinates are written at
  const auto joint_at = [&](std::complex<double> z) -> json {
    for (std::size_t j = 0; j + 1 < joints.size(); j += 2)
      if (std::abs(z - std::complex<double>(joints[j], joints[j + 1])) <= 1e-12 * joints_size) return j / 2;
    return nullptr;
  };
  for (const InstantCentre& c : centres.centres) {
    // A Kennedy line: the other two centres it passes through (indices into this list).
    json lines = json::array();
    for (std::size_t k = 0; k + 1 < c.kennedy.size(); k += 2) lines.push_back(json::array({find(c.kennedy[k]), find(c.kennedy[k + 1])}));
    const json joint = c.at_infinity ? json(nullptr) : joint_at(c.at);
    structure["centres"].push_back({{"name", centre_name(centres, c)}, {"infinite", c.at_infinity}, {"joint", joint},
                                    {"seen_from", c.seen_from.has_value()}});
    // A pin's centre is at its joint whatever the dimensions: a page that solves again
    // puts it where it draws the joint, not at the tape's N / (i D) (0 / 0 where the two
    // bodies turn alike).
    if (c.pin && !joint.is_null()) structure["centres"].back()["pin"] = true;
    if (const json tape = centre_tape_json(centres, c, layout); !tape.is_null()) structure["centres"].back()["tape"] = tape;
    kennedy.push_back(std::move(lines));
    if (c.at_infinity) push_point(row, c.at, 1.0, 1.0);
    else if (joint.is_null()) push_point(row, c.at, per_unit, size);
    if (c.seen_from) push_point(row, *c.seen_from, per_unit, size);
  }
  json missing = json::array();
  for (const auto& pair : centres.not_found) missing.push_back("I" + centres.bodies[pair.first] + centres.bodies[pair.second]);
  structure["not_found"] = missing;
  row[0] = structures.index(std::move(structure));
  row[1] = kennedy_sets.index(std::move(kennedy));
  return row;
}

}  // namespace

json constructions_json(const std::vector<ValueAnalysis>& values, const MotionDrawing& drawing, double per_unit,
                        const PointFields& point_fields, const TapeLayout* centre_tape, double size) {
  Structures polygon_structures, centre_structures, kennedy_sets;
  json rows = json::array();
  for (std::size_t r = 0; r < values.size(); ++r) {
    const ValueAnalysis& value = values[r];
    if (!value.polygons && !value.centres) {
      rows.push_back(nullptr);
      continue;
    }
    json row = json::object();
    if (value.polygons)
      row["polygons"] = json::array({polygon_json(value.polygons->first, per_unit, point_fields, polygon_structures),
                                     polygon_json(value.polygons->second, per_unit, point_fields, polygon_structures)});
    if (value.centres) {
      // The joints' places (SI) of a drawing of joints and links; of a vector-loop file's,
      // its row's places (the vectors' ends and blocks, the points on links) with each
      // vector's direction left out (NaN: no centre is there): a centre at one is named by
      // its index in the row, as the page reads the row's places.
      std::vector<double> joints;
      if (drawing.form == MotionDrawing::Form::linkage && r < drawing.rows.size())
        joints.assign(drawing.rows[r].begin(), drawing.rows[r].begin() + std::min(drawing.rows[r].size(), 2 * drawing.joint_names.size()));
      if (drawing.form == MotionDrawing::Form::loops && r < drawing.rows.size()) {
        joints = drawing.rows[r];
        for (std::size_t g = 0; g < drawing.segments.size() && 8 * g + 7 < joints.size(); ++g)
          joints[8 * g + 6] = joints[8 * g + 7] = std::numeric_limits<double>::quiet_NaN();
      }
      row["centres"] = centres_json(*value.centres, joints, per_unit, centre_structures, kennedy_sets, centre_tape, size);
    }
    rows.push_back(std::move(row));
  }
  json out = {{"polygon_structures", polygon_structures.list()}, {"centre_structures", centre_structures.list()},
              {"kennedy_sets", kennedy_sets.list()}, {"rows", rows}};
  if (centre_tape) out["centre_parallel_tolerance"] = kCentreParallelTolerance;
  return out;
}

}  // namespace kinema
