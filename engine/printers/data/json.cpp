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

// One block's rows as JSON objects, the keys built once: the members of a row in order
// (input, status, coordinates, points, frames, a linkage's blocks and sliders, a circuit's
// branch), each number so that it reads back exactly (or to --precision digits), never NaN.
class JsonRowWriter {
 public:
  JsonRowWriter(std::string& out, const PrintJob& job) : out_(out), job_(job), system_(job.model.system) {
    for (const Coordinate& q : system_.unknowns) coordinate_keys_.push_back(quoted(q.name) + ": {\"value\": ");
    for (const PointObservable& p : system_.points) point_keys_.push_back(quoted(p.name) + ": {\"position\": ");
    for (const FrameObservable& f : system_.frames) frame_keys_.push_back(quoted(f.name) + ": {\"angular_velocity\": ");
    blocks_ = block_links(system_);  // joints and links: once, not per row
    for (const GuidePoint& g : guide_points(system_)) {
      const SolvingPlan::Slider& slider = system_.plan->sliders[g.slider];
      guide_keys_.push_back(quoted(g.name) + ": {\"slider\": " + quoted(system_.plan->joints[slider.joint].name) +
                            ", \"link\": " + quoted(system_.plan->links[slider.guide - 1].name) + ", \"velocity\": ");
    }
    for (const RelativeTurning& r : relative_turnings(system_)) {
      turning_keys_.push_back(quoted(r.rate_name) + ": {\"links\": [" + quoted(system_.plan->links[r.block - 1].name) +
                              ", " + quoted(system_.plan->links[r.other - 1].name) + "], \"joint\": " +
                              quoted(system_.plan->joints[r.joint].name) + ", \"second_rate_name\": " +
                              quoted(r.second_rate_name) + ", \"rate\": ");
    }
    if (job.circuit)
      for (const std::string& joint : dyad_inner_joints(system_)) branch_keys_.push_back(quoted(joint) + ": ");
    if (job.sensitivities)
      for (const SensitivityColumn& c : *job.sensitivities) sensitivity_keys_.push_back(quoted(c.named.name) + ": ");
  }

  /// The row's "sensitivities" member: each column asked for (null where undefined).
  void sensitivities(const double* values) {
    out_ += ", \"sensitivities\": {";
    for (std::size_t k = 0; k < sensitivity_keys_.size(); ++k) {
      if (k > 0) out_ += ", ";
      out_ += sensitivity_keys_[k];
      number(values[k]);
    }
    out_ += '}';
  }

  /// A row's members after its "input" key: `values` are its result columns.
  void row(const MotionTable& table, std::size_t row, const double* values, std::size_t columns, const OutputScale& scale) {
    const Status status = table.status(row);
    number(values[0]);
    member(", \"input_rate\": ", values[1]);
    member(", \"input_second_rate\": ", values[2]);
    out_ += ", \"status\": \"";
    out_ += status_name(status);
    out_ += '"';
    const std::string message = describe_failure(system_, table.input(row), table.failure(row));
    if (!message.empty()) out_ += ", \"message\": " + quoted(message);
    const double* v = coordinates(values + kInputColumns, status);
    if (status != Status::unassembled) member(", \"loop_residual\": ", table.loop_residual(row) / scale.length);
    v = points(v, status);
    if (!system_.frames.empty()) v = frames(v, status);
    if (system_.plan && status == Status::ok) linkage(v);
    if (job_.circuit && status != Status::unassembled) branch(values + columns - branch_keys_.size());
  }

 private:
  std::string& out_;
  const PrintJob& job_;
  const ConstraintSystem& system_;
  std::vector<std::string> coordinate_keys_, point_keys_, frame_keys_, guide_keys_, turning_keys_, branch_keys_,
      sensitivity_keys_;
  std::vector<std::pair<std::size_t, std::string>> blocks_;
  char buffer_[kMaxNumberChars];

  void number(double value) {
    if (!std::isfinite(value)) {
      out_ += "null";
      return;
    }
    if (job_.precision > 0) value = round_significant(value, job_.precision);
    out_.append(buffer_, put_shortest(buffer_, value));
  }
  void vector(const double* v, std::size_t dimension) {
    out_ += '[';
    for (std::size_t c = 0; c < dimension; ++c) {
      if (c > 0) out_ += ", ";
      number(v[c]);
    }
    out_ += ']';
  }
  // `text` (separator and key) then a number or a vector.
  void member(const char* text, double value) {
    out_ += text;
    number(value);
  }
  void member_vector(const char* text, const double* v, std::size_t dimension) {
    out_ += text;
    vector(v, dimension);
  }

  const double* coordinates(const double* v, Status status) {
    out_ += ", \"coordinates\": {";
    for (std::size_t i = 0; i < system_.unknowns.size(); ++i, v += 3) {
      if (status == Status::unassembled) continue;
      if (i > 0) out_ += ", ";
      out_ += coordinate_keys_[i];
      number(v[0]);
      member(", \"rate\": ", v[1]);
      member(", \"second_rate\": ", v[2]);
      out_ += '}';
    }
    out_ += '}';
    return v;
  }

  const double* points(const double* v, Status status) {
    out_ += ", \"points\": {";
    for (std::size_t p = 0; p < system_.points.size(); ++p) {
      const std::size_t d = system_.points[p].components.size();
      if (status == Status::ok) {
        if (p > 0) out_ += ", ";
        out_ += point_keys_[p];
        vector(v, d);
        member_vector(", \"velocity\": ", v + d, d);
        member(", \"speed\": ", v[2 * d]);
        member_vector(", \"acceleration\": ", v + 2 * d + 1, d);
        member(", \"acceleration_magnitude\": ", v[3 * d + 1]);
        out_ += '}';
      }
      v += 3 * d + 2;
    }
    out_ += '}';
    return v;
  }

  // Spatial chains: each frame's w and alpha.
  const double* frames(const double* v, Status status) {
    out_ += ", \"frames\": {";
    for (std::size_t f = 0; f < system_.frames.size(); ++f, v += 6) {
      if (status != Status::ok) continue;
      out_ += (f > 0 ? ", " : "") + frame_keys_[f];
      vector(v, 3);
      member_vector(", \"angular_acceleration\": ", v + 3, 3);
      out_ += '}';
    }
    out_ += '}';
    return v;
  }

  // Joints and links: blocks, then sliders, then the guides' points and the relative turnings.
  void linkage(const double* v) {
    out_ += ", \"blocks\": {";
    for (std::size_t k = 0; k < blocks_.size(); ++k, v += 3) {
      out_ += (k > 0 ? ", " : "") + quoted(system_.plan->links[blocks_[k].first - 1].name) + ": {\"angle\": ";
      number(v[0]);
      member(", \"rate\": ", v[1]);
      member(", \"second_rate\": ", v[2]);
      out_ += '}';
    }
    out_ += "}, \"sliders\": {";
    const auto& sliders = system_.plan->sliders;
    for (std::size_t k = 0; k < sliders.size(); ++k, v += 6) {
      out_ += (k > 0 ? ", " : "") + quoted(system_.plan->joints[sliders[k].joint].name) + ": ";
      member_vector("{\"relative_velocity\": ", v, 2);
      member_vector(", \"relative_acceleration\": ", v + 2, 2);
      member_vector(", \"coriolis\": ", v + 4, 2);
      out_ += '}';
    }
    out_ += '}';
    if (!guide_keys_.empty()) {  // the guide's point under each slider on a moving guide
      out_ += ", \"guide_points\": {";
      for (std::size_t k = 0; k < guide_keys_.size(); ++k, v += 4) {
        out_ += (k > 0 ? ", " : "") + guide_keys_[k];
        vector(v, 2);
        member_vector(", \"acceleration\": ", v + 2, 2);
        out_ += '}';
      }
      out_ += '}';
    }
    if (!turning_keys_.empty()) {  // each slider block relative to a link it is pinned to
      out_ += ", \"relative_turnings\": {";
      for (std::size_t k = 0; k < turning_keys_.size(); ++k, v += 2) {
        out_ += (k > 0 ? ", " : "") + turning_keys_[k];
        number(v[0]);
        member(", \"second_rate\": ", v[1]);
        out_ += '}';
      }
      out_ += '}';
    }
  }

  // Each dyad's assembly sign along a circuit, by its inner joint.
  void branch(const double* signs) {
    out_ += ", \"branch\": {";
    for (std::size_t k = 0; k < branch_keys_.size(); ++k) {
      out_ += (k > 0 ? ", " : "") + branch_keys_[k];
      number(signs[k]);
    }
    out_ += '}';
  }
};

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
        // Every limit position; a time ratio only between two (null otherwise).
        list.push_back({{"coordinate", s.name},
                        {"limit_inputs", s.limit_inputs},
                        {"limit_values", s.limit_values},
                        {"strokes", s.strokes},
                        {"time_ratio", std::isfinite(s.time_ratio) ? json(s.time_ratio) : json(nullptr)}});
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
    if (job.sensitivities) {  // --sensitivity: each row's "sensitivities" by these names
      json list = json::array();
      for (const SensitivityColumn& c : *job.sensitivities) list.push_back({{"name", c.named.name}, {"unit", c.named.unit}});
      doc["sensitivities"] = list;
    }
    std::string text = doc.dump(2);  // ends with "\n}": the results go before it
    text.resize(text.size() - 2);
    out += text + ",\n  \"results\": [";
  }

  void rows(std::string& out, const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last,
            std::size_t run_row) const override {
    const ConstraintSystem& system = job.model.system;
    const OutputScale scale(system);
    // The block's values at once (worked out column by column), then row by row: the
    // result columns, then the sensitivities asked for.
    const std::size_t columns = result_column_count(system, job.circuit), width = printed_column_count(job);
    std::vector<double> block((last - first) * width);
    printed_rows(job, table, first, last, block.data());
    JsonRowWriter writer(out, job);
    for (std::size_t row = first; row < last; ++row) {
      out += run_row + (row - first) == 0 ? "\n    {\"input\": " : ",\n    {\"input\": ";
      const double* values = block.data() + (row - first) * width;
      writer.row(table, row, values, columns, scale);
      if (job.sensitivities) writer.sensitivities(values + columns);
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
