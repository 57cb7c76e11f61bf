#include "engine/printers/web/page.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>
#include <map>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "engine/base/number_format.hpp"
#include "engine/analysis/diagnostics.hpp"
#include "engine/analysis/output_scale.hpp"
#include "engine/analysis/problem_scale.hpp"
#include "engine/base/sha256.hpp"
#include "engine/printers/code/tape_emitter.hpp"
#include "engine/printers/web/mathml.hpp"
#include "engine/printers/web/page_constructions.hpp"

namespace kinema {

namespace {

using json = nlohmann::ordered_json;

// The page's script and style as written in engine/printers/web/ with their SHA-256
// digests (hex), by CMakeLists.txt at configure time.
#include "web_page_assets.inc"

// Coordinates to the drawing's digits: 7 significant are far below a pixel at any zoom
// the page offers and keep a long run's file small. NaN stays NaN (null in JSON).
double drawn(double value) { return std::isfinite(value) ? round_significant(value, 7) : value; }

// A point or a direction (per_unit 1) of the drawing, round-off at `size` (its unit's) as 0.
json point_json(std::complex<double> z, double per_unit, double size) {
  return json::array({drawn(zero_at_scale(z.real() / per_unit, size)), drawn(zero_at_scale(z.imag() / per_unit, size))});
}

// A row's values each written once: the row is [its pattern, its distinct values], the
// pattern (shared by rows, in "row_patterns") giving each place's index among them. A loop
// drawing repeats each vector's ends and its zeros, which are then written once a row.
class RowPatterns {
 public:
  json pack(const std::vector<double>& row) {
    std::vector<std::uint64_t> distinct;  // by bits: -0 and NaN stay what they are
    json values = json::array({0}), pattern = json::array();
    for (const double value : row) {
      std::uint64_t bits;
      std::memcpy(&bits, &value, sizeof bits);
      auto found = std::find(distinct.begin(), distinct.end(), bits);
      if (found == distinct.end() || std::isnan(value)) {
        distinct.push_back(bits);
        values.push_back(value);
        found = distinct.end() - 1;
      }
      pattern.push_back(found - distinct.begin());
    }
    const std::string key = pattern.dump();
    const auto known = index_.emplace(key, list_.size());
    if (known.second) list_.push_back(std::move(pattern));
    values[0] = known.first->second;
    return values;
  }
  const json& list() const { return list_; }

 private:
  json list_ = json::array();
  std::map<std::string, std::size_t> index_;
};

// The drawing's parts that stay from row to row, and each row's coordinates, in the file's
// output length unit (angles stay in rad). Round-off is written 0 (zero_at_scale): a
// length's at the larger of the mechanism's size (`size`, output units) and the largest
// length drawn over the run, a unit direction's or an angle's (rad) at 1.
json drawing_json(const MotionDrawing& drawing, double per_unit, double size) {
  json out = json::object();
  out["form"] = drawing.form == MotionDrawing::Form::linkage ? "linkage"
                : drawing.form == MotionDrawing::Form::loops ? "loops"
                : drawing.form == MotionDrawing::Form::chain ? "chain"
                                                             : "none";
  if (drawing.form == MotionDrawing::Form::linkage) {
    out["joint_names"] = drawing.joint_names;
    out["links"] = json::array();
    for (const auto& link : drawing.links)
      out["links"].push_back({{"name", link.name}, {"joints", link.joints}, {"block", link.block}});
    out["pivots"] = drawing.ground_pivots;
    out["guides"] = json::array();
    for (const auto& guide : drawing.guides)
      out["guides"].push_back({{"through", point_json(guide.through, per_unit, size)}, {"along", point_json(guide.along, 1, 1)}});
  } else if (drawing.form == MotionDrawing::Form::loops) {
    out["segments"] = json::array();
    for (const DrawingSegment& s : drawing.segments) {
      const char* kind = s.kind == DrawingSegment::Kind::ground ? "ground"
                         : s.kind == DrawingSegment::Kind::slider ? "slider"
                                                                  : "link";
      // How a re-solved row lays it out from the tape's link vectors (term, loop_start, ...).
      out["segments"].push_back({{"kind", kind}, {"link", s.link}, {"fixed_guide", s.fixed_guide},
                                 {"guide_link", s.guide_link}, {"block_label", s.block_label}, {"term", s.term},
                                 {"loop_start", s.loop_start}, {"block_at_from", s.block_at_from},
                                 {"guide_from_tape", s.guide_from_tape}, {"pins", {s.pin_at_from, s.pin_at_to}}});
    }
    out["points_on_links"] = json::array();
    for (const PointOnLink& p : drawing.points_on_links)
      out["points_on_links"].push_back({{"point", p.point}, {"link", p.link}, {"vector", p.vector}});
    out["link_labels"] = drawing.link_labels;
    out["letters"] = json::array();
    for (const LetteredCorner& c : drawing.lettered_corners)
      out["letters"].push_back({{"letter", c.letter}, {"segment", c.segment}, {"at_to", c.at_to}});
  } else if (drawing.form == MotionDrawing::Form::chain) {
    out["frames"] = drawing.frame_names;
    out["parents"] = drawing.frame_parents;
    out["ground_frames"] = drawing.bodies.ground_frames;
    out["frame_joints"] = drawing.bodies.joints;
    out["view"] = {{"theta", drawing.view.theta}, {"phi", drawing.view.phi}};
    out["point_frames"] = drawing.bodies.point_frames;
    out["couplers"] = drawing.bodies.couplers;
  }
  // Lengths in the output unit; the loops' unit directions (along) and blocks' angles as they are.
  const std::size_t segment_values = 8 * drawing.segments.size();
  const auto is_length = [&](std::size_t k) {
    const bool direction = drawing.form == MotionDrawing::Form::loops && k < segment_values && k % 8 >= 6;
    const bool angle = (drawing.form == MotionDrawing::Form::linkage && k >= 2 * drawing.joint_names.size()) ||
                       (drawing.form == MotionDrawing::Form::chain && k % 12 >= 3);  // unit axes
    return !direction && !angle;
  };
  double lengths = size;
  for (const std::vector<double>& row : drawing.rows)
    for (std::size_t k = 0; k < row.size(); ++k)
      if (is_length(k)) lengths = std::max(lengths, largest_magnitude({row[k] / per_unit}));
  json rows = json::array();
  RowPatterns patterns;
  for (const std::vector<double>& row : drawing.rows) {
    std::vector<double> values;
    for (std::size_t k = 0; k < row.size(); ++k)
      values.push_back(drawn(is_length(k) ? zero_at_scale(row[k] / per_unit, lengths) : zero_at_scale(row[k], 1)));
    rows.push_back(values.empty() ? json(nullptr) : patterns.pack(values));
  }
  out["row_patterns"] = patterns.list();
  out["rows"] = rows;
  return out;
}

// The CSV fields (as kinema eval --format csv writes them: the status after the input's
// three columns) of a result column.
std::size_t csv_field(std::size_t column) { return column < kInputColumns ? column : column + 1; }

// Where each point's values are among the CSV fields, and which fields the plots show.
json columns_json(const ConstraintSystem& system, const std::vector<ResultColumn>& columns) {
  const ProblemScale problem(system);
  json out = json::object();
  const std::size_t n = system.unknowns.size();
  json rates = json::array(), second_rates = json::array(), speeds = json::array(), points = json::array();
  for (std::size_t k = 0; k < n; ++k) {
    rates.push_back(csv_field(kInputColumns + 3 * k + 1));
    second_rates.push_back(csv_field(kInputColumns + 3 * k + 2));
  }
  std::size_t column = kInputColumns + 3 * n;
  for (const PointObservable& point : system.points) {
    const std::size_t d = point.components.size();
    // Position (d), velocity (d), speed, acceleration (d), its magnitude.
    json p = {{"name", point.name}, {"dimension", d}, {"position", csv_field(column)},
              {"velocity", csv_field(column + d)}, {"speed", csv_field(column + 2 * d)},
              {"acceleration", csv_field(column + 2 * d + 1)}};
    speeds.push_back(csv_field(column + 2 * d));
    points.push_back(p);
    column += 3 * d + 2;
  }
  out["points"] = points;
  // One plot a unit: an angle's rate in rad/s beside a length's in mm/s on one axis leaves
  // the smaller flat. A plot of one unit keeps its plain title.
  json plots = json::array();
  const auto unit_of = [&](const json& field) -> const std::string& {  // csv_field undone
    const std::size_t f = field.get<std::size_t>();
    return columns[f > kInputColumns ? f - 1 : f].unit;
  };
  const auto by_unit = [&](const std::string& title, const json& fields) {
    std::vector<std::string> units;
    for (const json& f : fields)
      if (std::find(units.begin(), units.end(), unit_of(f)) == units.end()) units.push_back(unit_of(f));
    for (const std::string& unit : units) {
      json mine = json::array();
      for (const json& f : fields)
        if (unit_of(f) == unit) mine.push_back(f);
      plots.push_back({{"title", units.size() > 1 ? title + " in " + unit : title}, {"fields", mine}});
    }
    if (units.empty()) plots.push_back({{"title", title}, {"fields", fields}});
  };
  by_unit("rates", rates);
  by_unit("second rates", second_rates);
  by_unit("point speeds", speeds);
  out["plots"] = plots;
  json names = json::array();
  // Each field with the problem's size for its kind: the readout shows it zero at that scale.
  for (std::size_t k = 0; k < columns.size(); ++k) {
    names.push_back({{"name", columns[k].name}, {"unit", columns[k].unit}, {"size", problem.of(columns[k])}});
    if (k + 1 == kInputColumns) names.push_back({{"name", "status"}, {"unit", ""}});
  }
  names.push_back({{"name", "note"}, {"unit", ""}});
  out["fields"] = names;
  return out;
}

// The rows as kinema eval --format csv writes them (the same printer), one string a row.
std::vector<std::string> csv_lines(const PrintJob& job, std::string& header) {
  const ResultsPrinter& csv = *find_results_printer("csv");
  const MotionTable& table = *job.values;
  std::string text;
  csv.head(header, job, table.size());
  if (!header.empty() && header.back() == '\n') header.pop_back();
  csv.rows(text, job, table, 0, table.size(), 0);
  std::vector<std::string> lines;
  std::size_t start = 0;
  for (std::size_t end; (end = text.find('\n', start)) != std::string::npos; start = end + 1)
    lines.push_back(text.substr(start, end - start));
  return lines;
}

// Inside <script type="application/json">: no '<' at all, so no text of the file can end the
// element ("</script>") or open a comment; JSON reads \u003c back as '<'.
std::string script_safe(const std::string& json_text) {
  std::string out;
  out.reserve(json_text.size());
  for (char c : json_text) {
    if (c == '<') out += "\\u003c";
    else out += c;
  }
  return out;
}

// A compiled tape as the page's runner takes it: its instructions six numbers each (op, out,
// a, b, c, exponent), its initial registers (inputs, constants), each stage's end, where each
// input level's instructions begin in it, and its output registers.
json tape_json(const CompiledExpressions& tape) {
  json code = json::array();
  for (const auto& in : tape.instructions()) {
    for (const long long v : {static_cast<long long>(in.op), static_cast<long long>(in.out), static_cast<long long>(in.a),
                              static_cast<long long>(in.b), static_cast<long long>(in.c), static_cast<long long>(in.exponent)})
      code.push_back(v);
  }
  json ends = json::array(), outputs = json::array(), levels = json::array();
  for (std::size_t stage = 0; stage < tape.stage_count(); ++stage) {
    ends.push_back(tape.stage_end(stage));
    json begins = json::array();
    for (int level = 0; level <= tape.levels(); ++level) begins.push_back(tape.level_begin(stage, level));
    levels.push_back(begins);
    json registers = json::array();
    for (std::size_t k = 0; k < tape.stage_output_count(stage); ++k) registers.push_back(tape.output_register(stage, k));
    outputs.push_back(registers);
  }
  return {{"code", code}, {"registers", tape.initial_registers()}, {"stage_end", ends}, {"level_begin", levels},
          {"outputs", outputs}};
}

// Joints and links: where the page finds on the drawing stage each drawn joint (by the
// drawing's joint names), the blocks' angles, the fixed guides and the extra result
// columns, with how each column is written (an angle wrapped to degrees, a length in the
// output unit, or as it is); null for anything else.
json linkage_json(const ConstraintSystem& system, const MotionDrawing& drawing, const TapeLayout& layout) {
  if (!system.plan || layout.linkage_joint_count == 0 || drawing.form != MotionDrawing::Form::linkage) return nullptr;
  json joints = json::array();
  for (const std::string& name : drawing.joint_names) {
    std::size_t j = 0;
    while (j < system.plan->joints.size() && system.plan->joints[j].name != name) ++j;
    if (j == system.plan->joints.size()) return nullptr;
    joints.push_back(layout.linkage_joint_output(j));
  }
  json kinds = json::array();
  for (std::size_t b = 0; b < block_links(system).size(); ++b) kinds.insert(kinds.end(), {"angle", "rate", "rate"});
  for (std::size_t k = 0; k < 6 * system.plan->sliders.size() + 4 * guide_points(system).size(); ++k) kinds.push_back("length");
  for (std::size_t k = 0; k < 2 * relative_turnings(system).size(); ++k) kinds.push_back("rate");
  if (kinds.size() != layout.linkage_column_count) return nullptr;
  return {{"joints", joints}, {"blocks_at", layout.linkage_block_output(0)}, {"block_count", layout.linkage_block_count},
          {"guides_at", layout.linkage_guide_output(0)}, {"guide_count", layout.linkage_guide_count},
          {"columns_at", layout.linkage_column_output(0)}, {"column_kinds", kinds}};
}

// What the page's sliders need to solve again (engine/analysis/resolving.hpp), with the
// rows' inputs (SI) and the output units; null where the page cannot.
json resolving_json(const PrintJob& job, const OutputScale& scale) {
  if (!job.analysis->resolving || job.circuit) return nullptr;
  const Resolving& r = *job.analysis->resolving;
  const ConstraintSystem& system = job.model.system;
  json parameters = json::array();
  for (const Resolving::Parameter& p : r.parameters) {
    json parameter = {{"name", p.name}, {"value", p.value}, {"dimension", dimension_name(p.dimension)},
                      {"slider", p.slider}, {"sets_length_scale", p.sets_length_scale}};
    // A slider's range (SI): where the run assembles somewhere, and everywhere (null: nowhere said).
    if (p.slider && std::isfinite(p.range.min))
      parameter["range"] = {{"min", p.range.min}, {"max", p.range.max}, {"whole_min", p.range.whole_min},
                            {"whole_max", p.range.whole_max}};
    parameters.push_back(parameter);
  }
  json unknowns = json::array();
  for (const Coordinate& q : system.unknowns) unknowns.push_back(dimension_name(q.dimension));
  json inputs = json::array();
  for (std::size_t row = 0; row < job.values->size(); ++row) inputs.push_back(job.values->input(row));
  json constants = json::object();
  for (const auto& [name, value] : r.constants) constants[name] = value;
  const json linkage = linkage_json(system, *job.analysis->motion, r.layout);
  if (system.plan && linkage.is_null()) return nullptr;
  return {{"tape", tape_json(*r.tape)},
          {"parameter_count", r.layout.parameter_count},
          {"point_dimensions", r.layout.point_dimensions},
          {"link_vector_count", r.layout.link_vector_count},
          {"input_level", TapeLayout::kInputLevel},
          {"coordinate_level", TapeLayout::kCoordinateLevel},
          {"vector_outputs", TapeLayout::kVectorOutputs},
          {"vector_position_at", TapeLayout::kVectorPositionAt},
          {"vector_guide_at", TapeLayout::kVectorGuideAt},
          {"parameters", parameters},
          {"formulas", tape_json(r.formulas)},
          {"formula_targets", r.formula_targets},
          {"guess", r.guess},
          {"guess_input", r.guess_input},
          {"periodic_input", r.periodic_input},
          {"unknowns", unknowns},
          {"length_unknowns", r.length_unknowns},
          {"rate", r.rate},
          {"second_rate", r.second_rate},
          {"max_step", r.max_step},
          {"max_step_follows_length", r.max_step_follows_length},
          {"constants", constants},
          {"inputs", inputs},
          {"input_dimension", dimension_name(system.input.dimension)},
          {"length_per_unit", scale.length},
          {"length_unit", scale.length_unit},
          {"linkage", linkage},
          {"frame_count", r.layout.frame_count},
          {"frames_at", r.layout.frame_placement_output(0)},
          {"frame_outputs", TapeLayout::kFramePlacementOutputs}};
}

}  // namespace

std::string base64_of_hex(const std::string& hex) {
  static const char* const digits = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::vector<unsigned char> bytes;
  for (std::size_t i = 0; i + 1 < hex.size(); i += 2) bytes.push_back(static_cast<unsigned char>(std::stoi(hex.substr(i, 2), nullptr, 16)));
  std::string out;
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    const unsigned value = (bytes[i] << 16) | (i + 1 < bytes.size() ? bytes[i + 1] << 8 : 0) | (i + 2 < bytes.size() ? bytes[i + 2] : 0);
    out += digits[(value >> 18) & 63];
    out += digits[(value >> 12) & 63];
    out += i + 1 < bytes.size() ? digits[(value >> 6) & 63] : '=';
    out += i + 2 < bytes.size() ? digits[value & 63] : '=';
  }
  return out;
}

void write_page(std::ostream& out, const PrintJob& job) {
  if (!job.analysis || !job.analysis->motion)
    throw std::logic_error("write_page: the job's analysis holds no motion (analyse it with ViewNeeds::motion)");
  const MotionDrawing& drawing = *job.analysis->motion;
  const ConstraintSystem& system = job.model.system;
  const MotionTable& table = *job.values;
  const OutputScale scale(system);
  const std::vector<ResultColumn> columns = result_columns(system, scale, job.circuit);
  json data = json::object();
  data["title"] = system.title;
  data["description"] = system.description;
  data["file"] = system.source_file;
  data["input"] = {{"name", columns[0].name}, {"unit", columns[0].unit}};
  data["length_unit"] = scale.length_unit;
  data["circuit"] = job.circuit;
  data["spatial"] = !system.frames.empty();
  data["columns"] = columns_json(system, columns);
  std::string header;
  data["rows"] = csv_lines(job, header);
  data["header"] = header;
  json reasons = json::array();
  for (std::size_t r = 0; r < table.size(); ++r)
    reasons.push_back(table.status(r) == Status::ok ? std::string() : describe_failure(system, table.input(r), table.failure(r)));
  data["reasons"] = reasons;
  const double size = ProblemScale(system).of(Dimension::length, 0);  // output units
  data["drawing"] = drawing_json(drawing, scale.length, size);
  PointFields point_fields;
  for (const auto& point : data["columns"]["points"])
    if (point["dimension"] == 2) point_fields[point["name"]] = {point["velocity"], point["acceleration"]};
  json resolve = resolving_json(job, scale);
  // A page that solves again finds the centres of its rows from the drawing stage's outputs.
  const TapeLayout* centre_tape = resolve.is_null() ? nullptr : &job.analysis->resolving->layout;
  data["constructions"] = constructions_json(job.analysis->values, drawing, scale.length, point_fields, centre_tape, size * scale.length);
  // The readout's zero at the problem's scale: the fraction of a field's scale below which
  // a value is shown as 0 (zero_at_scale's, engine/base/number_format).
  data["round_off"] = kRoundOffFraction;
  data["resolve"] = std::move(resolve);

  // The derivation as the notes print it, in MathML (markup of kinema's own, every text escaped).
  std::ostringstream latex;
  find_printer(PrintKind::derivation, "latex")->print(latex, job);
  std::string derivation;
  try {
    derivation = mathml_of_latex(latex.str());
  } catch (const MathmlError&) {
    // A formula whose LaTeX the page does not read yet: the page says so, and where to read it.
    derivation = "<p>This derivation uses LaTeX the page does not show yet: <code>kinema derive FILE --format latex</code> prints it.</p>\n";
  }

  // The script: the tape's runner generated from the op table, then page.js.
  std::ostringstream runner;
  write_tape_runner_js(runner);
  const std::string script = runner.str() + kPageScript;
  const std::string script_hash = base64_of_hex(sha256_hex(script)), style_hash = base64_of_hex(sha256_hex(kPageStyle));
  // Nothing but the page's own script and style runs or loads: no fetch, no frame, no form.
  out << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
      << "<meta http-equiv=\"Content-Security-Policy\" content=\"default-src 'none'; script-src 'sha256-" << script_hash
      << "'; style-src 'sha256-" << style_hash << "'; img-src data:; base-uri 'none'; form-action 'none'\">\n"
      << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
      << "<title>kinema page</title>\n<style>" << kPageStyle << "</style>\n</head>\n<body>\n"
      << "<details id=\"derivation\"><summary>The derivation (as kinema derive --format latex prints it)</summary>\n"
      << derivation << "</details>\n"
      << "<script type=\"application/json\" id=\"kinema-data\">" << script_safe(data.dump(-1, ' ', false, json::error_handler_t::replace))
      << "</script>\n<script>" << script << "</script>\n</body>\n</html>\n";
}

}  // namespace kinema
