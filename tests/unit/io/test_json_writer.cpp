#include "tsmframe/io/json_writer.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <vector>

namespace {

// Every key, plain or in need of escaping, reads back as itself: a key of printable ASCII is
// written as is, any other (a quote, a backslash, a control character, UTF-8) escaped.
TEST(JsonWriter, EveryKeyReadsBackAsItself) {
  const std::vector<std::string> keys{"uy_35003", "", "a \"quoted\" key", "back\\slash", "line\nbreak",
                                      "tab\t", std::string("nul\0in", 6), "\x7f", "Θ_c — é"};
  std::ostringstream text;
  tsm::io::JsonWriter writer(text);
  writer.begin_object();
  for (size_t k = 0; k < keys.size(); ++k) writer.key(keys[k]).value(static_cast<int>(k));
  writer.end_object();
  const nlohmann::json read = nlohmann::json::parse(text.str());
  ASSERT_EQ(read.size(), keys.size());
  for (size_t k = 0; k < keys.size(); ++k) EXPECT_EQ(read.at(keys[k]), static_cast<int>(k)) << k;
  EXPECT_NE(text.str().find("{\"uy_35003\":0,"), std::string::npos);
}

TEST(JsonWriter, NumbersReadBackToTheSameDoubleAndNonFiniteAsNull) {
  const std::vector<double> values{0.1, -1e-13, 2.0, 1.0 / 3.0, std::numeric_limits<double>::max(), -0.0};
  std::ostringstream text;
  tsm::io::JsonWriter writer(text);
  writer.begin_array();
  for (const double x : values) writer.value(x);
  writer.value(std::numeric_limits<double>::quiet_NaN());
  writer.end_array();
  const nlohmann::json read = nlohmann::json::parse(text.str());
  for (size_t k = 0; k < values.size(); ++k) EXPECT_EQ(read[k].get<double>(), values[k]) << k;
  EXPECT_TRUE(read.back().is_null());
  EXPECT_EQ(text.str().find("-0,"), std::string::npos);  // no "-0"
}

}  // namespace
