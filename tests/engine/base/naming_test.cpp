// engine/symbolic/naming: printed names of rates, LaTeX spellings of names,
// and the check of LaTeX names written in mechanism files.
#include <doctest/doctest.h>

#include <string>

#include "engine/base/errors.hpp"
#include "engine/base/naming.hpp"

using kinema::check_latex_name;
using kinema::default_rate_name;
using kinema::latex_symbol_name;

TEST_CASE("engine/symbolic/naming: default_rate_name") {
  // Angles named theta/phi: omega and alpha with the same subscript.
  CHECK(default_rate_name("theta3", 1) == "omega3");
  CHECK(default_rate_name("theta3", 2) == "alpha3");
  CHECK(default_rate_name("phi2", 1) == "omega2");
  CHECK(default_rate_name("phi2", 2) == "alpha2");
  CHECK(default_rate_name("thetaB", 1) == "omegaB");
  CHECK(default_rate_name("theta_in", 2) == "alpha_in");
  // Other coordinates: _dot and _ddot.
  CHECK(default_rate_name("r1", 1) == "r1_dot");
  CHECK(default_rate_name("r1", 2) == "r1_ddot");
  CHECK(default_rate_name("x", 1) == "x_dot");
  CHECK(default_rate_name("yF", 2) == "yF_ddot");
  CHECK(default_rate_name("alpha", 1) == "alpha_dot");
  // Only a prefix counts: a name that merely contains theta is not an angle by name.
  CHECK(default_rate_name("xtheta", 1) == "xtheta_dot");
  // A bare theta or phi has no subscript to carry over: it keeps its own name.
  CHECK(default_rate_name("theta", 1) == "theta_dot");
  CHECK(default_rate_name("phi", 2) == "phi_ddot");
}

TEST_CASE("engine/symbolic/naming: latex_symbol_name") {
  // Greek letters with subscripts; the longest Greek word wins (theta, not eta).
  CHECK(latex_symbol_name("theta3") == "\\theta_{3}");
  CHECK(latex_symbol_name("eta2") == "\\eta_{2}");
  CHECK(latex_symbol_name("phi") == "\\phi");
  CHECK(latex_symbol_name("varphi2") == "\\varphi_{2}");
  CHECK(latex_symbol_name("Omega") == "\\Omega");
  CHECK(latex_symbol_name("beta") == "\\beta");
  CHECK(latex_symbol_name("alpha1") == "\\alpha_{1}");
  CHECK(latex_symbol_name("omegaB") == "\\omega_{B}");
  // One letter and a short subscript; segments in capitals; longer words upright-italic.
  CHECK(latex_symbol_name("x") == "x");
  CHECK(latex_symbol_name("r1") == "r_{1}");
  CHECK(latex_symbol_name("La") == "L_{a}");
  CHECK(latex_symbol_name("yF") == "y_{F}");
  CHECK(latex_symbol_name("AB") == "\\mathit{AB}");
  CHECK(latex_symbol_name("CD2") == "\\mathit{CD2}");
  CHECK(latex_symbol_name("length") == "\\mathit{length}");
  // Dots go on the letter, not on the subscript.
  CHECK(latex_symbol_name("x_dot") == "\\dot{x}");
  CHECK(latex_symbol_name("x_ddot") == "\\ddot{x}");
  CHECK(latex_symbol_name("theta3_dot") == "\\dot{\\theta}_{3}");
  CHECK(latex_symbol_name("yF_ddot") == "\\ddot{y}_{F}");
  // A qualifier after an underscore joins the subscript, upright.
  CHECK(latex_symbol_name("theta2_given") == "\\theta_{2,\\mathrm{given}}");
  CHECK(latex_symbol_name("x_in") == "x_{\\mathrm{in}}");
  CHECK(latex_symbol_name("r_max_stroke") == "r_{\\mathrm{max stroke}}");
  // Whatever the name, the result passes the check applied to names from files.
  for (const char* name : {"theta3", "r1_dot", "theta2_given", "AB", "x_in", "length", "yF_ddot"}) {
    CAPTURE(name);
    CHECK_NOTHROW(check_latex_name(latex_symbol_name(name), "generated"));
  }
}

TEST_CASE("engine/symbolic/naming: check_latex_name allows names, refuses commands and specials") {
  for (const char* good : {"\\varphi_{2}", "\\dot{s}'", "\\hat{x}_1", "\\mathrm{AB}", "r_{1,\\mathit{out}}",
                           "\\ddot{\\theta}_{3}", "L a", "\\vec{r}", "q", "x'", "x''_{1}", "x_1'", "\\theta_3'",
                           "{x}_{1,\\mathrm{out}}", "\\vec{r}_\\alpha", "\\hat {x}", "{{{{{{{{x}}}}}}}}"}) {
    CAPTURE(good);
    CHECK_NOTHROW(check_latex_name(good, "here"));
  }
  struct Bad {
    const char* latex;
    const char* named;  // what the message must point at
  };
  for (const Bad& bad : {Bad{"\\input{/etc/passwd}", "\\input"}, Bad{"\\def\\x{1}", "\\def"},
                         Bad{"\\textbf{x}", "\\textbf"}, Bad{"\\\\", "\\"}, Bad{"x$y", "\"$\""},
                         Bad{"50%", "\"%\""}, Bad{"a&b", "\"&\""}, Bad{"#1", "\"#\""}, Bad{"x~y", "\"~\""},
                         Bad{"x^{2}", "\"^\""}, Bad{"^^5cinput", "\"^\""},
                         // Audit 2026-11-24: names the old check passed and pdflatex stopped on, and
                         // commands beyond math typesetting; each message says what to write.
                         Bad{"x_", "write x_{1}"}, Bad{"\\hat", "write \\hat{x}"}, Bad{"\\hat x", "write \\hat{x}"},
                         Bad{"x_1_2", "x_{1,2}"}, Bad{"x__1", "x_{1,2}"}, Bad{"x'_1'", "x''_{1}"},
                         Bad{"_1", "nothing before"}, Bad{"'x", "nothing before"}, Bad{"x\\", "\\"},
                         Bad{"x_\\hat{y}", "x_{\\hat{y}}"}, Bad{"x_,", "x_{1}"}, Bad{" ", "nothing to typeset"},
                         Bad{"{{{{{{{{{x}}}}}}}}}", "8 deep"}, Bad{"\\alphax", "uses \\alphax; only Greek"},
                         Bad{"\\csname", "uses \\csname; only Greek"}, Bad{"\\catcode", "uses \\catcode; only Greek"},
                         Bad{"\\immediate", "uses \\immediate; only Greek"}, Bad{"\\openout", "uses \\openout; only Greek"},
                         Bad{"\\write", "uses \\write; only Greek"}, Bad{"x\xc3\xa9", "past ASCII"},
                         Bad{"\\input{/etc/passwd}", "uses \\input; only Greek"}, Bad{"\\def\\x{1}", "uses \\def; only Greek"},
                         Bad{"x\\", "starts no command"}, Bad{"{}", "nothing to typeset"}, Bad{"{ }", "nothing to typeset"},
                         Bad{"\\hat{}", "nothing to typeset"}, Bad{"\\mathrm{}", "nothing to typeset"},
                         // Issue 33: kinema dotted it as \dot{\hat{x}_{\hat{y}}}, which amsmath cannot typeset.
                         Bad{"\\hat{x}_{\\hat{y}}", "more than one accent"}, Bad{"\\bar{\\hat{x}}", "keep one"}}) {
    CAPTURE(bad.latex);
    try {
      check_latex_name(bad.latex, "unit.toml:7: unknown \"q\"");
      FAIL("accepted");
    } catch (const kinema::InputError& error) {
      const std::string message = error.what();
      CAPTURE(message);
      CHECK(message.find("unit.toml:7: unknown \"q\"") == 0);  // the context comes first
      CHECK(message.find(bad.named) != std::string::npos);
    }
  }
}
