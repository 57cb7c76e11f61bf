// Every output format is a printer over the same results: the model (its
// constraint system and derivation), for the formats that show numbers the solved
// values, and what the analysis worked out for the view (engine/analysis/analysis.hpp:
// design figures, polygons, ...). A printer only formats: it says what it needs
// (Printer::needs), the caller computes that once (analyse_for_views) and passes it in.
// The command line finds a printer by its kind and name.
#pragma once

#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "engine/analysis/analysis.hpp"
#include "engine/analysis/sensitivities.hpp"
#include "engine/model.hpp"
#include "engine/problems/problem_answer.hpp"
#include "engine/symbolic/dyad_derivation_types.hpp"

namespace kinema {

/// What a printer prints from.
struct PrintJob {
  PrintJob(const Model& printed, const MotionTable* at_values = nullptr, const MotionTable* over_range = nullptr)
      : model(printed), values(at_values), sweep(over_range) {}
  const Model& model;
  const MotionTable* values = nullptr;  ///< Results at the requested input values.
  const MotionTable* sweep = nullptr;   ///< A run over the input's range (plots).
  /// What the printer's needs() asked for, computed by analyse_for_views (engine/run/view.hpp
  /// does both); required by a printer whose needs() asks for anything.
  const Analysis* analysis = nullptr;
  bool fragment = false;                ///< Documents: no preamble, for \input into notes.
  int precision = 0;                    ///< Results: significant digits in text formats (0: the format's default).
  bool circuit = false;                 ///< Results: rows along a circuit (a direction and dyad signs each).
  /// Results: derivative columns printed after the result columns (kinema eval
  /// --sensitivity), their values in the tables' derived columns (Sensitivities::fill).
  const std::vector<SensitivityColumn>* sensitivities = nullptr;
  /// Derivations and documents: the loops' equations, or the seeds' methods dyad by dyad
  /// (joints and links; engine/symbolic/dyad_method).
  DerivationMethod method = DerivationMethod::loops;
  std::string code_namespace;           ///< Code: the namespace of the generated code.
  /// Derivations and documents of a spatial chain: the frame whose axes vectors are given
  /// along (empty: the observer's).
  std::string basis;
  /// Documents: a problem's asked answers, boxed in a section of their own (a key of kinema problems).
  const std::vector<ProblemAnswer>* answers = nullptr;
};

/// What a printer shows.
enum class PrintKind {
  derivation,  ///< The symbolic derivation (kinema derive).
  results,     ///< Numbers at input values (kinema eval).
  document,    ///< A worked solution (kinema latex).
  code,        ///< Exported code (kinema codegen).
};

class Printer {
 public:
  virtual ~Printer() = default;
  virtual PrintKind kind() const = 0;
  virtual const char* name() const = 0;  ///< As --format takes it: "csv".
  virtual void print(std::ostream& out, const PrintJob& job) const = 0;
  /// What printing `job` shows beyond the results (none by default): analyse_for_views
  /// computes it into job.analysis before print.
  virtual ViewNeeds needs(const PrintJob& job) const;
};

/// What a derivation shows of job beyond the model's: the relations dyad by dyad in
/// job.method (where `by_dyads`: the printer shows them for this system) and a driven
/// chain worked out at the instant in job.basis.
ViewNeeds derivation_needs(const PrintJob& job, bool by_dyads);

/// job.analysis; std::logic_error when a printer that needs one was given none.
const Analysis& analysis_of(const PrintJob& job);

/// A results format printed a block of rows at a time, so that a long run streams
/// (engine/run/results_stream.hpp): head, the rows of each block in order, tail.
/// print() is the three over the whole of job.values, so a streamed run and a
/// printed table give the same bytes.
class ResultsPrinter : public Printer {
 public:
  PrintKind kind() const final { return PrintKind::results; }
  void print(std::ostream& out, const PrintJob& job) const final;
  /// What comes before the first row of a run of `rows` values.
  virtual void head(std::string& out, const PrintJob& job, std::size_t rows) const = 0;
  /// Rows [first, last) of table, the first being value `run_row` of the run.
  virtual void rows(std::string& out, const PrintJob& job, const MotionTable& table, std::size_t first,
                    std::size_t last, std::size_t run_row) const = 0;
  /// What comes after the last row of a run of `rows` values.
  virtual void tail(std::string& out, const PrintJob& job, std::size_t rows) const = 0;
};

/// The columns a results printer prints: result_columns, then the job's sensitivity columns.
std::vector<ResultColumn> printed_columns(const PrintJob& job);
std::size_t printed_column_count(const PrintJob& job);
/// Rows [first, last) of table in the order of printed_columns, one row after the other:
/// result_rows' values, then the table's derived columns (the sensitivities, filled before).
void printed_rows(const PrintJob& job, const MotionTable& table, std::size_t first, std::size_t last, double* values);

/// The printer of that kind and name, or nullptr.
const Printer* find_printer(PrintKind kind, std::string_view name);
/// The results printer of that name, or nullptr.
const ResultsPrinter* find_results_printer(std::string_view name);
/// Names of the printers of a kind, in a stable order (for --help and messages).
std::vector<std::string> printer_names(PrintKind kind);

}  // namespace kinema
