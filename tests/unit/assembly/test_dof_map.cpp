// The dof numbering (assembly/dof_map): a contact node is ordered with the element it rests on
// or is nearest, so the ladder of a mat lying on a beam fills in only a few blocks per node.
#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

#include <nlohmann/json.hpp>

#include "tsmframe/assembly/dof_map.hpp"
#include "tsmframe/io/model_reader.hpp"
#include "tsmframe/linalg/block_matrix.hpp"

namespace {

TEST(EliminationOrder, ContactsAreOrderedWithTheElementTheyRestOnOrAreNearest) {
  // A mat of 600 elements lying on a beam of 1,800, every mat node a contact on the beam: resting
  // on it from the start (drawn at the gap), or 1 cm above it. Once the contacts touch, the
  // tangent is a ladder. DofMap orders each contact node with the element it rests on or is
  // nearest, so the ladder fills a few blocks per node; ordered as two separate chains it filled
  // in like a dense block (a mat of 1,000 nodes on 3,000 elements took 6 minutes in the
  // factorisation, now a second).
  using nlohmann::json;
  for (const double height : {0.05, 0.06}) {
    json m = {{"materials", {{"steel", {{"E", 2e11}}}}},
              {"sections", {{"beam", {{"A", 4e-3}, {"I", 2e-5}}}, {"mat", {{"A", 1e-3}, {"I", 1e-8}}}}},
              {"nodes", json::array({{{"id", 1}, {"x", 0.0}, {"y", 0.0}}, {{"id", 2}, {"x", 10.0}, {"y", 0.0}},
                                     {{"id", 3}, {"x", 0.005}, {"y", height}}, {{"id", 4}, {"x", 9.995}, {"y", height}}})},
              {"members", json::array({{{"from", 1}, {"to", 2}, {"divisions", 1800}, {"material", "steel"}, {"section", "beam"}},
                                       {{"from", 3}, {"to", 4}, {"divisions", 600}, {"material", "steel"}, {"section", "mat"}}})},
              {"supports", json::array({{{"node", 1}, {"type", "pinned"}}, {{"node", 2}, {"type", "roller-x"}},
                                        {{"node", 3}, {"type", "pinned"}}, {{"node", 4}, {"type", "pinned"}}})},
              {"contacts", json::array({{{"nodes", {{"members", {1}}}}, {"members", {0}}, {"gap", 0.05}}})}};
    const tsm::Model model = tsm::io::read_model(m);
    const tsm::assembly::DofMap dofs(model);
    // The tangent's block pattern with every contact touching the beam element below its node,
    // in DofMap's order.
    const int n = dofs.block_count();
    std::vector<std::vector<int>> rows(n);
    auto join = [&](int a, int b) {
      const int ba = dofs.block(a), bb = dofs.block(b);
      if (ba < 0 || bb < 0) return;
      rows[std::min(ba, bb)].push_back(std::max(ba, bb));
    };
    for (const tsm::Element& e : model.elements) join(e.start, e.end);
    for (const tsm::ContactSpec& c : model.contacts) {
      const double x = model.nodes[c.node].position.x();
      for (const tsm::Element& e : model.elements)
        if (e.member == 0 && model.nodes[e.start].position.x() <= x && x <= model.nodes[e.end].position.x()) {
          join(c.node, e.start);
          join(c.node, e.end);
          break;
        }
    }
    tsm::linalg::BlockMatrix pattern;
    pattern.size = n;
    pattern.column.push_back(0);
    for (int b = 0; b < n; ++b) {
      std::vector<int>& r = rows[b];
      r.push_back(b);
      std::sort(r.begin(), r.end());
      r.erase(std::unique(r.begin(), r.end()), r.end());
      pattern.row.insert(pattern.row.end(), r.begin(), r.end());
      pattern.column.push_back(static_cast<int>(pattern.row.size()));
    }
    const size_t entries = pattern.row.size();
    tsm::linalg::add_fill(pattern);
    EXPECT_LT(pattern.row.size(), 8u * static_cast<size_t>(n)) << "height " << height << ": entries " << entries << " before the fill";
  }
}

}  // namespace
