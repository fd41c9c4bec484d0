#include "tsmframe/io/member_options.hpp"

#include <cmath>
#include <numbers>

#include "tsmframe/io/input_error.hpp"
#include "tsmframe/io/json_input.hpp"

namespace tsm::io {

using nlohmann::json;

void read_member_load(const json& load, const std::string& path, MemberInput& member) {
  expect_object(load, path);
  check_keys(load, path, {"fx", "fy", "pressure"});
  if (auto fx = optional_number(load, "fx", path)) member.load.x() = *fx;
  if (auto fy = optional_number(load, "fy", path)) member.load.y() = *fy;
  if (auto p = optional_number(load, "pressure", path)) member.pressure = *p;
  if (member.load.x() == 0.0 && member.load.y() == 0.0 && member.pressure == 0.0)
    fail(path, "give fx, fy or pressure (force per unit length)");
}

void read_end_springs(const json& springs, const std::string& path, MemberInput& member) {
  expect_object(springs, path);
  check_keys(springs, path, {"start", "end"});
  for (const std::string end : {"start", "end"}) {
    if (!springs.contains(end)) continue;
    const std::string epath = child(path, end);
    const double stiffness = number(springs[end], epath);
    if (!(stiffness > 0.0) || !std::isfinite(stiffness))
      fail(epath, "a rotational spring's stiffness (moment per radian) must be a positive finite number (a hinge is \"release\")");
    if ((end == "start" && member.release_start) || (end == "end" && member.release_end))
      fail(epath, "that end is released (a hinge): a spring there holds nothing");
    (end == "start" ? member.flexibility_from : member.flexibility_to) = 1.0 / stiffness;
  }
  if (!springs.contains("start") && !springs.contains("end")) fail(path, "give start or end (rotational stiffness, moment per radian)");
}

Arc read_arc(const json& arc, const std::string& path) {
  expect_object(arc, path);
  check_keys(arc, path, {"center", "sweep"});
  if (!arc.contains("center")) fail(child(path, "center"), "missing (required)");
  Arc out;
  out.centre = point(arc["center"], child(path, "center"));
  out.sweep = required_number(arc, "sweep", path);
  if (out.sweep == 0.0 || std::abs(out.sweep) > 2.0 * std::numbers::pi * (1 + 1e-12))
    fail(child(path, "sweep"), "must be non-zero and at most 2π in size");
  return out;
}

}  // namespace tsm::io
