// The parser of experiment configs (experiment_config.h): the profiles and --set overrides
// applied (key_paths.h), the top-level keys each study reads, the scene and models, the sweep's
// axes and values, and every job expanded once and checked (job_expansion.h) before any work.
#include "experiment/experiment_config.h"

#include <algorithm>
#include <map>

#include "contact/model_registry.h"
#include "contact/unbuilt_models.h"
#include "experiment/job_expansion.h"
#include "experiment/key_paths.h"
#include "experiment/study.h"
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

std::string ScalarText(const ConfigNode& n) {
  if (!n.IsScalar()) n.Fail("a sweep value must be a single value (or {label: NAME, value: ...})");
  return n.AsString();
}

}  // namespace

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

}  // namespace contactlab
