// A sweep's assignments (study/assignment.hpp): where a pointer may set a value — an entry a
// list has, one past its end, any key of an object, new objects under a new key — and that
// nothing else is built: a list made under a new key holds one entry, never the entries up to
// an index (found by fuzz/fuzz_study.cpp: "/analysis/analysis/end/steps/18446744073709551615"
// aborted the expansion of a case, and ".../4000000000" would have made 4·10⁹ nulls).
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>
#include <string>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/study/assignment.hpp"

namespace {

using nlohmann::json;
using tsm::study::assign;
using tsm::study::Assignment;
using tsm::study::unassignable;

json model() { return {{"analysis", json::object()}, {"nodes", json::array({1, 2})}}; }

TEST(Assignment, UnderANewKeyAListIsMadeOnlyForItsFirstEntry) {
  for (const char* pointer : {"/analysis/new/0", "/analysis/new/-", "/analysis/new/0/x", "/analysis/new/-/y", "/extra/a/b/0"}) {
    EXPECT_FALSE(unassignable(model(), pointer)) << pointer;
    json m = model();
    assign(m, {pointer, 5, "sweep[0].path"});
    EXPECT_EQ(m.dump().find("null"), std::string::npos) << pointer << ": " << m.dump();
  }
  json m = model();
  assign(m, {"/analysis/new/-/y", 5, "sweep[0].path"});
  EXPECT_EQ(m["analysis"]["new"], json::parse(R"([{"y": 5}])"));
}

TEST(Assignment, UnderANewKeyAnIndexPastTheFirstEntryIsRefusedWithoutBuildingTheList) {
  for (const char* pointer : {"/analysis/new/4000000000", "/analysis/analysis/end/steps/18446744073709551615",
                              "/analysis/new/99999999999999999999999", "/analysis/new/7/x", "/analysis/new/1",
                              "/analysis/new/01", "/analysis/new/", "/extra/0/4000000000"}) {
    EXPECT_TRUE(unassignable(model(), pointer)) << pointer;
    json m = model();
    EXPECT_THROW(assign(m, {pointer, 5, "sweep[0].path"}), tsm::io::InputError) << pointer;
    EXPECT_EQ(m, model()) << pointer << ": nothing is built";
  }
  EXPECT_EQ(unassignable(model(), "/analysis/new/4000000000").value_or(""),
            "\"/analysis/new\" is new: it would be made a list, where 4000000000 is past the end of its one entry (0 or \"-\" makes it)");
}

TEST(Assignment, AnIndexPastTheEndOfAListTheModelHasIsRefused) {
  EXPECT_EQ(unassignable(model(), "/nodes/4000000000").value_or(""),
            "\"/nodes\" has 2 entries: 4000000000 is past its end (0 to 1 name them, 2 appends one)");
  EXPECT_FALSE(unassignable(model(), "/nodes/2"));
  EXPECT_FALSE(unassignable(model(), "/nodes/-"));
}

}  // namespace
