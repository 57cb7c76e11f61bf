// Design studies (issue 36): many designs of one mechanism, each a set of values of
// parameters the file writes, solved over one run of input values and summed up per design
// in figures (Grashof class, least transmission angle, time ratio, largest rates and point
// speeds and accelerations, whether every value assembles). Nothing is derived or compiled
// per design: every design runs on the model's one compiled tape, whose inputs the
// parameters are (only the work on them alone is rerun), its values solved as
// solve_motion(with_parameters(model, design), inputs) solves them, on several threads, 32
// designs at a time in the lanes of the batch tape where the input has a rate
// (engine/numeric/design_lanes: the values a lane cannot solve as the scalar solver
// would go to it).
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "engine/analysis/design_figures.hpp"
#include "engine/model.hpp"

namespace kinema {

/// The designs of a study: the parameters varied (names the file writes) and their SI
/// values; design i gives names[k] the value values[k][i]. Parameters written as formulas
/// of the varied ones follow them, as with_parameters has them follow.
struct Designs {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;
  std::size_t size() const { return values.empty() ? 0 : values.front().size(); }
};

/// Most designs in a study, and most values a study solves in all (designs times the run's
/// values): each design's values of every parameter are held, and a study is solved before
/// its table is written, so a typo's 10^8 designs are refused before anything is held.
constexpr std::size_t kMaxStudyDesigns = 1'000'000;
constexpr std::size_t kMaxStudyValues = 100'000'000;

/// InputError unless `designs` designs over `values` values each are within the bounds
/// above (the caller's words: "--vary", "study").
void check_study_size(std::size_t designs, std::size_t values, const std::string& asked);

/// The number of combinations of axes of these sizes; InputError (naming the sizes) for
/// more than kMaxStudyDesigns, so that a caller can refuse a grid before copying its axes.
std::size_t design_grid_size(const std::vector<std::size_t>& sizes);

/// Every combination of the axes' values (axes[k] for names[k]), the first name varying
/// slowest; InputError for more than kMaxStudyDesigns of them.
Designs design_grid(const std::vector<std::string>& names, const std::vector<std::vector<double>>& axes);

/// The figures a study can compute (StudyOptions::figures asks for a set of them).
enum class StudyFigure : unsigned {
  grashof,                 ///< Four-bars: the class four_bar_figures gives (none for other mechanisms).
  min_transmission_angle,  ///< Four-bars: the least transmission angle over the run (rad).
  time_ratio,              ///< A crank's turn: the strokes' time ratio (set_strokes) of a four-bar's rocker or a slider.
  assembles,               ///< Whether every value assembles, and how many do not.
  max_rates,               ///< Each unknown's largest |rate|.
  max_second_rates,        ///< Each unknown's largest |second rate|.
  max_speeds,              ///< Each point's largest speed.
  max_accelerations,       ///< Each point's largest acceleration magnitude.
  kCount
};
constexpr unsigned study_figure_bit(StudyFigure figure) { return 1u << static_cast<unsigned>(figure); }
constexpr unsigned kAllStudyFigures = (1u << static_cast<unsigned>(StudyFigure::kCount)) - 1;

struct StudyOptions {
  unsigned figures = kAllStudyFigures;  ///< study_figure_bit of each figure wanted.
  unsigned threads = 1;                 ///< Designs are shared out among this many threads.
  /// Designs solved kLanes at a time, one to a lane of the batch tape (engine/numeric/
  /// design_lanes), where the input has a rate; else each alone. The same numbers to rounding.
  bool across_designs = true;
  /// Asked by each thread before it takes the next designs (32 at most, a lane's worth):
  /// true stops the study, which throws Cancelled once every thread has finished the
  /// designs in its hands; an exception it throws stops the study the same way and comes
  /// out of run_design_study. Called from every thread at once: it must be thread-safe.
  std::function<bool()> cancelled;
  bool wants(StudyFigure figure) const { return (figures & study_figure_bit(figure)) != 0; }
};

/// One element per design of each figure asked for (empty vectors for the others), in SI.
/// NaN where a figure is not defined for a design: a mechanism that is not a four-bar (no
/// class, no transmission angle), no full turn of a crank or no unknown with exactly two
/// limit positions over it (no time ratio), no assembled value (no largest rates).
struct StudyResults {
  std::vector<GrashofClass> grashof;
  std::vector<double> min_transmission_angle;
  std::vector<double> time_ratio;
  std::vector<std::uint8_t> assembles;     ///< 1 where every value of the run assembled.
  std::vector<std::uint32_t> failed_values; ///< Values of the run that did not assemble.
  std::vector<std::vector<double>> max_rate, max_second_rate;   ///< [unknown][design]
  std::vector<std::vector<double>> max_speed, max_acceleration; ///< [point][design]
  std::uint64_t lane_values = 0;  ///< Values solved in lanes across designs (the rest one by one): a diagnostic.
};

/// The figures of every design over the input values `inputs` (SI), each value solved as
/// solve_motion(with_parameters(model, design), inputs) solves it. The largest rates and point
/// figures are over the values whose status is ok; the least transmission angle over those
/// that assemble (as four_bar_figures has it); the time ratio from the rows of the first
/// turn of the run (a crank's run of at least 360 deg), each limit position refined as
/// find_limit_positions refines it: of a four-bar's rocker, else of the first slider
/// coordinate with exactly two (slider_strokes' first). InputError (before anything is
/// solved) for a name the file does not write (naming the file's parameters; one kinema
/// made is said to be), a name given twice, lists of different lengths, or a value that is not
/// finite.
StudyResults run_design_study(const Model& model, const Designs& designs, const std::vector<double>& inputs,
                              const StudyOptions& options = {});

/// A study as a table for the views (the command line's CSV, JSON and npy, the Python
/// module's array): a column per varied parameter, then per figure asked for, a value per
/// design. Names follow the sweep's npy fields: "grashof", "min_transmission_angle",
/// "time_ratio", "assembles", "failed_values", "max_abs_" and an unknown's rate or second
/// rate column ("max_abs_omega3", "max_abs_alpha3"), "max_" and a point's speed or
/// acceleration column ("max_P_speed", "max_P_acceleration").
struct StudyColumn {
  enum class Kind { real, grashof, flag, count } kind = Kind::real;  ///< grashof: GrashofClass codes; flag: 0 or 1
  std::string name, unit;     ///< unit empty for none
  std::vector<double> values;
};
/// The figure fields study_columns can give for this system (after the parameters), in
/// order, each with the figure that makes it.
std::vector<std::pair<std::string, StudyFigure>> study_figure_fields(const ConstraintSystem& system);

enum class StudyUnits { file, si };  ///< The file's output units (lengths in its unit, angles in deg), or SI.
std::vector<StudyColumn> study_columns(const ConstraintSystem& system, const Designs& designs,
                                       const StudyResults& results, StudyUnits units);

}  // namespace kinema
