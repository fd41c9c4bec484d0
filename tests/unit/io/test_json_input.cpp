// The JSON input helpers (io/json_input.hpp) both readers use: each helper's value, and its
// error as the user sees it — `JSON.path: reason` — in the one path syntax.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "tsmframe/io/json_input.hpp"

namespace {

using nlohmann::json;
namespace io = tsm::io;

/// The error `read` throws, as the command line prints it after the file name; "" if none.
template <class Read>
std::string error_of(Read read) {
  try {
    read();
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(JsonPath, NamesKeysWithDotsIndicesInBracketsAndQuotesKeysThatAreNoIdentifiers) {
  EXPECT_EQ(io::child("", "nodes"), "nodes");
  EXPECT_EQ(io::child("members", 2), "members[2]");
  EXPECT_EQ(io::child("members[2]", "end_springs"), "members[2].end_springs");
  EXPECT_EQ(io::child("sweep[0].variants[1].set", "/supports"), "sweep[0].variants[1].set[\"/supports\"]");
  EXPECT_EQ(io::child("materials", "2nd steel"), "materials[\"2nd steel\"]");
  EXPECT_EQ(io::child("units", ""), "units[\"\"]");
}

TEST(JsonInput, QuotesTextAsJsonAndNamesTypesInWords) {
  EXPECT_EQ(io::quote_text("a\"b"), "\"a\\\"b\"");
  EXPECT_STREQ(io::type_name(json(1.5)), "a number");
  EXPECT_STREQ(io::type_name(json("x")), "a string");
  EXPECT_STREQ(io::type_name(json(true)), "true/false");
  EXPECT_STREQ(io::type_name(json::array()), "a list");
  EXPECT_STREQ(io::type_name(json::object()), "an object");
  EXPECT_STREQ(io::type_name(json()), "null");
}

TEST(JsonInput, ParsesTextAndNamesTheLineAndColumnOfASyntaxError) {
  EXPECT_EQ(io::parse_json("{\"a\": [1, 2]}")["a"][1], 2);
  // Line 3 is `  "b": ]`: the bracket is its 8th character.
  const std::string error = error_of([] { io::parse_json("{\n  \"a\": 1,\n  \"b\": ]\n}"); });
  EXPECT_EQ(error.rfind("invalid JSON at line 3, column 8: syntax error", 0), 0u) << error;
}

TEST(JsonInput, ExpectsObjectsAndListsSayingWhatItFound) {
  EXPECT_EQ(error_of([] { io::expect_object(json::array(), "analysis"); }), "analysis: expected an object, found a list");
  EXPECT_EQ(error_of([] { io::expect_array(json("x"), "nodes"); }), "nodes: expected a list, found a string");
  EXPECT_EQ(error_of([] { io::expect_object(json::object(), "analysis"); }), "");
}

TEST(JsonInput, RefusesAnUnknownKeyListingTheKnownOnesButIgnoresExtra) {
  const json member = {{"from", 1}, {"sectoin", "box"}};
  EXPECT_EQ(error_of([&] { io::check_keys(member, "members[0]", {"from", "to"}); }),
            "members[0].sectoin: unknown key \"sectoin\" (expected one of: from, to)");
  const json with_extra = {{"from", 1}, {"extra", {{"note", "anything"}}}};
  EXPECT_EQ(error_of([&] { io::check_keys(with_extra, "members[0]", {"from", "to"}); }), "");
}

TEST(JsonInput, ReadsFiniteNumbersWithinPlusMinus1e50) {
  EXPECT_EQ(io::number(json(-2.5), "x"), -2.5);
  EXPECT_EQ(io::number(json(7), "x"), 7.0);
  EXPECT_EQ(error_of([] { io::number(json("7"), "nodes[0].x"); }), "nodes[0].x: expected a number, found a string");
  EXPECT_EQ(error_of([] { io::number(json(1e51), "loads[0].fy"); }),
            "loads[0].fy: beyond ±1e50 (1e+51): no unit system needs it, and products of such numbers overflow");
  EXPECT_EQ(io::number(json(-1e50), "x"), -1e50);
}

TEST(JsonInput, ReadsOptionalAndRequiredNumbersUnderTheirKeys) {
  const json analysis = {{"tolerance", 1e-6}};
  EXPECT_EQ(io::optional_number(analysis, "tolerance", "analysis"), 1e-6);
  EXPECT_FALSE(io::optional_number(analysis, "max_iterations", "analysis"));
  EXPECT_EQ(io::required_number(analysis, "tolerance", "analysis"), 1e-6);
  EXPECT_EQ(error_of([&] { io::required_number(analysis, "target", "analysis.control"); }), "analysis.control.target: missing (required)");
  EXPECT_EQ(io::positive(0.5, "E"), 0.5);
  EXPECT_EQ(error_of([] { io::positive(-1.0, "materials.steel.E"); }), "materials.steel.E: must be positive, got -1");
  EXPECT_EQ(error_of([] { io::positive(0.0, "materials.steel.E"); }), "materials.steel.E: must be positive, got 0");
}

TEST(JsonInput, ReadsWholeNumbersAlsoWrittenAsFloatsButNoFractions) {
  EXPECT_EQ(io::integer(json(12), "n"), 12);
  EXPECT_EQ(io::integer(json(-3), "n"), -3);
  EXPECT_EQ(io::integer(json(12.0), "n"), 12);
  EXPECT_EQ(error_of([] { io::integer(json(2.5), "members[0].divisions"); }), "members[0].divisions: expected a whole number, found 2.5");
  EXPECT_EQ(error_of([] { io::integer(json("2"), "members[0].divisions"); }), "members[0].divisions: expected a whole number, found a string");
  EXPECT_EQ(io::integer(json(9223372036854775807L), "n"), 9223372036854775807L);
}

TEST(JsonInput, RefusesAWholeNumberPastTheLargestLongInsteadOfWrappingItToANegativeOne) {
  // 2⁶⁴ − 1 is stored unsigned; read as a long it would be −1 (a node id −1, "unknown node -1").
  EXPECT_EQ(error_of([] { io::integer(json(18446744073709551615UL), "loads[0].node"); }),
            "loads[0].node: expected a whole number within ±9223372036854775807, found 18446744073709551615");
  EXPECT_EQ(error_of([] { io::integer(json(9223372036854775808UL), "n"); }),
            "n: expected a whole number within ±9223372036854775807, found 9223372036854775808");
  EXPECT_EQ(error_of([] { io::bounded_integer(json(18446744073709551615UL), "nodes[0].id", -5, 5); }),
            "nodes[0].id: must be between -5 and 5, got 18446744073709551615");
}

TEST(JsonInput, BoundsWholeNumbers) {
  EXPECT_EQ(io::bounded_integer(json(10), "n", 1, 10), 10);
  EXPECT_EQ(io::bounded_integer(json(1), "n", 1, 10), 1);
  EXPECT_EQ(error_of([] { io::bounded_integer(json(0), "members[1].divisions", 1, 10); }),
            "members[1].divisions: must be between 1 and 10, got 0");
  EXPECT_EQ(error_of([] { io::bounded_integer(json(11), "members[1].divisions", 1, 10); }),
            "members[1].divisions: must be between 1 and 10, got 11");
}

TEST(JsonInput, ReadsStringsBooleansPointsAndDofNames) {
  EXPECT_EQ(io::string(json("box"), "s"), "box");
  EXPECT_EQ(error_of([] { io::string(json(3), "members[0].section"); }), "members[0].section: expected a string, found a number");
  EXPECT_TRUE(io::boolean(json(true), "b"));
  EXPECT_EQ(error_of([] { io::boolean(json(1), "analysis.cutback"); }), "analysis.cutback: expected true or false, found a number");
  EXPECT_EQ(io::point(json({1.5, -2.0}), "p"), Eigen::Vector2d(1.5, -2.0));
  EXPECT_EQ(error_of([] { io::point(json({1.0}), "members[0].arc.center"); }), "members[0].arc.center: expected a point [x, y]");
  EXPECT_EQ(error_of([] { io::point(json({1.0, "y"}), "members[0].arc.center"); }),
            "members[0].arc.center[1]: expected a number, found a string");
  EXPECT_EQ(io::dof_from_name("ux", "d"), tsm::ux);
  EXPECT_EQ(io::dof_from_name("uy", "d"), tsm::uy);
  EXPECT_EQ(io::dof_from_name("rz", "d"), tsm::rz);
  EXPECT_EQ(error_of([] { io::dof_from_name("uz", "supports[0].fix[1]"); }),
            "supports[0].fix[1]: unknown dof \"uz\" (expected ux, uy or rz)");
}

/// Node 1 at (0, 0) and node 7 at (2, 0): the model is 2 long.
tsm::Model two_nodes() {
  tsm::Model model;
  model.nodes = {{1, {0.0, 0.0}}, {7, {2.0, 0.0}}};
  model.size = 2.0;
  return model;
}

int resolve(const json& value, const tsm::Model& model) {
  return io::resolve_node(io::node_reference(value, "loads[0].node"), "loads[0].node", model,
                          [&](long id) { return model.node_index(static_cast<int>(id)); });
}

TEST(NodeReference, NamesANodeByIdOrByItsCoordinates) {
  const tsm::Model model = two_nodes();
  EXPECT_EQ(resolve(json(7), model), 1);
  EXPECT_EQ(resolve(json(1), model), 0);
  EXPECT_EQ(resolve(json({2.0, 0.0}), model), 1);
  EXPECT_EQ(resolve(json({2.0 + 1e-10, 0.0}), model), 1);  // within 1e-9 of the model's size
  const io::NodeReference by_id = io::node_reference(json(7), "n");
  EXPECT_EQ(by_id.id, 7);
  EXPECT_FALSE(io::node_reference(json({2.0, 0.0}), "n").id);
}

TEST(NodeReference, SaysWhichNodeIsNotThereAndWhichIsNearest) {
  const tsm::Model model = two_nodes();
  EXPECT_EQ(error_of([&] { resolve(json(3), model); }), "loads[0].node: unknown node 3");
  EXPECT_EQ(error_of([&] { resolve(json({1.5, 0.0}), model); }),
            "loads[0].node: no node at [1.5, 0] (the nearest, node 7, is at [2, 0], 0.5 away)");
  EXPECT_EQ(error_of([&] { resolve(json("tip"), model); }), "loads[0].node: expected a node id or [x, y], found a string");
  EXPECT_EQ(error_of([&] { resolve(json(2.5), model); }), "loads[0].node: expected a whole number, found 2.5");
}

}  // namespace
