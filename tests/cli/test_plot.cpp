// `tsmframe plot MODEL.json`: the model drawn before solving (app/main.cpp, scripts/plot_model.py,
// python/tsmframe/model_plot.py). A picture written whole where it was asked for; a mechanism drawn
// and then refused as a run refuses it (exit 2, one line); bad input refused with nothing
// written; a picture that cannot be written is the system's failure (exit 3, the OS's reason).
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <set>
#include <nlohmann/json.hpp>
#include <string>

#include "support/cli.hpp"
#include "support/scratch_directory.hpp"

namespace {

namespace fs = std::filesystem;
using nlohmann::json;

using tsm::test::Outcome;
using tsm::test::run_command;

/// A portal frame on two pins with a hinged beam, a sway load and a load on the beam.
json portal() {
  return json::parse(R"({
    "title": "a portal to draw",
    "materials": {"steel": {"E": 2e11}}, "sections": {"s": {"A": 1e-2, "I": 1e-4}},
    "nodes": [{"id": 1, "x": 0, "y": 0}, {"id": 2, "x": 0, "y": 3}, {"id": 3, "x": 4, "y": 3}, {"id": 4, "x": 4, "y": 0}],
    "members": [{"from": 1, "to": 2, "material": "steel", "section": "s"},
                {"from": 2, "to": 3, "divisions": 4, "material": "steel", "section": "s", "release": "start"},
                {"from": 3, "to": 4, "material": "steel", "section": "s"}],
    "supports": [{"node": 1, "type": "pinned"}, {"node": 4, "type": "pinned"}],
    "loads": [{"node": 2, "fx": 1e3}, {"node": 3, "fy": -2e3, "mz": 500}]
  })");
}

class Plot : public tsm::test::ScratchDirectory {
 protected:
  Plot() : ScratchDirectory("tsmframe-plot-") {}

  /// `tsmframe plot ARGUMENTS` run in the scratch directory.
  Outcome plot(const std::string& arguments) {
    return run_command("cd " + dir_.string() + " && " + TSMFRAME_CLI + " plot " + arguments + " 2>&1");
  }

  std::string read(const fs::path& path) {
    std::ifstream in(path, std::ios::binary);
    return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
  }

  /// Whether anything but `kept` is in the scratch directory (a temporary left behind).
  bool only(const std::set<std::string>& kept) {
    for (const auto& entry : fs::directory_iterator(dir_))
      if (!kept.count(entry.path().filename().string())) return false;
    return true;
  }
};

TEST_F(Plot, DrawsTheModelBesideItByDefault) {
  write("portal.json", portal());
  const Outcome o = plot("portal.json");
  EXPECT_EQ(o.exit_code, 0) << o.output;
  EXPECT_EQ(o.output, "drawn: portal.png\n");
  EXPECT_EQ(read(dir_ / "portal.png").substr(1, 3), "PNG");
  EXPECT_TRUE(only({"portal.json", "portal.png"}));
}

TEST_F(Plot, AnSvgOrAPdfWhereAsked) {
  write("portal.json", portal());
  ASSERT_EQ(plot("portal.json -o drawn.svg").exit_code, 0);
  EXPECT_NE(read(dir_ / "drawn.svg").find("<svg"), std::string::npos);
  ASSERT_EQ(plot("portal.json --out drawn.pdf").exit_code, 0);
  EXPECT_EQ(read(dir_ / "drawn.pdf").substr(0, 5), "%PDF-");
}

TEST_F(Plot, AMechanismIsDrawnThenRefused) {
  json m = portal();
  m["supports"] = json::parse(R"([{"node": 1, "type": "roller-x"}, {"node": 4, "type": "roller-x"}])");
  write("loose.json", m);
  const Outcome o = plot("loose.json");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("loose.json: supports: structure is a mechanism: ", 0), 0u) << o.output;
  EXPECT_NE(o.output.find("free to move along x"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(drawn in loose.png)\n"), std::string::npos) << o.output;
  EXPECT_EQ(std::count(o.output.begin(), o.output.end(), '\n'), 1);
  EXPECT_TRUE(fs::exists(dir_ / "loose.png"));
}

TEST_F(Plot, AMechanismAmongHingesIsDrawnThenRefused) {
  // Pinned feet and a beam hinged at both ends: the supports hold the frame as a body, but it sways
  // with no element deforming — found as a run finds it (the unloaded tangent's null vector).
  json m = portal();
  m["members"][1]["release"] = "both";
  write("sway.json", m);
  const Outcome o = plot("sway.json");
  EXPECT_EQ(o.exit_code, 2) << o.output;
  EXPECT_EQ(o.output.rfind("sway.json: the structure is a mechanism: unloaded, it can move with no element deforming — ", 0), 0u)
      << o.output;
  EXPECT_NE(o.output.find("moving along x"), std::string::npos) << o.output;
  EXPECT_NE(o.output.find("(drawn in sway.png)\n"), std::string::npos) << o.output;
  EXPECT_TRUE(fs::exists(dir_ / "sway.png"));
  const Outcome run = run_command("cd " + dir_.string() + " && " + TSMFRAME_CLI + " run sway.json -q 2>&1");
  EXPECT_EQ(run.exit_code, 1);  // the run meets the same mechanism at its first step
  EXPECT_NE(run.output.find("the structure is a mechanism: unloaded, it can move with no element deforming"), std::string::npos)
      << run.output;
}

TEST_F(Plot, BadInputDrawsNothing) {
  json m = portal();
  m["members"][0]["sectoin"] = "s";
  write("typo.json", m);
  const Outcome typo = plot("typo.json");
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_EQ(typo.output.rfind("typo.json: members[0].sectoin: unknown key \"sectoin\"", 0), 0u) << typo.output;
  const Outcome missing = plot("nothere.json");
  EXPECT_EQ(missing.exit_code, 2);
  EXPECT_EQ(missing.output, "nothere.json: cannot open the file\n");
  write("portal.json", portal());
  const Outcome format = plot("portal.json -o portal.jpg");
  EXPECT_EQ(format.exit_code, 2);
  EXPECT_NE(format.output.find("portal.jpg: the picture's format is unknown (expected .png, .svg or .pdf)"), std::string::npos);
  EXPECT_TRUE(only({"typo.json", "portal.json"}));
}

TEST_F(Plot, APictureThatCannotBeWrittenIsTheSystemsFailure) {
  write("portal.json", portal());
  const Outcome o = plot("portal.json -o no/such/directory/portal.png");
  EXPECT_EQ(o.exit_code, 3) << o.output;
  EXPECT_EQ(o.output, "tsmframe: no/such/directory/portal.png: cannot write: No such file or directory\n");
}

}  // namespace
