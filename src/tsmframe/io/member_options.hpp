#pragma once
// A member entry's options beyond its ends, mesh and section (FORMAT: "load", "end_springs",
// "arc"), read into its MemberInput, each checked with its JSON path. The member's ends, its
// element, section and release are the model reader's.

#include <nlohmann/json.hpp>
#include <string>

#include "tsmframe/model/mesh.hpp"

namespace tsm::io {

/// A member's "load": force per unit length in global x and y, and a follower pressure.
void read_member_load(const nlohmann::json& load, const std::string& path, MemberInput& member);
/// Rotational springs at a member's ends (semi-rigid connections), kept as flexibilities 1/k;
/// read after the member's release (a spring beside a hinge is refused).
void read_end_springs(const nlohmann::json& springs, const std::string& path, MemberInput& member);
/// A member's "arc" (its centre and sweep; whether it joins the member's nodes is the mesh's check).
Arc read_arc(const nlohmann::json& arc, const std::string& path);

}  // namespace tsm::io
