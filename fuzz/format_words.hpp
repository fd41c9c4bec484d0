#pragma once
// The words of the input formats (model files, study files): keys and enumerated values, for the
// structural mutator to rename keys to, add keys under and put in strings. A key or value the
// readers do not know is as useful (its refusal is tested too): the mutator adds the words of
// each document it mutates as well.

#include <string>
#include <vector>

namespace tsm::fuzz {

inline std::vector<std::string> format_words() {
  return {
      // model files
      "format", "tsmframe-model/1", "title", "units", "length", "force", "materials", "E", "G", "nu", "sections", "A",
      "I", "shear_area", "nodes", "id", "x", "y", "members", "from", "to", "divisions", "element", "timoshenko",
      "euler-bernoulli", "material", "section", "arc", "center", "sweep", "release", "start", "end", "both",
      "end_springs", "load", "fx", "fy", "mz", "pressure", "supports", "node", "fix", "type", "fixed", "pinned",
      "roller-x", "roller-y", "ux", "uy", "rz", "loads", "prescribed", "contacts", "element", "frame", "chord",
      "cantilever", "gap", "edge", "max_stiffness_ratio", "sliding_tangent", "all", "extra", "normal", "deflected",
      "between", "follower", "gravity", "density", "springs", "kx", "ky", "kr", "k", "direction", "foundation", "roller",
      "stages", "increment",
      // analysis
      "analysis", "control", "steps", "path", "displacement", "target", "arc-length", "initial_increment",
      "min_increment", "max_increment", "max_steps", "until", "value", "load_factor", "tolerance", "max_iterations",
      "cutback", "max_cutbacks", "output", "last", "every", "monitor",
      // study files
      "tsmframe-study/1", "model", "model_file", "name", "values", "range", "variants", "label", "set", "record",
      "quantity", "reaction", "contact_force", "contact_xi", "dof", "of", "max", "min", "max_abs", "keep",
      // JSON pointers of a study's sweep
      "/members/0/divisions", "/nodes/1/x", "/loads/0/fy", "/analysis/control/steps", "/contacts/0/gap", "/loads/-",
      "/supports", "/title"};
}

}  // namespace tsm::fuzz
