// `kinema check`: a student's answers compared with the mechanism's (a file's own
// dimensions, or a class table's variant), each right or wrong within a tolerance, and for
// a wrong one the mistakes of the catalogue (engine/problems/mistake_catalogue.hpp) that
// reproduce it. The printers (engine/printers/check_report.hpp) only format the report.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "engine/model.hpp"
#include "engine/problems/answer_verdicts.hpp"
#include "readers/answers_file.hpp"
#include "readers/class_table.hpp"

namespace kinema {

/// What answers are checked against: a model and the driver's rates (SI) with the rate as
/// written, and for a class variant the answers its key asks for (their input values stand
/// for an answer written without one).
struct CheckSubject {
  const Model* model = nullptr;
  std::string source;  ///< The mechanism file.
  std::optional<long> variant;
  double rate = 0.0, second_rate = 0.0;
  std::string rate_text;
  std::vector<ClassAnswer> asked;
};

/// A mechanism file's own dimensions and driver.
CheckSubject file_subject(const Model& model);

/// A class variant: the source model with the variant's parameters (with_parameters: no
/// new derivation). A parameter named as the driver's rate or second rate ("omega2",
/// "alpha2") sets that rate instead. InputError naming the class table for a parameter
/// the source file does not write.
Model variant_model(const Model& source, const ClassTable& table, const ClassVariant& variant);
/// The subject of a variant whose model variant_model made (`model` must outlive it).
CheckSubject variant_subject(const Model& model, const ClassTable& table, const ClassVariant& variant);

/// The quantity an answer names: a result column ("omega3", "P_vx", "B_coriolis_x"), or vP
/// and aP for a point P's speed and acceleration magnitude; InputError at `where` naming
/// the quantity and listing those of the mechanism for any other.
std::string answer_column(const ConstraintSystem& system, const std::string& quantity, const SourceLocation& where);

/// Each answer checked: its value read in its unit (the column's output unit when it has
/// none), compared at its input value within the tolerance, and a wrong one's mistakes
/// found. InputError with file:line for a bad answer; AssemblyError or
/// SingularPositionError where the mechanism has no rates at an answer's input value.
CheckReport check_answers(const CheckSubject& subject, const AnswersFile& answers, const AnswerTolerance& tolerance);

}  // namespace kinema
