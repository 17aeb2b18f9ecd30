#include "experiment/experiment_config.h"

#include <sstream>

#include "util/atomic_file.h"
#include "util/data_path.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {
namespace {

const char* const kAxes[] = {"points",     "levels",   "method",          "resolution", "pointshell_resolution",
                             "k_C",        "node_budget", "coherence",     "max_point_speed", "level",
                             "model",      "roles",    "gradient",        "scene",      "offset"};

// Sets ROOT[path] = VALUE (YAML text), creating maps along the path.
void ApplyOverride(YAML::Node root, const std::string& assignment, const std::string& file) {
  const auto eq = assignment.find('=');
  if (eq == std::string::npos || eq == 0) Fail("--set " + assignment, "expected key.path=value");
  const std::string path = assignment.substr(0, eq);
  YAML::Node value;
  try {
    // An empty value means an empty string ("--set reference=" turns the reference off).
    value = eq + 1 == assignment.size() ? YAML::Node(std::string()) : YAML::Load(assignment.substr(eq + 1));
  } catch (const YAML::Exception& e) {
    Fail("--set " + assignment, "the value is not valid YAML: " + e.msg);
  }
  std::vector<std::string> keys;
  std::stringstream ss(path);
  for (std::string k; std::getline(ss, k, '.');) {
    if (k.empty()) Fail("--set " + assignment, "empty key in the path");
    keys.push_back(k);
  }
  std::vector<YAML::Node> chain{root};
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    YAML::Node next = chain.back()[keys[i]];
    if (next && !next.IsMap()) Fail("--set " + assignment, "'" + keys[i] + "' in " + file + " is not a mapping");
    if (!next) {
      chain.back()[keys[i]] = YAML::Node(YAML::NodeType::Map);
      next = chain.back()[keys[i]];
    }
    chain.push_back(next);
  }
  chain.back()[keys.back()] = value;
}

std::string ScalarText(const ConfigNode& n) {
  if (!n.IsScalar()) n.Fail("a sweep value must be a single value");
  return n.AsString();
}

}  // namespace

std::string Job::Label() const {
  std::string s;
  for (const auto& [axis, value] : axis_values) s += (s.empty() ? "" : " ") + axis + "=" + value;
  return s.empty() ? "(single run)" : s;
}

ExperimentConfig LoadExperimentConfig(const std::filesystem::path& config_file, const std::vector<std::string>& given,
                                      const std::string& profile) {
  const std::string text = ReadWholeFile(config_file);
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
    if (!p || !p.IsMap()) Fail(config_file.string(), "has no profile '" + profile + "' (under 'profiles')");
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
  const ConfigNode node = overrides.empty() ? ConfigNode::LoadString(text, config_file.string())
                                            : ConfigNode::LoadString(resolved, config_file.string() + " (with --set)");
  return ParseExperimentConfig(node, resolved);
}

ExperimentConfig ParseExperimentConfig(const ConfigNode& root, std::string resolved_yaml) {
  root.ExpectKeys({"name", "description", "scene", "models", "moving_body", "trajectory", "reference",
                   "reference_every", "metrics", "sweep", "profiles"});
  ExperimentConfig c;
  c.trajectory_node = root.Get("trajectory");
  c.file = root.file();
  c.resolved_yaml = std::move(resolved_yaml);
  c.name = root.String("name", std::filesystem::path(root.file()).stem().string());
  c.description = root.String("description", "");
  const ConfigNode scene = root.Get("scene");
  if (scene.IsScalar()) {
    c.scene = LoadScene(RequireDataFile(scene.AsString(), FolderOf(root.file())));
  } else {
    c.scene = ParseScene(scene);
  }
  if (auto m = root.Find("models")) {
    for (const ConfigNode& e : m->Elements()) c.models.push_back(e.AsString());
    if (c.models.empty()) m->Fail("lists no model");
  } else {
    c.models = c.scene.models;
  }
  c.moving_body = root.String("moving_body", c.scene.field_body.name);
  c.moving_body_is_default = !root.Has("moving_body");
  if (c.moving_body != c.scene.field_body.name && c.moving_body != c.scene.pointshell_body.name) {
    root.Get("moving_body").Fail("'" + c.moving_body + "' is not a body of the scene");
  }
  c.trajectory_node.ExpectMap();
  if (!c.trajectory_node.Has("type")) c.trajectory_node.Fail("missing required key 'type'");
  if (auto r = root.Find("reference"); r && r->IsMap()) {
    r->ExpectKeys({"model", "points", "levels", "resolution"});
    c.reference_model = r->Get("model").AsString();
    c.reference_points = int(r->PositiveInt("points", 0));
    c.reference_levels = int(r->PositiveInt("levels", 0));
    c.reference_resolution = int(r->PositiveInt("resolution", 0));
  } else {
    c.reference_model = root.String("reference", "");
  }
  c.reference_every = int(root.PositiveInt("reference_every", 1));
  if (auto m = root.Find("metrics")) {
    m->ExpectKeys({"cutoff_hz", "timing"});
    c.cutoff_hz = m->Positive("cutoff_hz", c.cutoff_hz);
    c.timing = m->Bool("timing", c.timing);
  }
  if (auto s = root.Find("sweep")) {
    for (const std::string& key : s->Keys()) {
      bool known = false;
      for (const char* a : kAxes) known = known || key == a;
      const ConfigNode axis = s->Get(key);
      if (!known) axis.Fail("unknown sweep axis (points, levels, method, resolution, pointshell_resolution, k_C, "
                            "node_budget, coherence, max_point_speed, level, model, roles, gradient, scene, offset)");
      SweepAxis a{key, {}};
      if (axis.IsSequence()) {
        for (const ConfigNode& v : axis.Elements()) a.values.push_back(ScalarText(v));
      } else {
        a.values.push_back(ScalarText(axis));
      }
      if (a.values.empty()) axis.Fail("a sweep axis needs at least one value");
      c.sweep.push_back(a);
    }
  }
  // Check every sweep value and the trajectory now, so errors come before any work.
  for (Job& job : ExpandJobs(c)) (void)job;
  (void)ParseTrajectory(c.trajectory_node);
  return c;
}

void ApplySweepValue(const std::string& axis, const std::string& value, Job* job, const std::string& where) {
  const std::string at = where + ": sweep." + axis + " value '" + value + "'";
  auto as_int = [&]() {
    const std::optional<long long> v = ParseInteger(value);
    if (!v) Fail(at, "is not an integer");
    return *v;
  };
  auto as_double = [&]() {
    const std::optional<double> v = ParseDouble(value);
    if (!v) Fail(at, "is not a number");
    return *v;
  };
  Scene& s = job->scene;
  if (axis == "points") {
    const long long v = as_int();
    if (v <= 0) Fail(at, "must be positive");
    s.pointshell_body.pointshell.points = int(v);
  } else if (axis == "levels") {
    const long long v = as_int();
    if (v <= 0) Fail(at, "must be positive");
    s.pointshell_body.pointshell.levels = int(v);
  } else if (axis == "method") {
    if (value != "repulsion" && value != "voxel" && value != "vertices" && value != "random") {
      Fail(at, "must be repulsion, voxel, vertices or random");
    }
    s.pointshell_body.pointshell.method = value;
  } else if (axis == "resolution" || axis == "pointshell_resolution") {
    const long long v = as_int();
    if (v < 8 || v > 1024) Fail(at, "must be between 8 and 1024");
    (axis == "resolution" ? s.field_body : s.pointshell_body).field.resolution = int(v);
  } else if (axis == "k_C") {
    const double v = as_double();
    if (v < 0) Fail(at, "must not be negative");
    s.model.k_C = v;
  } else if (axis == "node_budget") {
    const long long v = as_int();
    if (v < 0) Fail(at, "must not be negative");
    s.model.node_budget = v;
  } else if (axis == "coherence") {
    if (value != "true" && value != "false") Fail(at, "must be true or false");
    s.model.coherence = value == "true";
  } else if (axis == "max_point_speed") {
    const double v = as_double();
    if (!(v > 0)) Fail(at, "must be positive");
    s.model.max_point_speed = v;
  } else if (axis == "level") {
    s.model.level = int(as_int());
  } else if (axis == "gradient") {
    if (value != "halfspace" && value != "field") Fail(at, "must be halfspace or field");
    s.model.gradient = value == "field" ? ContactGradient::kField : ContactGradient::kHalfspace;
  } else if (axis == "model") {
    job->models = {value};
  } else if (axis == "offset") {
    // The pointshell's level-set offset in metres, or "default" (half a field spacing).
    if (value == "default") {
      s.pointshell_body.pointshell.offset = -1;
    } else {
      const double v = as_double();
      if (v < 0) Fail(at, "must not be negative (or 'default')");
      s.pointshell_body.pointshell.offset = v;
    }
  } else if (axis == "scene") {
    job->scene = LoadScene(RequireDataFile(value, FolderOf(where)));
    job->models = job->models.empty() ? job->scene.models : job->models;
  } else if (axis == "roles") {
    if (value == "swapped") {
      s = s.Swapped();
    } else if (value != "normal") {
      Fail(at, "must be normal or swapped");
    }
  } else {
    Fail(at, "unknown sweep axis");
  }
}

std::vector<Job> ExpandJobs(const ExperimentConfig& config) {
  std::vector<Job> jobs;
  std::size_t total = 1;
  for (const SweepAxis& a : config.sweep) total *= a.values.size();
  for (std::size_t index = 0; index < total; ++index) {
    Job job;
    job.index = int(index);
    job.scene = config.scene;
    job.models = config.models;
    job.moving_body = config.moving_body;
    std::size_t rest = index;
    std::vector<std::size_t> pick(config.sweep.size());
    for (std::size_t a = config.sweep.size(); a-- > 0;) {
      pick[a] = rest % config.sweep[a].values.size();
      rest /= config.sweep[a].values.size();
    }
    // The scene first, then roles, so the other axes apply to the bodies' final roles.
    for (const char* first : {"scene", "roles", ""}) {
      for (std::size_t a = 0; a < config.sweep.size(); ++a) {
        const std::string& name = config.sweep[a].name;
        const bool early = name == "scene" || name == "roles";
        if (*first ? name != first : early) continue;
        ApplySweepValue(name, config.sweep[a].values[pick[a]], &job, config.file);
      }
      // Unless the config names it, the moving body is the field body of the job's scene
      // (before a role swap, so the same physical body moves in both role orders).
      if (std::string(first) == "scene" && config.moving_body_is_default) job.moving_body = job.scene.field_body.name;
    }
    if (job.moving_body != job.scene.field_body.name && job.moving_body != job.scene.pointshell_body.name) {
      Fail(config.file, "moving_body '" + job.moving_body + "' is not a body of the scene of job " +
                            std::to_string(index));
    }
    for (std::size_t a = 0; a < config.sweep.size(); ++a) {
      job.axis_values.emplace_back(config.sweep[a].name, config.sweep[a].values[pick[a]]);
    }
    jobs.push_back(std::move(job));
  }
  return jobs;
}

}  // namespace contactlab
