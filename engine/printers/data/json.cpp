// Results for programs (schema in docs/outputs.md): the description of the run
// indented, then the results, one object per line so that a long run streams
// and stays readable with line tools (grep, head, jq -c).
#include <cmath>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/printers/printer.hpp"
#include "engine/analysis/design_figures.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/base/number_format.hpp"
#include "engine/analysis/output_scale.hpp"

namespace kinema {
namespace {

using json = nlohmann::ordered_json;

// A JSON string literal (quotes and escapes).
std::string quoted(const std::string& text) { return json(text).dump(); }

class JsonPrinter : public ResultsPrinter {
 public:
  const char* name() const override { return "json"; }
  ViewNeeds needs(const PrintJob&) const override {
    ViewNeeds needs;
    needs.design_figures = true;  // the head's "strokes" and "four_bar"
    return needs;
  }

  void head(std::string& out, const PrintJob& job, std::size_t) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    const Driver& input = system.input;
    auto kind_name = [](Dimension d) { return d == Dimension::angle ? "angle" : d == Dimension::time ? "time" : "length"; };
    json doc;
    doc["title"] = system.title;
    doc["units"] = {{"angle", "deg"},
                    {"angular_rate", "rad/s"},
                    {"angular_second_rate", "rad/s^2"},
                    {"length", scale.length_unit},
                    {"velocity", scale.length_unit + "/s"},
                    {"acceleration", scale.length_unit + "/s^2"}};
    doc["input"] = {{"name", input.name},
                    {"kind", kind_name(input.dimension)},
                    {"rate_name", input.rate.get_name()},
                    {"second_rate_name", input.second_rate.get_name()}};
    json coordinates = json::array();
    for (const Coordinate& q : system.unknowns) {
      coordinates.push_back({{"name", q.name},
                             {"kind", kind_name(q.dimension)},
                             {"rate_name", q.rate.get_name()},
                             {"second_rate_name", q.second_rate.get_name()}});
    }
    doc["coordinates"] = coordinates;
    json points = json::array();
    for (const PointObservable& p : system.points) points.push_back(p.name);
    doc["points"] = points;
    const Analysis& analysis = analysis_of(job);
    const std::vector<Strokes>& strokes = analysis.strokes;
    if (!strokes.empty()) {  // a crank-driven slider's limits and time ratio
      json list = json::array();
      for (const Strokes& s : strokes) {
        list.push_back({{"coordinate", s.name},
                        {"limit_inputs", {s.limit_inputs[0], s.limit_inputs[1]}},
                        {"limit_values", {s.limit_values[0], s.limit_values[1]}},
                        {"strokes", {s.first_stroke, s.second_stroke}},
                        {"time_ratio", s.time_ratio}});
      }
      doc["strokes"] = list;
    }
    if (const auto& f = analysis.four_bar) {  // design figures of a four-bar
      const auto finite = [](double x) { return std::isfinite(x) ? json(x) : json(nullptr); };
      doc["four_bar"] = {{"grashof", f->grashof},
                         {"inequality", f->inequality},
                         {"lengths", {{"ground", f->ground / scale.length},
                                      {"crank", f->crank / scale.length},
                                      {"coupler", f->coupler / scale.length},
                                      {"rocker", f->rocker / scale.length}}},
                         {"transmission_angle", {{"least", finite(f->least_transmission)},
                                                 {"least_at", finite(f->least_at)},
                                                 {"greatest", finite(f->greatest_transmission)},
                                                 {"greatest_at", finite(f->greatest_at)},
                                                 {"full_turn", f->full_turn}}},
                         {"toggles", f->toggles}};
    }
    if (!system.frames.empty()) {
      json frames = json::array();
      for (const FrameObservable& f : system.frames) frames.push_back(f.name);
      doc["frames"] = frames;
    }
    std::string text = doc.dump(2);  // ends with "\n}": the results go before it
    text.resize(text.size() - 2);
    out += text + ",\n  \"results\": [";
  }

  void rows(std::string& out, const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last,
            std::size_t run_row) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    // The block's values at once (worked out column by column), then row by row.
    const std::size_t columns = result_column_count(system, job.circuit);
    std::vector<double> block((last - first) * columns);
    result_rows(system, scale, table, first, last, block.data());
    std::vector<std::string> coordinate_keys, point_keys, frame_keys;
    for (const Coordinate& q : system.unknowns) coordinate_keys.push_back(quoted(q.name) + ": {\"value\": ");
    for (const PointObservable& p : system.points) point_keys.push_back(quoted(p.name) + ": {\"position\": ");
    for (const FrameObservable& f : system.frames) frame_keys.push_back(quoted(f.name) + ": {\"angular_velocity\": ");
    const auto blocks = block_links(system);  // joints and links: once, not per row
    std::vector<std::string> guide_keys, turning_keys;
    for (const GuidePoint& g : guide_points(system)) {
      const LinkageFrames::Slider& slider = system.linkage->frames.sliders[g.slider];
      guide_keys.push_back(quoted(g.name) + ": {\"slider\": " + quoted(system.linkage->joints[slider.joint].name) +
                           ", \"link\": " + quoted(system.linkage->links[slider.guide - 1].name) + ", \"velocity\": ");
    }
    for (const RelativeTurning& r : relative_turnings(system)) {
      turning_keys.push_back(quoted(r.rate_name) + ": {\"links\": [" + quoted(system.linkage->links[r.block - 1].name) +
                             ", " + quoted(system.linkage->links[r.other - 1].name) + "], \"joint\": " +
                             quoted(system.linkage->joints[r.joint].name) + ", \"second_rate_name\": " +
                             quoted(r.second_rate_name) + ", \"rate\": ");
    }
    std::vector<std::string> branch_keys;
    if (job.circuit)
      for (const std::string& joint : dyad_inner_joints(system)) branch_keys.push_back(quoted(joint) + ": ");
    char buffer[kMaxNumberChars];
    // Every double so that it reads back exactly, or rounded to --precision digits;
    // never NaN or infinity (not JSON): null.
    const auto number = [&](double value) {
      if (!std::isfinite(value)) {
        out += "null";
        return;
      }
      if (job.precision > 0) value = round_significant(value, job.precision);
      out.append(buffer, put_shortest(buffer, value));
    };
    const auto vector = [&](const double* v, std::size_t dimension) {
      out += '[';
      for (std::size_t c = 0; c < dimension; ++c) {
        if (c > 0) out += ", ";
        number(v[c]);
      }
      out += ']';
    };
    // `text` (separator and key) then a number or a vector.
    const auto member = [&](const char* text, double value) {
      out += text;
      number(value);
    };
    const auto member_vector = [&](const char* text, const double* v, std::size_t dimension) {
      out += text;
      vector(v, dimension);
    };
    for (std::size_t row = first; row < last; ++row) {
      const double* values = block.data() + (row - first) * columns;
      const Status status = table.status(row);
      out += run_row + (row - first) == 0 ? "\n    {\"input\": " : ",\n    {\"input\": ";
      number(values[0]);
      member(", \"input_rate\": ", values[1]);
      member(", \"input_second_rate\": ", values[2]);
      out += ", \"status\": \"";
      out += status_name(status);
      out += '"';
      const std::string message = describe_failure(system, table.input(row), table.failure(row));
      if (!message.empty()) out += ", \"message\": " + quoted(message);
      out += ", \"coordinates\": {";
      const double* v = values + kInputColumns;
      for (std::size_t i = 0; i < system.unknowns.size(); ++i, v += 3) {
        if (status == Status::unassembled) continue;
        if (i > 0) out += ", ";
        out += coordinate_keys[i];
        number(v[0]);
        member(", \"rate\": ", v[1]);
        member(", \"second_rate\": ", v[2]);
        out += '}';
      }
      out += '}';
      if (status != Status::unassembled) {
        member(", \"loop_residual\": ", table.loop_residual(row) / scale.length);
      }
      out += ", \"points\": {";
      for (std::size_t p = 0; p < system.points.size(); ++p) {
        const std::size_t d = system.points[p].components.size();
        if (status == Status::ok) {
          if (p > 0) out += ", ";
          out += point_keys[p];
          vector(v, d);
          member_vector(", \"velocity\": ", v + d, d);
          member(", \"speed\": ", v[2 * d]);
          member_vector(", \"acceleration\": ", v + 2 * d + 1, d);
          member(", \"acceleration_magnitude\": ", v[3 * d + 1]);
          out += '}';
        }
        v += 3 * d + 2;
      }
      out += '}';
      if (!system.frames.empty()) {  // spatial chains: each frame's w and alpha
        out += ", \"frames\": {";
        for (std::size_t f = 0; f < system.frames.size(); ++f, v += 6) {
          if (status != Status::ok) continue;
          out += (f > 0 ? ", " : "") + frame_keys[f];
          vector(v, 3);
          member_vector(", \"angular_acceleration\": ", v + 3, 3);
          out += '}';
        }
        out += '}';
      }
      if (system.linkage && status == Status::ok) {  // joints and links: blocks, then sliders
        out += ", \"blocks\": {";
        for (std::size_t k = 0; k < blocks.size(); ++k, v += 3) {
          out += (k > 0 ? ", " : "") + quoted(system.linkage->links[blocks[k].first - 1].name) + ": {\"angle\": ";
          number(v[0]);
          member(", \"rate\": ", v[1]);
          member(", \"second_rate\": ", v[2]);
          out += '}';
        }
        out += "}, \"sliders\": {";
        const auto& sliders = system.linkage->frames.sliders;
        for (std::size_t k = 0; k < sliders.size(); ++k, v += 6) {
          out += (k > 0 ? ", " : "") + quoted(system.linkage->joints[sliders[k].joint].name) + ": ";
          member_vector("{\"relative_velocity\": ", v, 2);
          member_vector(", \"relative_acceleration\": ", v + 2, 2);
          member_vector(", \"coriolis\": ", v + 4, 2);
          out += '}';
        }
        out += '}';
        if (!guide_keys.empty()) {  // the guide's point under each slider on a moving guide
          out += ", \"guide_points\": {";
          for (std::size_t k = 0; k < guide_keys.size(); ++k, v += 4) {
            out += (k > 0 ? ", " : "") + guide_keys[k];
            vector(v, 2);
            member_vector(", \"acceleration\": ", v + 2, 2);
            out += '}';
          }
          out += '}';
        }
        if (!turning_keys.empty()) {  // each slider block relative to a link it is pinned to
          out += ", \"relative_turnings\": {";
          for (std::size_t k = 0; k < turning_keys.size(); ++k, v += 2) {
            out += (k > 0 ? ", " : "") + turning_keys[k];
            number(v[0]);
            member(", \"second_rate\": ", v[1]);
            out += '}';
          }
          out += '}';
        }
      }
      if (job.circuit && status != Status::unassembled) {  // each dyad's assembly sign, by its inner joint
        const double* signs = values + columns - branch_keys.size();
        out += ", \"branch\": {";
        for (std::size_t k = 0; k < branch_keys.size(); ++k) {
          out += (k > 0 ? ", " : "") + branch_keys[k];
          number(signs[k]);
        }
        out += '}';
      }
      out += '}';
    }
  }

  void tail(std::string& out, const PrintJob&, std::size_t rows) const override {
    out += rows > 0 ? "\n  ]\n}\n" : "]\n}\n";
  }
};

}  // namespace

const ResultsPrinter& json_printer() {
  static const JsonPrinter printer;
  return printer;
}

}  // namespace kinema
