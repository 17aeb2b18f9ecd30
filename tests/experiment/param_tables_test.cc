// Parameters declared once (util/param_table.h): a row added to a table is parsed, range-checked,
// hashed and reachable by a sweep; every scene parameter that shapes a cached artefact is in
// that artefact's cache key (changing it rebuilds the artefact), and every one that does not is
// not (the artefact built afresh is byte-identical to the cached one it reuses).
#include <gtest/gtest.h>

#include <array>
#include <cstdio>
#include <fstream>
#include <functional>
#include <map>
#include <set>
#include <sstream>
#include <string>

#include "contact/model_registry.h"
#include "experiment/experiment_config.h"
#include "scene/scene.h"
#include "scene/scene_assets.h"
#include "test_support.h"
#include "util/error.h"
#include "util/param_table.h"

namespace contactlab {
namespace {

namespace fs = std::filesystem;
using testing::TempDir;

using testing::ErrorOf;

struct Widget {
  int teeth = 12;
  double radius = 0.05;
  std::string finish = "matte";
};

TEST(ParamTable, ARowAddedToATableIsParsedCheckedHashedAndShown) {
  using P = ParamRows<Widget>;
  const ParamTable<Widget> before("widget", "A test block.",
                                  {P::Integer("teeth", PARAM_MEMBER(teeth), 3, 200, "teeth").Shapes(kShapesField)});
  // The same table with one row more: nothing else changes to read, check, hash and show it.
  std::vector<ParamRow<Widget>> rows = before.rows();
  rows.push_back(P::Number("radius", PARAM_MEMBER(radius), Above(0), AtMost(1), "pitch radius")
                     .Unit("m")
                     .Shapes(kShapesPointshell)
                     .Sweepable());
  const ParamTable<Widget> after("widget", "A test block.", rows);

  const Widget w = after.Parse(ConfigNode::LoadString("teeth: 20\nradius: 0.25\n", "w.yaml"));
  EXPECT_EQ(w.teeth, 20);
  EXPECT_EQ(w.radius, 0.25);
  EXPECT_NE(ErrorOf([&] { before.Parse(ConfigNode::LoadString("radius: 0.25\n", "w.yaml")); })
                .find("w.yaml:1: radius: unknown key (known keys here: teeth)"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { after.Parse(ConfigNode::LoadString("teeth: 20\nradius: 2\n", "w.yaml")); })
                .find("w.yaml:2: radius: must be in (0, 1], got 2"),
            std::string::npos);
  EXPECT_NE(ErrorOf([&] { after.Parse(ConfigNode::LoadString("radius: wide\n", "w.yaml")); }).find("'wide'"),
            std::string::npos);

  // Hashed into the key of the artefact it shapes, and only that one.
  auto key = [&](const Widget& x, unsigned artefact) {
    Hasher h;
    after.Hash(x, artefact, &h);
    return h.Hex();
  };
  Widget other = w;
  other.radius = 0.5;
  EXPECT_NE(key(w, kShapesPointshell), key(other, kShapesPointshell));
  EXPECT_EQ(key(w, kShapesField), key(other, kShapesField));
  EXPECT_EQ(after.SweepKeys(), std::vector<std::string>{"radius"});
  const std::string reference = after.Reference("widget");
  EXPECT_NE(reference.find("| `radius` | number | in (0, 1] | 0.05 | m | pointshell | `radius` | pitch radius |"),
            std::string::npos)
      << reference;
}

// Every key a sweep may name alone reaches its block: a sweep over the row's example value
// gives a job whose scene holds it.
TEST(ParamTable, EverySweepableSceneKeyIsASweepAxis) {
  TempDir dir;
  std::ofstream(dir / "scene.yaml")
      << "bodies:\n"
         "  - {name: a, mesh: \"box:0.01,0.01,0.01\", role: pointshell, deformable: {modes: 4}}\n"
         "  - {name: b, mesh: \"box:0.03,0.03,0.01\", role: field, deformable: {field: {proxies: 20}}}\n";
  // Friction is carried between rigid bodies only: its keys sweep over the same bodies, rigid,
  // with friction on (a dynamic coefficient may not exceed the static one).
  std::ofstream(dir / "rigid.yaml")
      << "bodies:\n"
         "  - {name: a, mesh: \"box:0.01,0.01,0.01\", role: pointshell}\n"
         "  - {name: b, mesh: \"box:0.03,0.03,0.01\", role: field}\n"
         "model: {friction: {static: 0.9}}\n";
  int checked = 0;
  for (const SceneBlock& block : SceneBlocks()) {
    for (const std::string& key : block.sweep_keys) {
      std::string example;
      const auto find = [&](const auto& table) {
        if (const auto* row = table.Find(key); row != nullptr && example.empty()) example = row->example;
      };
      const bool friction = block.alias_prefix == "friction_";
      if (friction) find(FrictionParamTable());  // its keys share names with the model section's
      find(FieldParams());
      find(PointshellParams());
      find(DeformableParams());
      find(DeformedFieldParams());
      find(ContactParamTable());
      for (const ContactModelEntry* e : ContactModelEntries()) {  // each model's own keys and blocks
        if (e->pair_params) find(*e->pair_params->table);
        for (const ModelParamBlock& b : e->body_blocks) find(*b.table);
      }
      if (key == "node_budget") example = "500";
      ASSERT_FALSE(example.empty()) << key << " has no example value";
      const std::string axis = block.alias_prefix + key;
      std::ofstream(dir / "run.yaml") << "name: t\nscene: " << (friction ? "rigid.yaml" : "scene.yaml")
                                      << "\nmodels: [pointshell-linear]\n"
                                         "trajectory: {type: slide, duration: 0.01}\n"
                                         "sweep: {" << axis << ": [" << example << "]}\n";
      const ExperimentConfig config = LoadExperimentConfig(dir / "run.yaml");
      const std::vector<Job> jobs = ExpandJobs(config);
      ASSERT_EQ(jobs.size(), 1u) << axis;
      EXPECT_EQ(block.value(jobs[0].scene, key), example) << "sweep axis " << axis;
      ++checked;
    }
  }
  EXPECT_GE(checked, 20);
}

// A body whose mesh is a box off its origin (so centring moves it), written to DIR/box.obj.
void WriteBox(const fs::path& file) {
  std::ofstream f(file);
  for (int i = 0; i < 8; ++i) {
    f << "v " << 0.03 + 0.02 * (i & 1) << " " << 0.01 + 0.016 * ((i >> 1) & 1) << " " << 0.012 * ((i >> 2) & 1) << "\n";
  }
  const int faces[12][3] = {{1, 3, 2}, {2, 3, 4}, {5, 6, 7}, {6, 8, 7}, {1, 2, 5}, {2, 6, 5},
                            {3, 7, 4}, {4, 7, 8}, {1, 5, 3}, {3, 5, 7}, {2, 4, 6}, {4, 8, 6}};
  for (const auto& t : faces) f << "f " << t[0] << " " << t[1] << " " << t[2] << "\n";
}

// Body A's blocks as YAML, each block's base keys with CHANGE[block] set over them.
using BlockValues = std::map<std::string, std::map<std::string, std::string>>;
std::string SceneText(BlockValues change) {
  BlockValues v = {
      {"body", {{"name", "a"}, {"mesh", "box.obj"}, {"role", "pointshell"}}},
      {"field", {{"resolution", "64"}}},
      {"pointshell", {{"points", "64"}, {"levels", "2"}}},
      {"deformable", {{"modes", "2"}, {"cells", "4"}}},
      {"deformable.damping", {}},
      {"deformable.field", {{"proxies", "8"}, {"neighbours", "4"}}},
  };
  for (const auto& [block, keys] : change) {
    for (const auto& [key, value] : keys) v[block][key] = value;
  }
  auto map = [&](const std::string& block) {
    std::string s;
    for (const auto& [key, value] : v[block]) s += (s.empty() ? "" : ", ") + key + ": " + value;
    return s;
  };
  const bool rigid = v["deformable"].count("-") > 0;  // CHANGE["deformable"]["-"]: no deformable block
  return "bodies:\n  - {" + map("body") + ", field: {" + map("field") + "}, pointshell: {" + map("pointshell") + "}" +
         (rigid ? std::string()
                : ", deformable: {" + map("deformable") + ", damping: {" + map("deformable.damping") + "}, field: {" +
                      map("deformable.field") + "}}") +
         "}\n  - {name: b, mesh: \"sphere:0.01,1\", role: field, field: {resolution: 16}}\n";
}

const char* kPrefix[] = {"field-", "pointshell-", "reduced-"};
const unsigned kArtefact[] = {kShapesField, kShapesPointshell, kShapesReducedModel};

// The cached files of each artefact kind in DIR.
std::array<std::set<std::string>, 3> CachedFiles(const fs::path& dir) {
  std::array<std::set<std::string>, 3> files;
  for (const auto& e : fs::directory_iterator(dir)) {
    const std::string name = e.path().filename().string();
    for (int a = 0; a < 3; ++a) {
      if (name.rfind(kPrefix[a], 0) == 0) files[a].insert(name);
    }
  }
  return files;
}

TEST(ParamTable, EveryParameterThatShapesACachedArtefactIsInItsKeyAndNoOtherIs) {
  TempDir dir;
  WriteBox(dir / "box.obj");
  AssetOptions options;
  options.cache_dir = dir / "cache";
  options.verbose = false;
  const auto scene_of = [&](const BlockValues& change) {
    return ParseScene(ConfigNode::LoadString(SceneText(change), (dir / "scene.yaml").string()));
  };
  const auto build_all = [](BodyAssets& A) {
    (void)A.field();
    (void)A.pointshell();
    if (A.deformable()) (void)A.reduced_model();
  };
  const std::vector<std::pair<std::string, std::vector<std::string>>> blocks = {
      {"body", BodyParams().Keys()},
      {"field", FieldParams().Keys()},
      {"pointshell", PointshellParams().Keys()},
      {"deformable", DeformableParams().Keys()},
      {"deformable.field", DeformedFieldParams().Keys()},
  };
  struct Row {
    std::string example, type;
    unsigned shapes;
  };
  const auto row_of = [](const std::string& block, const std::string& key) {
    const auto of = [&](const auto& table) {
      const auto* r = table.Find(key);
      return Row{r->example, r->type, r->shapes};
    };
    if (block == "body") return of(BodyParams());
    if (block == "field") return of(FieldParams());
    if (block == "pointshell") return of(PointshellParams());
    if (block == "deformable.field") return of(DeformedFieldParams());
    return of(DeformableParams());
  };
  int checked = 0;
  for (const auto& [block, keys] : blocks) {
    for (const std::string& key : keys) {
      const auto [example, type, shapes] = row_of(block, key);
      if (type == "block") continue;  // its rows are checked in their own block
      SCOPED_TRACE(block + "." + key + ": " + example);
      if (example.empty()) {
        EXPECT_EQ(shapes, 0u) << block << "." << key << " shapes a cached artefact but has no example to change it by";
        continue;
      }
      // band applies to sparse fields only: its baseline is sparse.
      // A sparse field is for rigid bodies; band applies to sparse fields only.
      const bool deformable = !(block == "field" && (key == "storage" || key == "band"));
      BlockValues base_extra;
      if (!deformable) {
        base_extra["deformable"]["-"] = "";
        base_extra["field"]["padding"] = "0.5";  // a sparse field's coarse boundary stays clear of the offset
      }
      if (block == "field" && key == "band") base_extra["field"]["storage"] = "sparse";
      BlockValues changed = base_extra;
      changed[block][key] = example;
      const Scene base_scene = scene_of(base_extra), scene = scene_of(changed);
      SceneAssets base(base_scene, options);
      build_all(base.A);
      const auto before = CachedFiles(options.cache_dir);
      SceneAssets assets(scene, options);
      build_all(assets.A);
      const auto after = CachedFiles(options.cache_dir);
      for (int a = 0; a < (deformable ? 3 : 2); ++a) {
        const bool rebuilt = after[a].size() > before[a].size();
        EXPECT_EQ(rebuilt, (shapes & kArtefact[a]) != 0)
            << block << "." << key << ": " << example << ": " << kPrefix[a] << (rebuilt ? " rebuilt" : " reused");
      }
      // What it does not shape is what a fresh build of the changed scene makes, value for value
      // (the saved files also hold build times).
      AssetOptions fresh_options = options;
      fresh_options.use_cache = false;
      SceneAssets fresh(scene, fresh_options);
      const std::string what = block + "." + key + ": " + example + " changes the ";
      if (!(shapes & kShapesField)) {
        const auto a = fresh.A.field(), b = base.A.field();
        EXPECT_TRUE(a->values() == b->values() && a->origin() == b->origin() && a->spacing() == b->spacing())
            << what << "field, but is not in its cache key";
      }
      if (!(shapes & kShapesPointshell)) {
        const auto a = fresh.A.pointshell(), b = base.A.pointshell();
        EXPECT_TRUE(a->x == b->x && a->y == b->y && a->z == b->z && a->nx == b->nx && a->node_radius == b->node_radius)
            << what << "pointshell, but is not in its cache key";
      }
      if (deformable && !(shapes & kShapesReducedModel)) {
        const auto a = fresh.A.reduced_model(), b = base.A.reduced_model();
        EXPECT_TRUE(a->basis == b->basis && a->eigenvalues == b->eigenvalues && a->kind() == b->kind() &&
                    a->fixed == b->fixed && a->mesh.vertices == b->mesh.vertices)
            << what << "reduced model, but is not in its cache key";
      }
      ++checked;
    }
  }
  EXPECT_GE(checked, 28);
}

}  // namespace
}  // namespace contactlab
