// The model's drawing document (io/model_drawing): what `tsmframe plot` and Model.plot() draw —
// the meshed nodes and elements, the supports' held dofs, springs, loads per stage with the
// members' lumped, contacts grouped by what they may touch, and a mechanism named, not refused.
#include "tsmframe/io/model_drawing.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <nlohmann/json.hpp>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/model/mechanism.hpp"

namespace {

using nlohmann::json;

/// A portal on a pin and a skew roller, its beam hinged at one end and sprung at the other, under
/// a uniform load of 2 per length on its 4-m beam, a sway load, a follower load and a pressure on
/// the left column, a spring at the roller, and two nodes of a loose bar that may touch the beam.
json portal() {
  return {{"title", "drawn portal"},
          {"materials", {{"steel", {{"E", 2e11}}}}},
          {"sections", {{"s", {{"A", 1e-2}, {"I", 1e-4}}}}},
          {"nodes",
           {{{"id", 1}, {"x", 0}, {"y", 0}},
            {{"id", 2}, {"x", 0}, {"y", 3}},
            {{"id", 3}, {"x", 4}, {"y", 3}},
            {{"id", 4}, {"x", 4}, {"y", 0}},
            {{"id", 5}, {"x", 1}, {"y", 3.5}},
            {{"id", 6}, {"x", 3}, {"y", 3.5}}}},
          {"members",
           {{{"from", 1}, {"to", 2}, {"material", "steel"}, {"section", "s"}, {"load", {{"pressure", 5}}}},
            {{"from", 2}, {"to", 3}, {"divisions", 2}, {"material", "steel"}, {"section", "s"}, {"release", "start"},
             {"end_springs", {{"end", 7e6}}}, {"load", {{"fy", -2}}}},
            {{"from", 3}, {"to", 4}, {"material", "steel"}, {"section", "s"}},
            {{"from", 5}, {"to", 6}, {"material", "steel"}, {"section", "s"}}}},
          {"supports", {{{"node", 1}, {"type", "pinned"}}, {{"node", 4}, {"roller", {1, 1}}}, {{"node", 5}, {"type", "pinned"}},
                        {{"node", 6}, {"fix", {"ux"}}}}},
          {"springs", {{{"node", 4}, {"ky", 3e5}}, {{"node", 1}, {"kr", 4e5}}}},
          {"loads", {{{"node", 2}, {"fx", 10}, {"mz", 3}}, {{"node", 3}, {"fx", 1}, {"fy", -1}, {"follower", true}}}},
          {"prescribed", {{{"node", 6}, {"uy", -0.25}}}},
          {"contacts", {{{"nodes", {{"members", {3}}}}, {"members", {1}}, {"gap", 0.1}}}}};
}

json drawing_of(const json& model) {
  tsm::Model m = tsm::io::read_model(model, tsm::io::memory_budget(), 0.0, tsm::io::Mechanisms::allow);
  return json::parse(tsm::io::model_drawing(m, tsm::starting_mechanism(m)));
}

TEST(ModelDrawing, TheMeshAndWhatHoldsIt) {
  const json d = drawing_of(portal());
  EXPECT_EQ(d["format"], "tsmframe-drawing/1");
  EXPECT_EQ(d["title"], "drawn portal");
  EXPECT_FALSE(d.contains("mechanism"));
  EXPECT_EQ(d["nodes"].size(), 7u);     // 6 drawn + the beam's middle
  EXPECT_EQ(d["elements"].size(), 5u);  // 1 + 2 + 1 + 1
  EXPECT_EQ(d["elements"][1]["release"], "start");
  EXPECT_DOUBLE_EQ(d["elements"][2]["end_springs"]["end"].get<double>(), 7e6);
  // The pins hold ux, uy; the skew roller its normal; node 6 ux (its uy is prescribed: moved).
  std::map<int, json> supports;
  for (const json& s : d["supports"]) supports[s["node"].get<int>()] = s;
  EXPECT_EQ(supports.at(1)["held"], json({"ux", "uy"}));
  EXPECT_EQ(supports.at(4)["held"], json({"n"}));
  EXPECT_NEAR(supports.at(4)["along"][0].get<double>(), std::sqrt(0.5), 1e-15);
  EXPECT_EQ(supports.at(5)["held"], json({"ux", "uy"}));
  EXPECT_EQ(supports.at(6)["held"], json({"ux"}));
  ASSERT_EQ(d["springs"].size(), 2u);
  EXPECT_EQ(d["springs"][0]["kind"], "translation");
  EXPECT_EQ(d["springs"][0]["direction"], json({0.0, 1.0}));
  EXPECT_EQ(d["springs"][0]["stiffness"], 3e5);
  EXPECT_EQ(d["springs"][1]["kind"], "rotation");
}

TEST(ModelDrawing, LoadsWithTheMembersLumpedAndContactsGrouped) {
  const json d = drawing_of(portal());
  ASSERT_EQ(d["load_cases"].size(), 1u);
  const json& c = d["load_cases"][0];
  // Node 2: the sway load, the moment, and half of the beam's first element's 2 × 2 m: fy = −2.
  // The beam's middle (id 7): −4; node 3: −2 (its follower load is apart).
  std::map<int, json> loads;
  for (const json& l : c["loads"]) loads[l[0].get<int>()] = l;
  EXPECT_EQ(loads.at(2), json({2, 10.0, -2.0, 3.0}));
  EXPECT_EQ(loads.at(7), json({7, 0.0, -4.0, 0.0}));
  EXPECT_EQ(loads.at(3), json({3, 0.0, -2.0, 0.0}));
  EXPECT_EQ(loads.size(), 3u);
  EXPECT_EQ(c["follower"], json::array({{3, 1.0, -1.0}}));
  EXPECT_EQ(c["pressures"], json::array({{0, 5.0}}));
  EXPECT_EQ(c["prescribed"], json::array({{{"node", 6}, {"dof", "uy"}, {"value", -0.25}, {"increment", false}}}));
  ASSERT_EQ(d["contacts"].size(), 1u);
  EXPECT_EQ(d["contacts"][0]["nodes"], json({5, 6}));
  EXPECT_EQ(d["contacts"][0]["members"], json({1}));
  EXPECT_EQ(d["contacts"][0]["gap"], 0.1);
}

TEST(ModelDrawing, EachStageItsOwnLoads) {
  json m = portal();
  m.erase("prescribed");
  m["stages"] = {{{"name", "press"}, {"prescribed", {{{"node", 6}, {"uy", -0.25}}}}},
                 {{"name", "sway"}, {"loads", {{{"node", 3}, {"fx", 7}}}}, {"prescribed", {{{"node", 6}, {"uy", 0.5}, {"increment", true}}}}}};
  m.erase("loads");
  const json d = drawing_of(m);
  ASSERT_EQ(d["load_cases"].size(), 2u);
  EXPECT_EQ(d["load_cases"][0]["name"], "press");
  EXPECT_EQ(d["load_cases"][0]["pressures"], json::array({{0, 5.0}}));  // the members' loads are the first stage's
  EXPECT_EQ(d["load_cases"][0]["prescribed"][0]["value"], -0.25);
  EXPECT_EQ(d["load_cases"][1]["name"], "sway");
  EXPECT_EQ(d["load_cases"][1]["loads"], json::array({{3, 7.0, 0.0, 0.0}}));
  EXPECT_EQ(d["load_cases"][1]["pressures"], json::array());
  EXPECT_EQ(d["load_cases"][1]["prescribed"], json::array({{{"node", 6}, {"dof", "uy"}, {"value", 0.5}, {"increment", true}}}));
}

TEST(ModelDrawing, AMechanismIsDrawnAndNamedNotRefused) {
  json m = portal();
  m["supports"][0] = {{"node", 1}, {"type", "roller-x"}};  // nothing holds the portal along x now
  m["supports"][1] = {{"node", 4}, {"type", "roller-x"}};
  EXPECT_THROW(tsm::io::read_model(m), tsm::io::InputError);  // a run refuses it
  const json d = drawing_of(m);
  ASSERT_TRUE(d.contains("mechanism"));
  EXPECT_NE(d["mechanism"].get<std::string>().find("free to move along x"), std::string::npos) << d["mechanism"];
  EXPECT_EQ(d["elements"].size(), 5u);
}

}  // namespace
