// Studies registered like models (experiment/study.h): the registry, config sections a study does
// not read refused naming the study that does, meta.json recording the study so that merge asks
// it instead of sniffing files, and the closed-loop study run from a config: the swept coupling
// stiffness reaches the loop, a soft coupling is passive and settles, and single-job runs merge
// into the whole sweep.
#include "experiment/study.h"

#include <gtest/gtest.h>

#include <fstream>
#include <map>
#include <set>
#include <sstream>

#include "experiment/studies/closed_loop/closed_loop_study.h"
#include "experiment/studies/contact/result_csv.h"
#include "experiment/studies/contact/contact_study.h"
#include "scene_fixtures.h"
#include "csv_rows.h"
#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

using testing::TempDir;
namespace fs = std::filesystem;

ExperimentConfig Load(const TempDir& dir, const std::string& text) {
  std::ofstream(dir / "config.yaml") << text;
  return LoadExperimentConfig(dir / "config.yaml");
}

using testing::ReadCsvRows;

// The ball-on-plate scene with the plate as the haptic body pushed up into the ball.
std::string LoopConfig(const std::string& loop = "{motions: [push, slide]}",
                       const std::string& sweep = "sweep: {k_vc: [500, 2000]}\n") {
  testing::BallOnPlate scene;
  return "name: tiny-loop\nstudy: closed-loop\nmodels: [pointshell]\nscene:\n" + scene.Yaml(2) + "loop: " + loop +
         "\n" + sweep;
}

TEST(Study, EveryRegisteredStudyDeclaresItsFilesOnce) {
  const std::vector<std::string> names = StudyNames();
  for (const char* expected : {"contact", "deformed-field", "closed-loop"}) {
    EXPECT_NE(std::find(names.begin(), names.end(), expected), names.end()) << expected;
  }
  EXPECT_EQ(std::set<std::string>(names.begin(), names.end()).size(), names.size());
  for (const Study& s : Studies()) {
    SCOPED_TRACE(s.name);
    EXPECT_FALSE(s.description.empty());
    EXPECT_TRUE(s.run);
    const std::vector<std::string> files = s.Files();
    ASSERT_FALSE(files.empty());
    EXPECT_EQ(files.back(), "meta.json");
    EXPECT_EQ(std::set<std::string>(files.begin(), files.end()).size(), files.size());
    for (const ResultTable& t : s.tables) EXPECT_EQ(fs::path(t.file).extension(), ".csv") << t.file;
    // Every table, derived ones too, declares its columns once, each with a meaning.
    for (const ResultTable* t : s.AllTables()) {
      SCOPED_TRACE(t->file);
      EXPECT_FALSE(t->columns.empty());
      std::set<std::string> names;
      for (const ResultColumn& c : t->columns) {
        EXPECT_TRUE(names.insert(c.name).second) << c.name << " declared twice";
        EXPECT_FALSE(c.meaning.empty()) << c.name;
      }
    }
    for (const std::string& r : s.required) EXPECT_TRUE(s.Reads(r)) << r;
    // Every section is documented for `contactlab params`, and none repeats a common key.
    for (const ConfigKey& k : s.sections) {
      EXPECT_FALSE(k.value.empty()) << k.key;
      EXPECT_FALSE(k.meaning.empty()) << k.key;
      for (const ConfigKey& common : CommonConfigKeys()) EXPECT_NE(k.key, common.key);
    }
  }
  // Only the contact study's cycles are trajectories a viewer replays.
  EXPECT_TRUE(FindStudy("contact")->replayable);
  EXPECT_FALSE(FindStudy("deformed-field")->replayable);
  EXPECT_FALSE(FindStudy("closed-loop")->replayable);
  EXPECT_EQ(FindStudy("no-such-study"), nullptr);
}

TEST(Study, ASectionOnlyAnotherStudyReadsIsRefusedNamingThatStudy) {
  TempDir dir;
  auto expect_error = [&](const std::string& text, std::vector<std::string> parts) {
    try {
      (void)Load(dir, text);
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      const std::string msg = e.what();
      parts.push_back("config.yaml");
      for (const std::string& p : parts) EXPECT_NE(msg.find(p), std::string::npos) << p << " not in: " << msg;
    }
  };
  const std::string scene = "scene:\n" + testing::BallOnPlate().Yaml(2);
  // A contact config given the closed-loop study's section, and the other way round.
  expect_error("name: x\n" + scene + "trajectory: {type: approach-press}\nloop: {k_vc: 100}\n",
               {"loop", "is not read by study: contact", "closed-loop"});
  expect_error(LoopConfig() + "trajectory: {type: approach-press}\n", {"trajectory", "closed-loop", "contact"});
  expect_error(LoopConfig() + "measure: {points: 10}\n", {"measure", "deformed-field"});
  // A key no study reads, an unknown study, a bad loop key, and a contact config without its
  // required trajectory.
  expect_error(LoopConfig() + "loops: {}\n", {"loops"});
  expect_error("name: x\nstudy: closed-loops\n" + scene, {"closed-loops", "contact", "deformed-field", "closed-loop"});
  expect_error(LoopConfig("{k_vc: -3}", ""), {"loop.k_vc", "-3"});
  expect_error(LoopConfig("{motions: [push, wiggle]}"), {"wiggle", "push, slide, corner"});
  expect_error(LoopConfig("{k_vc: 1000}", "sweep: {k_vc: [1000, 0]}\n"), {"job k_vc=0", "loop.k_vc", "got 0"});
  expect_error("name: x\n" + scene, {"trajectory"});
  // A cycle of 10 s once gave rows of 0 cycles judged stable: a cycle too slow for the study's
  // 200 ms windows (10 cycles each at least) is refused naming the job and the key.
  expect_error(LoopConfig("{k_vc: 1000}", "sweep: {cycle_seconds: [0.001, 0.05]}\n"),
               {"cycle_seconds=0.05", "model.cycle_seconds", "too slow for the closed-loop study"});
  // Both bodies at one position gave PlaceAtDepth's message, naming neither file nor key.
  testing::BallOnPlate coincident;
  coincident.ball_z = -0.01;
  expect_error("name: x\nstudy: closed-loop\nmodels: [pointshell]\nscene:\n" + coincident.Yaml(2) + "loop: {k_vc: 1000}\n",
               {"bodies' pose", "'plate'", "'ball'", "one position"});
  // The closed-loop study's alias is not an alias of a contact config.
  expect_error("name: x\n" + scene + "trajectory: {type: approach-press}\nsweep: {k_vc: [1, 2]}\n",
               {"unknown sweep axis"});
}

// A result table holding a non-finite number is refused, naming the file, the line and the
// column, and no file of the run is written; a finite table writes its row counts to meta.json.
TEST(Study, ResultsWithANonFiniteCellAreRefusedAndNothingWritten) {
  TempDir dir;
  const Study& study = *FindStudy("closed-loop");
  ASSERT_EQ(study.TableFiles(), std::vector<std::string>{"stability.csv"});
  for (const char* bad : {"nan", "-nan", "inf", "-inf", "NaN", "0.5 nan 1"}) {
    const std::string table = std::string("experiment,job,q\ninfo,0,0.5 1\ninfo,0,") + bad + "\n";
    try {
      WriteStudyResults(study, dir / "out", {table}, nlohmann::json::object());
      ADD_FAILURE() << "no error for " << bad;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_EQ(msg.rfind((dir / "out" / "stability.csv").string() + ":3: column q is ", 0), 0u) << msg;
    }
    for (const std::string& f : study.Files()) EXPECT_FALSE(fs::exists(dir / "out" / f)) << f;
  }
  // Cells that only begin like one ("info", "nano") are text, not numbers.
  WriteStudyResults(study, dir / "out", {"experiment,job,model\ninfo,0,nano\ninfo,1,x\n"}, nlohmann::json::object());
  const nlohmann::json meta = nlohmann::json::parse(ReadWholeFile(dir / "out" / "meta.json"));
  EXPECT_EQ(meta["table_rows"]["stability.csv"], 2);
}

TEST(Study, TheStudyOfAResultsFolderComesFromItsMetaJson) {
  TempDir dir;
  auto meta = [&](const std::string& text) {
    std::ofstream(dir / "meta.json") << text;
    return dir.path();
  };
  EXPECT_EQ(StudyOfResults(meta(R"({"study": "closed-loop", "resolved_config": "study: contact"})")).name, "closed-loop");
  // Runs recorded before meta.json named the study: their resolved config says it.
  EXPECT_EQ(StudyOfResults(meta(R"({"resolved_config": "name: a\nstudy: deformed-field\n"})")).name, "deformed-field");
  EXPECT_EQ(StudyOfResults(meta(R"({"resolved_config": "name: a\n"})")).name, "contact");
  auto expect_error = [&](const std::string& text, const std::string& part) {
    try {
      (void)StudyOfResults(meta(text));
      ADD_FAILURE() << "no error for " << text;
    } catch (const Error& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find((dir / "meta.json").string()), std::string::npos) << msg;
      EXPECT_NE(msg.find(part), std::string::npos) << msg;
    }
  };
  expect_error(R"({"study": "sideways"})", "'sideways'");
  expect_error(R"({"jobs": [0]})", "names no study");
  expect_error("{\"study\": ", "not valid JSON");
  fs::remove(dir / "meta.json");
  try {
    (void)StudyOfResults(dir.path());
    ADD_FAILURE() << "no error without meta.json";
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("meta.json: not found"), std::string::npos) << e.what();
  }
}

// Every table of the results folder DIR, a run of CONFIG, has the header its meta.json declares:
// the declared columns in order, with CONFIG's sweep axes after the job's keys (less those a
// table leaves out because a declared column has their name).
void ExpectHeadersAsDeclared(const fs::path& dir, const ExperimentConfig& config) {
  const nlohmann::json meta = nlohmann::json::parse(ReadWholeFile(dir / "meta.json"));
  for (const ResultTable* table : StudyOfResults(dir).AllTables()) {
    SCOPED_TRACE(table->file);
    ASSERT_TRUE(meta["columns"].contains(table->file));
    std::vector<std::string> expected;
    for (const auto& c : meta["columns"][table->file]) expected.push_back(c["name"].get<std::string>());
    if (table->keys != TableKeys::kNone) {
      std::vector<std::string> axes;
      for (const SweepAxis& a : config.sweep) {
        if (table->keys == TableKeys::kJobAndAllAxes || table->Find(a.name) == nullptr) axes.push_back(a.name);
      }
      ASSERT_GE(expected.size(), 2u);
      EXPECT_EQ(expected[0], "experiment");
      EXPECT_EQ(expected[1], "job");
      expected.insert(expected.begin() + 2, axes.begin(), axes.end());
    }
    std::ifstream in(dir / table->file);
    std::string header;
    std::getline(in, header);
    EXPECT_EQ(SplitCsvLine(header), expected);
  }
}

TEST(ClosedLoopStudy, TheSweptStiffnessReachesTheLoopAndSingleJobsMergeIntoTheSweep) {
  TempDir dir;
  const ExperimentConfig config = Load(dir, LoopConfig());
  const Study& study = StudyOf(config);
  ASSERT_EQ(study.name, "closed-loop");
  RunOptions o;
  o.assets.cache_dir = dir / "cache";
  o.assets.verbose = false;
  o.progress = false;
  o.out_dir = dir / "all";
  study.run(config, o, {});
  for (const std::string& f : study.Files()) EXPECT_TRUE(fs::is_regular_file(dir / "all" / f)) << f;
  EXPECT_EQ(StudyOfResults(dir / "all").name, "closed-loop");
  ExpectHeadersAsDeclared(dir / "all", config);

  const auto rows = ReadCsvRows(dir / "all" / "stability.csv");
  ASSERT_EQ(rows.size(), 4u);  // 2 jobs x 1 model x 2 motions
  const char* motions[] = {"push", "slide"};
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const auto& r = rows[i];
    SCOPED_TRACE(i);
    EXPECT_EQ(r.at("experiment"), "tiny-loop");
    EXPECT_EQ(r.at("job"), std::to_string(i / 2));
    EXPECT_EQ(r.at("model"), "pointshell");
    EXPECT_EQ(r.at("motion"), motions[i % 2]);
    EXPECT_DOUBLE_EQ(std::stod(r.at("k_vc")), i < 2 ? 500.0 : 2000.0);
    // It really pressed: contact force during the run, and a force held in contact.
    EXPECT_GT(std::stod(r.at("max_contact_force_N")), 0.5);
    EXPECT_GT(std::stod(r.at("hold_force_mean_N")), 0.3);
    // Passive (at most 1 % of the peak stored coupling energy, or 1 µJ, generated) and settled,
    // recomputed here from the columns.
    const double energy = std::stod(r.at("energy_into_hand_J")), peak = std::stod(r.at("peak_stored_energy_J"));
    EXPECT_GT(peak, 0);
    EXPECT_LE(energy, std::max(1e-6, 0.01 * peak));
    EXPECT_LT(std::stod(r.at("late_position_rms_m")), 20e-6);
    EXPECT_LT(std::stod(r.at("late_force_rms_N")), 0.05);
    EXPECT_EQ(r.at("stable"), "1");
    EXPECT_EQ(r.at("verdict"), "ok");
  }
  // A stiffer coupling stores the same hold force in a shorter spring: less peak energy.
  EXPECT_LT(std::stod(rows[2].at("peak_stored_energy_J")), std::stod(rows[0].at("peak_stored_energy_J")));

  for (int j : {0, 1}) {
    o.out_dir = dir / ("job-" + std::to_string(j));
    study.run(config, o, {j});
  }
  MergeResults({dir / "job-0", dir / "job-1"}, dir / "merged");
  const auto merged = ReadCsvRows(dir / "merged" / "stability.csv");
  ASSERT_EQ(merged.size(), rows.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    for (const auto& [column, value] : rows[i]) {
      if (column != "wall_s") EXPECT_EQ(merged[i].at(column), value) << column << " row " << i;
    }
  }
  EXPECT_EQ(StudyOfResults(dir / "merged").name, "closed-loop");
  ExpectHeadersAsDeclared(dir / "merged", config);
  EXPECT_FALSE(fs::exists(dir / "merged" / "cycles.csv"));

  // Folders of two studies do not merge.
  const ExperimentConfig contact = Load(dir, "name: tiny-loop\nscene:\n" + testing::BallOnPlate().Yaml(2) +
                                                 "trajectory: {type: approach-press, depth: 0.001, duration: 0.01}\n");
  o.out_dir = dir / "contact";
  StudyOf(contact).run(contact, o, {});
  ExpectHeadersAsDeclared(dir / "contact", contact);
  try {
    MergeResults({dir / "job-0", dir / "contact"}, dir / "mixed");
    ADD_FAILURE() << "no error";
  } catch (const Error& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find((dir / "contact" / "meta.json").string()), std::string::npos) << msg;
    EXPECT_NE(msg.find("holds a contact study"), std::string::npos) << msg;
  }
  EXPECT_FALSE(fs::exists(dir / "mixed"));
}

}  // namespace
}  // namespace contactlab
