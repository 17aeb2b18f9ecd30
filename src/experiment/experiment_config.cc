#include "experiment/experiment_config.h"

#include <algorithm>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>

#include "contact/model_registry.h"
#include "contact/unbuilt_models.h"
#include "experiment/study.h"
#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"

namespace contactlab {
namespace {

// Short sweep-axis names and the key paths they stand for.
// The sweep aliases of a config of STUDY: the scene's (its parameter tables name the keys a sweep
// may name alone, scene/scene.h), the harness's own, and the study's.
// Built afresh at each call (a few dozen keys), never cached: a model registered later (a test's,
// a Python one) brings its keys with it.
std::map<std::string, std::string> AxisAliases(const Study& study) {
  std::map<std::string, std::string> a;
  for (const SceneBlock& block : SceneBlocks()) {
    for (const std::string& key : block.sweep_keys) {
      if (!a.emplace(block.alias_prefix + key, block.path + key).second) {
        Fail("sweep aliases", "'" + block.alias_prefix + key + "' names keys of two scene blocks");
      }
    }
  }
  a["model"] = "models";
  a["scene"] = "scene";
  a["roles"] = "";
  for (const auto& [alias, path] : study.aliases) {
    if (!a.emplace(alias, path).second) {
      Fail("sweep aliases", "study " + study.name + "'s alias '" + alias + "' is already a scene or harness alias");
    }
  }
  return a;
}

std::string AliasList(const std::map<std::string, std::string>& aliases) {
  std::string list;
  for (const auto& [name, path] : aliases) list += (list.empty() ? "" : ", ") + name;
  return list;
}

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

std::string ScalarText(const ConfigNode& n) {
  if (!n.IsScalar()) n.Fail("a sweep value must be a single value (or {label: NAME, value: ...})");
  return n.AsString();
}

// The documents one job is parsed from.
struct JobDocuments {
  YAML::Node config;
  YAML::Node scene;
  std::string scene_file;
  std::string scene_text;  // the scene file's text (empty: an inline scene)
  bool roles_swapped = false;
};

// Loads the scene file NAME (data search path, first from the folder of CONFIG_FILE) as a
// document.
void LoadSceneDocument(const std::string& name, const std::string& config_file, JobDocuments* docs) {
  const std::filesystem::path file = RequireDataFile(name, FolderOf(config_file));
  docs->scene_text = ConfigNode::ReadText(file);
  docs->scene = ConfigNode::LoadString(docs->scene_text, file.string()).yaml();
  docs->scene_file = file.string();
}

// Exchanges the roles of the scene's two bodies.
void SwapRoles(JobDocuments* docs, const std::string& where) {
  YAML::Node bodies = docs->scene["bodies"];
  if (!bodies || !bodies.IsSequence()) Fail(where, "the scene has no list of bodies to swap");
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    YAML::Node role = bodies[i]["role"];
    if (!role || !role.IsScalar()) continue;  // the scene parser names the missing role
    const std::string r = role.Scalar();
    bodies[i]["role"] = r == "pointshell" ? "field" : r == "field" ? "pointshell" : r;
  }
  docs->roles_swapped = !docs->roles_swapped;
}

// Writes value V of AXIS into DOCS.
void ApplyAxis(const SweepAxis& axis, std::size_t v, const std::string& config_file, JobDocuments* docs,
               const std::string& where) {
  const std::string& value = axis.values[v];
  const bool labelled = v < axis.labelled_yaml.size() && !axis.labelled_yaml[v].empty();
  if (labelled && (axis.name == "roles" || axis.path == "scene" || axis.path == "models")) {
    Fail(where, "takes a plain value, not {label, value}");
  }
  if (axis.name == "roles") {
    if (value == "swapped") {
      SwapRoles(docs, where);
    } else if (value != "normal") {
      Fail(where, "must be normal or swapped");
    }
    return;
  }
  if (axis.path == "scene") {
    LoadSceneDocument(value, config_file, docs);
    docs->config["scene"] = value;
    return;
  }
  std::optional<YAML::Node> node;
  if (labelled) {
    node = YAML::Load(axis.labelled_yaml[v]);
  } else if (value != "default") {
    node = YAML::Node(value);
  }
  if (axis.path == "models" && node) {
    YAML::Node list(YAML::NodeType::Sequence);
    list.push_back(value);
    node = list;
  }
  // The deformed-field aliases write into the field body's deformable block; they must not
  // create one (that would make a rigid body deformable with every default).
  if (axis.path.rfind("scene.bodies[role=field].deformable.", 0) == 0 && axis.name.find('.') == std::string::npos) {
    bool deformable = false;
    const YAML::Node bodies = docs->scene["bodies"];
    for (std::size_t i = 0; bodies && bodies.IsSequence() && i < bodies.size(); ++i) {
      const YAML::Node b = bodies[i];
      if (b["role"] && b["role"].IsScalar() && b["role"].Scalar() == "field") {
        deformable = b["deformable"] && b["deformable"].IsMap();
      }
    }
    if (!deformable) Fail(where, "the scene's field body has no deformable block (" + axis.name + " sets its deformed field)");
  }
  if (axis.path.rfind("scene.", 0) == 0) {
    SetAtPath(docs->scene, axis.path.substr(6), node, where);
  } else {
    SetAtPath(docs->config, axis.path, node, where);
  }
}

// The field body's name in a scene document (what the scene parser would name it); a scene of
// many bodies: its tool.
std::string FieldBodyName(const YAML::Node& scene) {
  if (scene["tool"] && scene["tool"].IsScalar()) return scene["tool"].Scalar();
  const YAML::Node bodies = scene["bodies"];
  if (!bodies || !bodies.IsSequence()) return "";
  for (std::size_t i = 0; i < bodies.size(); ++i) {
    const YAML::Node b = bodies[i];
    if (b["role"] && b["role"].IsScalar() && b["role"].Scalar() == "field") {
      if (b["name"] && b["name"].IsScalar()) return b["name"].Scalar();
      if (b["mesh"] && b["mesh"].IsScalar()) return b["mesh"].Scalar();
    }
  }
  return "";
}

// Builds job INDEX with the axis values PICK (one index per axis) from CONFIG's documents.
Job BuildJob(const ExperimentConfig& config, int index, const std::vector<std::size_t>& pick) {
  // Each job's own copy of the documents, parsed again from their text where it is known so
  // every node keeps its line (YAML::Clone drops the marks: an error in a job's trajectory
  // would otherwise be reported at line 1).
  JobDocuments docs{config.document_text.empty() ? YAML::Clone(config.document) : YAML::Load(config.document_text),
                    {}, config.scene_file, config.scene_text};
  if (!config.scene_text.empty()) {
    docs.scene = YAML::Load(config.scene_text);
  } else if (config.scene_file == config.file && !config.document_text.empty()) {
    docs.scene = YAML::Load(config.document_text)["scene"];  // an inline scene, from its own parse
  } else {
    docs.scene = YAML::Clone(config.scene_document);
  }
  auto at = [&](std::size_t a) {
    return config.file + ": sweep." + config.sweep[a].name + " value '" + config.sweep[a].values[pick[a]] + "'";
  };
  // The scene first, then roles, so the other axes apply to the bodies' final roles.
  std::string moving_body = config.moving_body;
  for (const char* first : {"scene", "roles", ""}) {
    for (std::size_t a = 0; a < config.sweep.size(); ++a) {
      const std::string& name = config.sweep[a].name;
      const bool early = name == "scene" || name == "roles";
      if (*first ? name != first : early) continue;
      ApplyAxis(config.sweep[a], pick[a], config.file, &docs, at(a));
    }
    // Unless the config names it, the moving body is the field body of the job's scene
    // (before a role swap, so the same physical body moves in both role orders).
    if (std::string(first) == "scene" && config.moving_body_is_default) moving_body = FieldBodyName(docs.scene);
  }
  Job job;
  job.index = index;
  for (std::size_t a = 0; a < config.sweep.size(); ++a) {
    job.axis_values.emplace_back(config.sweep[a].name, config.sweep[a].values[pick[a]]);
  }
  const auto file = std::make_shared<const std::string>(config.file);
  // An inline scene's keys are named from the config's top ("scene.bodies[0]...").
  const std::string scene_path = docs.scene_file == config.file ? "scene" : "";
  job.scene = ParseScene(ConfigNode(docs.scene, std::make_shared<const std::string>(docs.scene_file), scene_path));
  if (docs.roles_swapped) job.scene.name += " (roles swapped)";
  job.roles_swapped = docs.roles_swapped;
  const ConfigNode root(docs.config, file, "");
  job.models = config.models;
  if (auto m = root.Find("models")) {
    job.models.clear();
    for (const ConfigNode& e : m->Elements()) job.models.push_back(e.AsString());
    if (job.models.empty()) m->Fail("lists no model");
  }
  job.moving_body = moving_body;
  if (job.moving_body != job.scene.field_body.name && job.moving_body != job.scene.pointshell_body.name) {
    Fail(config.file, "moving_body '" + job.moving_body + "' is not a body of the scene of job " +
                          std::to_string(index));
  }
  if (auto t = root.Find("trajectory")) job.trajectory_node = *t;
  job.config = root;
  return job;
}

}  // namespace

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

std::string Job::Label() const {
  std::string s;
  for (const auto& [axis, value] : axis_values) s += (s.empty() ? "" : " ") + axis + "=" + value;
  return s.empty() ? "(single run)" : s;
}

ExperimentConfig LoadExperimentConfig(const std::filesystem::path& config_file, const std::vector<std::string>& given,
                                      const std::string& profile) {
  const std::string text = ConfigNode::ReadText(config_file);
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    FailAtLine(config_file.string(), e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
  if (!root.IsMap()) Fail(config_file.string(), "an experiment config must be a mapping");
  // A profile's overrides come first, then those given on the command line.
  std::vector<std::string> overrides;
  if (!profile.empty()) {
    const YAML::Node p = root["profiles"] ? root["profiles"][profile] : YAML::Node();
    if (!p || !p.IsMap()) {
      std::string known;
      if (root["profiles"] && root["profiles"].IsMap()) {
        for (const auto& kv : root["profiles"]) {
          if (kv.first.IsScalar()) known += (known.empty() ? "" : ", ") + kv.first.Scalar();
        }
      }
      Fail(config_file.string(), "has no profile '" + QuoteToken(profile) + "' (under 'profiles'); " +
                                     (known.empty() ? std::string("it has no profiles") : "its profiles: " + known));
    }
    for (const auto& kv : p) {
      YAML::Emitter e;
      e << YAML::Flow << kv.second;
      overrides.push_back(kv.first.as<std::string>() + "=" + e.c_str());
    }
  }
  overrides.insert(overrides.end(), given.begin(), given.end());
  for (const std::string& o : overrides) ApplyOverride(root, o, config_file.string());
  YAML::Emitter emitter;
  emitter << root;
  const std::string resolved = emitter.c_str();
  // Re-parse the emitted text so error line numbers refer to the resolved config when
  // overrides were given, and to the file itself otherwise.
  const std::string& parsed = overrides.empty() ? text : resolved;
  const ConfigNode node =
      ConfigNode::LoadString(parsed, overrides.empty() ? config_file.string() : config_file.string() + " (with --set)");
  return ParseExperimentConfig(node, resolved, parsed);
}

namespace {

// The reference a contact study's models are measured against: a model name, or a denser
// version of the scene ({model, points, levels, resolution}).
void ParseReference(const ConfigNode& root, ExperimentConfig* config) {
  ExperimentConfig& c = *config;
  if (auto r = root.Find("reference"); r && r->IsMap()) {
    r->ExpectKeys({"model", "points", "levels", "resolution"});
    c.reference_model = r->Get("model").AsString();
    c.reference_points = int(r->IntInRange("points", 0, 1, kMaxPointshellPoints));
    c.reference_levels = int(r->IntInRange("levels", 0, 1, kMaxPointshellLevels));
    c.reference_resolution = int(r->IntInRange("resolution", 0, 8, kMaxFieldResolution));
  } else {
    c.reference_model = root.String("reference", "");
  }
  c.reference_every = int(root.PositiveInt("reference_every", 1));
  if (!c.reference_model.empty() && FindContactModel(c.reference_model) == nullptr &&
      !UnbuiltContactModelReason(c.reference_model)) {
    const ConfigNode r = root.Get("reference");
    const ConfigNode named = r.IsMap() ? r.Get("model") : r;
    CheckContactModel(c.reference_model, c.scene.model, c.scene.model_params, c.scene.pointshell_body.name, false,
                      c.scene.field_body.name, false, named.Location());  // throws, naming the known models
  }
}

// The number of jobs of SWEEP (the product of its axes' lengths), refused above kMaxSweepJobs
// before any value is read or any job built; the product is formed so that it cannot overflow.
void CheckSweepJobCount(const ConfigNode& sweep) {
  if (!sweep.IsMap()) return;  // ParseSweep names what it is
  unsigned long long jobs = 1;
  bool overflow = false;
  std::string lengths;
  for (const auto& kv : sweep.yaml()) {
    const std::size_t n = kv.second.IsSequence() ? kv.second.size() : 1;
    lengths += (lengths.empty() ? "" : " x ") + std::to_string(n);
    overflow = overflow || __builtin_mul_overflow(jobs, n, &jobs);
  }
  if (overflow || jobs > kMaxSweepJobs) {
    sweep.Fail(lengths + " values make " + (overflow ? "more than 2^64" : std::to_string(jobs)) +
               " jobs; a sweep may have at most " + std::to_string(kMaxSweepJobs) +
               " (split it into several configs, or sweep fewer values)");
  }
}

// The sweep axes, in order: an alias of STUDY (or the scene's) or a key path, each with its values.
std::vector<SweepAxis> ParseSweep(const ConfigNode& root, const Study& study) {
  std::vector<SweepAxis> sweep;
  if (auto s = root.Find("sweep")) {
    CheckSweepJobCount(*s);
    const std::map<std::string, std::string> aliases = AxisAliases(study);
    for (const std::string& key : s->Keys()) {
      const ConfigNode axis = s->Get(key);
      SweepAxis a{key, key, {}, {}};
      if (auto alias = aliases.find(key); alias != aliases.end()) {
        a.path = alias->second;
      } else if (key.find_first_of(".[") == std::string::npos) {
        axis.Fail("unknown sweep axis: give a key path (e.g. scene.model.k_C, trajectory.depth) or one of " +
                  AliasList(aliases));
      }
      // A value: a scalar, or {label: NAME, value: ANY}.
      auto add = [&](const ConfigNode& v) {
        if (v.IsMap()) {
          v.ExpectKeys({"label", "value"});
          const std::string label = ScalarText(v.Get("label"));
          if (label.empty() || label.find_first_of(",\n\r\"") != std::string::npos) {
            v.Get("label").Fail("a label must be a non-empty name without commas, quotes or line breaks");
          }
          YAML::Emitter e;
          e << YAML::Flow << v.Get("value").yaml();
          a.values.push_back(label);
          a.labelled_yaml.push_back(e.c_str());
        } else {
          a.values.push_back(ScalarText(v));
          a.labelled_yaml.emplace_back();
        }
      };
      if (axis.IsSequence()) {
        for (const ConfigNode& v : axis.Elements()) add(v);
      } else {
        add(axis);
      }
      if (a.values.empty()) axis.Fail("a sweep axis needs at least one value");
      sweep.push_back(a);
    }
  }
  return sweep;
}

// Every sweep value on its own (so an error names its axis and value), so errors come before any
// work; the combinations are checked as the jobs expand.
void CheckEachSweepValue(const ExperimentConfig& c) {
  for (std::size_t a = 0; a < c.sweep.size(); ++a) {
    for (std::size_t v = 0; v < c.sweep[a].values.size(); ++v) {
      ExperimentConfig one = c;
      one.sweep = {c.sweep[a]};
      one.sweep[0].values = {c.sweep[a].values[v]};
      one.sweep[0].labelled_yaml = {c.sweep[a].labelled_yaml[v]};
      try {
        (void)BuildJob(one, 0, {0});
      } catch (const Error& e) {
        const std::string at = c.file + ": sweep." + c.sweep[a].name + " value '" + c.sweep[a].values[v] + "'";
        const std::string msg = e.what();
        if (msg.rfind(at, 0) == 0) throw;
        Fail(at, msg);
      }
    }
  }
}

// Where model NAME was written in the config ROOT: its entry of the models list, or of a sweep
// over models (`model:` or `models:`), with file and line; the scene file's models list when the
// config names it nowhere (the job's models are then the scene's).
std::string ModelLocation(const ConfigNode& root, const Job& job, const std::string& name) {
  std::vector<ConfigNode> lists;
  if (auto m = root.Find("models")) lists.push_back(*m);
  if (auto sweep = root.Find("sweep"); sweep && sweep->IsMap()) {
    for (const char* key : {"model", "models"}) {
      if (auto axis = sweep->Find(key)) lists.push_back(*axis);
    }
  }
  for (const ConfigNode& list : lists) {
    if (!list.IsSequence()) continue;
    for (const ConfigNode& e : list.Elements()) {
      if (e.IsScalar() && e.AsString() == name) return e.Location();
    }
  }
  if (!lists.empty()) return lists.front().Location();
  return job.scene.file + ": models";
}

// What a job's models refuse of its scene (a name no model is registered under, a deformable
// body a model treats as rigid, coherence against a deformed field, ...), said before any job
// builds its assets. An unknown name is blamed on the list that holds it (the config's, or its
// scene's when the config names no models), not on the scene the run would build it for.
void CheckModelsAgainstScene(const ExperimentConfig& c, const ConfigNode& root, const Job& job) {
  const Scene& s = job.scene;
  const std::string where = c.file + (c.sweep.empty() ? std::string() : " (job " + job.Label() + ")");
  for (const std::string& name : job.models) {
    // A model this program was built without (contact/unbuilt_models.h) is left to the run,
    // so that listing and expanding jobs works in every build.
    if (FindContactModel(name) == nullptr && UnbuiltContactModelReason(name)) continue;
    if (FindContactModel(name) == nullptr) {
      CheckContactModel(name, s.model, s.model_params, s.pointshell_body.name, false, s.field_body.name, false,
                        ModelLocation(root, job, name));  // throws, naming the known models
    }
    if (s.many_bodies()) {
      // Every pair without a model of its own takes it, each in the A/B order its model needs.
      for (const PairSpec& pair : s.pairs) (void)OrderPair(s, pair, name);
      continue;
    }
    CheckContactModel(name, s.model, s.model_params, s.pointshell_body.name, s.pointshell_body.deformable.has_value(),
                      s.field_body.name, s.field_body.deformable.has_value(), where);
  }
}

}  // namespace

ExperimentConfig ParseExperimentConfig(const ConfigNode& root, std::string resolved_yaml, std::string document_text) {
  // The keys every study reads, then those of the config's study; a key only other studies read
  // is a mistake, not ignored.
  std::vector<std::string> keys;
  for (const ConfigKey& k : CommonConfigKeys()) keys.push_back(k.key);
  ExperimentConfig c;
  c.study = root.OneOf("study", c.study, StudyNames());
  const Study& study = *FindStudy(c.study);
  for (const ConfigKey& k : study.sections) keys.push_back(k.key);
  for (const Study& other : Studies()) {
    for (const ConfigKey& section : other.sections) {
      const std::string& key = section.key;
      if (std::find(keys.begin(), keys.end(), key) != keys.end() || !root.Has(key)) continue;
      std::string readers;
      for (const Study& s : Studies()) {
        if (s.Reads(key)) readers += (readers.empty() ? "" : ", ") + s.name;
      }
      root.Get(key).Fail("is not read by study: " + c.study + " (it belongs to study: " + readers + ")");
    }
  }
  root.ExpectKeys(keys);
  for (const std::string& key : study.required) (void)root.Get(key);
  if (auto t = root.Find("trajectory")) c.trajectory_node = *t;
  c.timing = study.timing;
  c.file = root.file();
  c.resolved_yaml = std::move(resolved_yaml);
  c.document = YAML::Clone(root.yaml());
  c.document_text = std::move(document_text);
  c.name = root.String("name", std::filesystem::path(root.file()).stem().string());
  // The name chooses the results folder results/NAME: a plain name, never a path.
  const bool plain = !c.name.empty() && c.name != "." && c.name != ".." &&
                     std::none_of(c.name.begin(), c.name.end(),
                                  [](char ch) { return ch == '/' || ch == '\\' || (unsigned char)ch < 0x20; });
  if (!plain) root.Get("name").Fail("must be a plain name (it chooses the folder results/NAME), got '" + c.name + "'");
  c.description = root.String("description", "");
  const ConfigNode scene = root.Get("scene");
  if (scene.IsScalar()) {
    JobDocuments docs;
    LoadSceneDocument(scene.AsString(), root.file(), &docs);
    c.scene_document = docs.scene;
    c.scene_file = docs.scene_file;
    c.scene_text = docs.scene_text;
  } else {
    scene.ExpectMap();
    c.scene_document = YAML::Clone(scene.yaml());
    c.scene_file = root.file();
  }
  c.scene = ParseScene(ConfigNode(c.scene_document, std::make_shared<const std::string>(c.scene_file),
                                  scene.IsScalar() ? "" : "scene"));
  if (!study.many_bodies) {
    c.scene.RequireTwoBodies("an experiment of study: " + c.study);
  } else if (!c.scene.many_bodies()) {
    scene.Fail("study: " + c.study + " takes a scene of many bodies (tool: NAME, and pairs); " + c.scene.file +
               " has two bodies and no tool (study: contact compares models on it)");
  }
  if (auto m = root.Find("models")) {
    for (const ConfigNode& e : m->Elements()) c.models.push_back(e.AsString());
    if (c.models.empty()) m->Fail("lists no model");
  } else {
    c.models = c.scene.models;
  }
  // The field body of a two-body scene, the tool of one of many (Scene: its field_body).
  c.moving_body = root.String("moving_body", c.scene.field_body.name);
  c.moving_body_is_default = !root.Has("moving_body");
  if (c.moving_body != c.scene.field_body.name && c.moving_body != c.scene.pointshell_body.name) {
    root.Get("moving_body").Fail("'" + c.moving_body + "' is not a body of the scene");
  }
  ParseReference(root, &c);
  if (auto m = root.Find("metrics")) {
    m->ExpectKeys({"cutoff_hz", "timing"});
    c.cutoff_hz = m->Positive("cutoff_hz", c.cutoff_hz);
    c.timing = m->Bool("timing", c.timing);
  }
  c.sweep = ParseSweep(root, study);
  CheckEachSweepValue(c);
  // Every job, built one at a time: what its models refuse of its scene, then its study's checks.
  ForEachJob(c, [&](const Job& job) {
    CheckModelsAgainstScene(c, root, job);
    if (study.check) study.check(c, root, job);
  });
  return c;
}

namespace {

// The value picked on each sweep axis by job INDEX (the last axis varies fastest), and back.
std::vector<std::size_t> AxisPicks(const ExperimentConfig& config, std::size_t index) {
  std::vector<std::size_t> pick(config.sweep.size());
  for (std::size_t a = config.sweep.size(); a-- > 0;) {
    pick[a] = index % config.sweep[a].values.size();
    index /= config.sweep[a].values.size();
  }
  return pick;
}

std::size_t JobIndex(const ExperimentConfig& config, const std::vector<std::size_t>& pick) {
  std::size_t index = 0;
  for (std::size_t a = 0; a < config.sweep.size(); ++a) index = index * config.sweep[a].values.size() + pick[a];
  return index;
}

}  // namespace

std::optional<Job> ConfigRoleOrderJob(const ExperimentConfig& config, const Job& job) {
  if (!job.roles_swapped) return job;
  std::vector<std::size_t> pick = AxisPicks(config, std::size_t(job.index));
  for (std::size_t a = 0; a < config.sweep.size(); ++a) {
    if (config.sweep[a].name != "roles") continue;
    const auto& values = config.sweep[a].values;
    const auto normal = std::find(values.begin(), values.end(), "normal");
    if (normal == values.end()) return std::nullopt;
    pick[a] = std::size_t(normal - values.begin());
    return BuildJob(config, int(JobIndex(config, pick)), pick);
  }
  return std::nullopt;
}

std::size_t JobCount(const ExperimentConfig& config) {
  std::size_t total = 1;
  for (const SweepAxis& a : config.sweep) total *= a.values.size();  // <= kMaxSweepJobs: checked at load
  return total;
}

std::string JobLabel(const ExperimentConfig& config, std::size_t index) {
  const std::vector<std::size_t> pick = AxisPicks(config, index);
  std::string label;
  for (std::size_t a = 0; a < config.sweep.size(); ++a) {
    label += (label.empty() ? "" : " ") + config.sweep[a].name + "=" + config.sweep[a].values[pick[a]];
  }
  return label.empty() ? "(single run)" : label;
}

Job ExpandJob(const ExperimentConfig& config, std::size_t index) {
  if (index >= JobCount(config)) {
    throw std::logic_error("job " + std::to_string(index) + " of a sweep of " + std::to_string(JobCount(config)));
  }
  try {
    return BuildJob(config, int(index), AxisPicks(config, index));
  } catch (const Error& e) {
    const std::string msg = e.what();
    if (msg.rfind(config.file + ": sweep.", 0) == 0) throw;
    Fail(config.file + ": job " + std::to_string(index) + " (" + JobLabel(config, index) + ")", msg);
  }
}

void ForEachJob(const ExperimentConfig& config, const std::function<void(const Job&)>& visit) {
  for (std::size_t index = 0, total = JobCount(config); index < total; ++index) visit(ExpandJob(config, index));
}

std::vector<Job> ExpandJobs(const ExperimentConfig& config) {
  std::vector<Job> jobs;
  ForEachJob(config, [&](const Job& job) { jobs.push_back(job); });
  return jobs;
}

}  // namespace contactlab
