// `kinema check`'s report, for people (each answer: given, expected, right or wrong, the
// likely mistake in words) and for a grader (JSON). Formats only: the checking is
// engine/problems/answer_check's.
#pragma once

#include <string>

#include "engine/problems/answer_verdicts.hpp"

namespace kinema {

/// One line per answer and a count of right ones.
std::string check_report_text(const CheckReport& report);

/// One JSON object: the subject, the tolerance, each answer with its verdict and the
/// matching mistakes (the first is "mistake", null when none or the answer is right), and
/// the counts. Numbers round-trip.
std::string check_report_json(const CheckReport& report);

}  // namespace kinema
