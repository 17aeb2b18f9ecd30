// Key paths of experiment configs (experiment_config.h): a path such as
// scene.bodies[name=ball].field.resolution or sweep.AXIS parsed into steps, a value set at one
// (SetAtPath: sweeps, profiles and --set) and the assignments of --set.
#include "experiment/key_paths.h"

#include <string>
#include <vector>

#include "experiment/experiment_config.h"
#include "util/error.h"

namespace contactlab {
namespace {

// One step of a key path: a key, optionally picking an element of the list it holds.
struct PathStep {
  std::string key;
  bool pick = false;
  std::string field;  // "" with pick: by index
  std::string value;  // the index, or the field's value
};

std::vector<PathStep> ParsePath(const std::string& path, const std::string& where) {
  std::vector<PathStep> steps;
  std::size_t i = 0;
  while (i <= path.size()) {
    std::size_t end = path.find('.', i);
    // A dot inside [...] belongs to the selector.
    const std::size_t open = path.find('[', i);
    if (open != std::string::npos && open < end) {
      const std::size_t close = path.find(']', open);
      if (close == std::string::npos) Fail(where, "unclosed '[' in key path '" + path + "'");
      end = path.find('.', close);
    }
    if (end == std::string::npos) end = path.size();
    const std::string part = path.substr(i, end - i);
    PathStep step;
    const std::size_t b = part.find('[');
    step.key = part.substr(0, b);
    if (b != std::string::npos) {
      if (part.back() != ']') Fail(where, "key path '" + path + "': text after ']'");
      const std::string sel = part.substr(b + 1, part.size() - b - 2);
      step.pick = true;
      const std::size_t eq = sel.find('=');
      if (eq == std::string::npos) {
        step.value = sel;
        if (sel != "*" && (sel.empty() || sel.find_first_not_of("0123456789") != std::string::npos)) {
          Fail(where, "key path '" + path + "': '[" + sel + "]' is neither an index, field=value nor *");
        }
      } else {
        step.field = sel.substr(0, eq);
        step.value = sel.substr(eq + 1);
      }
    }
    if (step.key.empty()) Fail(where, "empty key in key path '" + path + "'");
    steps.push_back(step);
    i = end + 1;
  }
  return steps;
}

// The '=' that ends the key path of ASSIGNMENT: the first one outside a "[field=value]"
// selector (npos when there is none).
std::size_t AssignmentEquals(const std::string& assignment) {
  int depth = 0;
  for (std::size_t i = 0; i < assignment.size(); ++i) {
    const char c = assignment[i];
    if (c == '[') ++depth;
    if (c == ']' && depth > 0) --depth;
    if (c == '=' && depth == 0) return i;
  }
  return std::string::npos;
}

}  // namespace

// Sets ROOT[path] = VALUE (YAML text), creating maps along the path, for --set and profiles.
void ApplyOverride(YAML::Node root, const std::string& assignment, const std::string& file) {
  const auto eq = AssignmentEquals(assignment);
  if (eq == std::string::npos || eq == 0) Fail("--set " + assignment, "expected key.path=value");
  YAML::Node value;
  try {
    // An empty value means an empty string ("--set reference=" turns the reference off).
    value = eq + 1 == assignment.size() ? YAML::Node(std::string()) : YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    Fail("--set " + assignment, "the value is not valid YAML: " + e.msg);
  }
  const std::string path = assignment.substr(0, eq);
  const std::string where = "--set " + assignment + " (in " + file + ")";
  // A sweep axis is named by a key path itself ("sweep.scene.bodies[role=field].field"): what
  // follows "sweep." is one key of the sweep mapping, not more steps of the path.
  const std::string sweep_prefix = "sweep.";
  if (path.size() > sweep_prefix.size() && path.compare(0, sweep_prefix.size(), sweep_prefix) == 0) {
    YAML::Node sweep = root["sweep"];
    if (sweep && !sweep.IsMap()) Fail(where, "cannot set '" + path + "': 'sweep' is not a mapping");
    if (!sweep) root["sweep"] = YAML::Node(YAML::NodeType::Map);
    root["sweep"][path.substr(sweep_prefix.size())] = value;
    return;
  }
  SetAtPath(root, path, value, where);
}

void SetAtPath(YAML::Node doc, const std::string& path, const std::optional<YAML::Node>& value,
               const std::string& where) {
  const std::vector<PathStep> steps = ParsePath(path, where);
  std::vector<YAML::Node> chain{doc};
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const PathStep& s = steps[i];
    const bool last = i + 1 == steps.size();
    YAML::Node parent = chain.back();
    if (!parent.IsMap() && !(parent.IsNull() && !parent.IsDefined())) {
      Fail(where, "cannot set '" + path + "': the value before '" + s.key + "' is not a mapping");
    }
    if (last && !s.pick) {
      if (value) {
        parent[s.key] = *value;
      } else {
        parent.remove(s.key);
      }
      return;
    }
    YAML::Node next = parent[s.key];
    if (!s.pick) {
      if (next && !next.IsMap()) Fail(where, "cannot set '" + path + "': '" + s.key + "' is not a mapping");
      if (!next) {
        parent[s.key] = YAML::Node(YAML::NodeType::Map);
        next = parent[s.key];
      }
      chain.push_back(next);
      continue;
    }
    // Pick an element of the list under s.key.
    if (!next || !next.IsSequence()) Fail(where, "cannot set '" + path + "': '" + s.key + "' is not a list");
    if (s.field.empty() && s.value == "*") {
      // "key[*]": every element gets the rest of the path (scene.bodies[*].inner_spheres.coverage
      // sets both bodies' packings from one sweep axis).
      if (next.size() == 0) Fail(where, "key path '" + path + "': '" + s.key + "' is an empty list");
      if (last) Fail(where, "key path '" + path + "': [*] needs a key after it");
      std::string rest;
      for (std::size_t j = i + 1; j < steps.size(); ++j) {
        rest += (rest.empty() ? "" : ".") + steps[j].key;
        if (steps[j].pick) rest += "[" + (steps[j].field.empty() ? "" : steps[j].field + "=") + steps[j].value + "]";
      }
      for (std::size_t e = 0; e < next.size(); ++e) SetAtPath(next[e], rest, value, where);
      return;
    }
    std::size_t found = next.size();
    for (std::size_t e = 0; e < next.size(); ++e) {
      const bool match = s.field.empty() ? std::to_string(e) == s.value
                                         : (next[e].IsMap() && next[e][s.field] && next[e][s.field].IsScalar() &&
                                            next[e][s.field].Scalar() == s.value);
      if (match) {
        if (found != next.size()) Fail(where, "key path '" + path + "': more than one element of '" + s.key +
                                                  "' has " + s.field + " = " + s.value);
        found = e;
      }
    }
    if (found == next.size()) {
      Fail(where, "key path '" + path + "': no element of '" + s.key + "' " +
                      (s.field.empty() ? "at index " + s.value : "has " + s.field + " = " + s.value));
    }
    if (last) {
      if (!value) Fail(where, "key path '" + path + "': a list element cannot be removed");
      next[found] = *value;
      return;
    }
    chain.push_back(next[found]);
  }
}

}  // namespace contactlab
