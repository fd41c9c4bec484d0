#include "tsmframe/io/contact_options.hpp"

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"

namespace tsm::io {

void read_contact_law_options(const nlohmann::json& entry, const std::string& path, ContactSpec& spec) {
  if (entry.contains("frame")) {
    const std::string frame = string(entry["frame"], child(path, "frame"));
    if (frame != "chord" && frame != "cantilever") fail(child(path, "frame"), "unknown frame " + quote_text(frame) + " (expected \"chord\" or \"cantilever\")");
    spec.frame = frame == "cantilever" ? ContactFrame::cantilever : ContactFrame::chord;
    if (spec.frame == ContactFrame::cantilever) spec.normal = ContactNormal::chord;  // its only one
  }
  if (entry.contains("normal")) {
    const std::string normal = string(entry["normal"], child(path, "normal"));
    if (normal != "chord" && normal != "deflected") fail(child(path, "normal"), "unknown normal " + quote_text(normal) + " (expected \"chord\" or \"deflected\")");
    spec.normal = normal == "deflected" ? ContactNormal::deflected : ContactNormal::chord;
    if (spec.normal == ContactNormal::deflected && spec.frame == ContactFrame::cantilever)
      fail(child(path, "normal"), "the cantilever frame pushes along its chord's normal only (use the chord frame for \"deflected\")");
  }
  if (auto edge = optional_number(entry, "edge", path)) {
    if (!(*edge >= 1e-12 && *edge <= 0.25)) fail(child(path, "edge"), "must lie between 1e-12 and 0.25 (a fraction of the element length)");
    spec.edge = *edge;
  }
  if (auto ratio = optional_number(entry, "max_stiffness_ratio", path)) {
    if (!(*ratio >= 1.0)) fail(child(path, "max_stiffness_ratio"), "must be at least 1 (the contact's stiffness at most this many times the stiffest element holding its node)");
    spec.max_stiffness_ratio = *ratio;
  }
  if (entry.contains("sliding_tangent")) spec.sliding_tangent = boolean(entry["sliding_tangent"], child(path, "sliding_tangent"));
  if (auto mu = optional_number(entry, "friction", path)) {
    if (!(*mu >= 0.0 && *mu <= 10.0)) fail(child(path, "friction"), "must lie between 0 and 10 (Coulomb's coefficient)");
    if (*mu > 0.0 && spec.frame == ContactFrame::cantilever)
      fail(child(path, "friction"), "friction is not in the cantilever frame yet (use the chord frame)");
    spec.friction = *mu;
  }
  if (auto gap = optional_number(entry, "gap", path)) {
    if (*gap < 0.0) fail(child(path, "gap"), "must not be negative");
    spec.gap = *gap;
  }
}

}  // namespace tsm::io
