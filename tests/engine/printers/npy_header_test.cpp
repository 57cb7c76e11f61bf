// The npy header both npy tables share (engine/printers/data/npy_header): the data starts on a
// 64-byte boundary, the length field says the dict's length, version 2.0 once the dict outgrows
// 1.0's 16-bit length; and a design study's npy table, read back by numpy, holds its columns.
#include <doctest/doctest.h>

#include <cmath>
#include <cstdint>
#include <string>
#include <vector>

#include "engine/printers/data/npy_header.hpp"
#include "engine/printers/data/study_table.hpp"

#include "tests/test_support.hpp"

namespace {

// The length field of a header (little-endian, 2 bytes in version 1, 4 in version 2).
std::uint32_t length_field(const std::string& header) {
  const std::size_t bytes = header[6] == '\x01' ? 2 : 4;
  std::uint32_t length = 0;
  for (std::size_t b = 0; b < bytes; ++b) length |= static_cast<std::uint32_t>(static_cast<unsigned char>(header[8 + b])) << (8 * b);
  return length;
}

}  // namespace

TEST_CASE("npy header: the data on a 64-byte boundary, its length field, version 2 for a long dict") {
  const std::string small = kinema::npy_header({{"theta3", "<f8"}, {"status", "|u1"}}, 7);
  CHECK(small.compare(0, 6, "\x93NUMPY") == 0);
  CHECK(small[6] == '\x01');
  CHECK(small.size() % 64 == 0);
  CHECK(length_field(small) == small.size() - 10);
  CHECK(small.back() == '\n');
  CHECK(small.find("'descr': [('theta3', '<f8'), ('status', '|u1')]") != std::string::npos);
  CHECK(small.find("'shape': (7,)") != std::string::npos);

  std::vector<kinema::NpyField> many;  // a dict of more than 65,535 characters
  for (int k = 0; k < 4000; ++k) many.push_back({"a_rather_long_field_" + std::to_string(k), "<f8"});
  const std::string large = kinema::npy_header(many, 3);
  CHECK(large[6] == '\x02');
  CHECK(large.size() % 64 == 0);
  CHECK(length_field(large) == large.size() - 12);
  CHECK(large.size() > 65536);
}

TEST_CASE("a design study's npy table read back by numpy holds its columns and types") {
  using Kind = kinema::StudyColumn::Kind;
  const std::vector<kinema::StudyColumn> columns{
      {Kind::real, "b", "mm", {110.5, 121.25, std::nan("")}},
      {Kind::grashof, "grashof", "", {0, 1, 2}},
      {Kind::flag, "assembles", "", {1, 0, 1}},
      {Kind::count, "unassembled", "", {0, 17, 4000000000.0}}};
  const std::string file = kinema_test::write_temporary("npy_header_study.npy", kinema::print_study_table(columns, "npy", 0));
  // numpy prints each field's dtype and values; NaN as nan.
  const auto read = kinema_test::run_shell(
      "/usr/bin/python3 -c \"import numpy, sys; t = numpy.load(sys.argv[1]); "
      "[print(n, t.dtype[n].str, ' '.join(repr(v.item()) for v in t[n])) for n in t.dtype.names]\" " +
      kinema_test::shell_quote(file));
  CAPTURE(read.err);
  REQUIRE(read.exit_status == 0);
  CHECK(read.out ==
        "b <f8 110.5 121.25 nan\n"
        "grashof |i1 0 1 2\n"
        "assembles |b1 True False True\n"
        "unassembled <u4 0 17 4000000000\n");
}
