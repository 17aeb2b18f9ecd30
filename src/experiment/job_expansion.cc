// How the jobs of an experiment config are built (experiment_config.h: ExpandJob, ForEachJob):
// each from its own copy of the config's documents, the scene axis first, then the roles, then
// every other sweep value written at its key path, and parsed again.
#include "experiment/job_expansion.h"

#include <optional>
#include <string>
#include <vector>

#include "experiment/experiment_config.h"
#include "util/data_path.h"
#include "util/error.h"

namespace contactlab {

// Loads the scene file NAME (data search path, first from the folder of CONFIG_FILE) as a
// document.
void LoadSceneDocument(const std::string& name, const std::string& config_file, JobDocuments* docs) {
  const std::filesystem::path file = RequireDataFile(name, FolderOf(config_file));
  docs->scene_text = ConfigNode::ReadText(file);
  docs->scene = ConfigNode::LoadString(docs->scene_text, file.string()).yaml();
  docs->scene_file = file.string();
}

namespace {

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

}  // namespace

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
  if (auto t = root.Find("trajectory")) {
    job.trajectory_node = *t;
    job.trajectory = ParseTrajectorySpec(*t);
  }
  job.config = root;
  return job;
}

std::string Job::Label() const {
  std::string s;
  for (const auto& [axis, value] : axis_values) s += (s.empty() ? "" : " ") + axis + "=" + value;
  return s.empty() ? "(single run)" : s;
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
