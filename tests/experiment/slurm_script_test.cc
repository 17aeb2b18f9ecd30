// Slurm scripts of a sweep (experiment/slurm_script.h): the generated scripts run under bash
// with a stand-in program that records its arguments, submission through a stand-in sbatch on
// $PATH, and the merge's check that names every task without complete results.
#include "experiment/slurm_script.h"
#include "experiment/study.h"

#include <gtest/gtest.h>
#include <sys/wait.h>

#include <cstdlib>
#include <fstream>
#include <string>

#include "test_support.h"
#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {
namespace {

namespace fs = std::filesystem;

// Runs COMMAND with /bin/sh; returns its exit code.
int Shell(const std::string& command) {
  const int status = std::system(command.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

// An executable shell script at PATH.
void WriteScript(const fs::path& path, const std::string& body) {
  std::ofstream(path) << "#!/bin/sh\n" << body;
  fs::permissions(path, fs::perms::owner_all);
}

// Expects F to throw Error containing every one of PARTS.
template <typename F>
void ExpectError(F f, const std::vector<std::string>& parts) {
  try {
    f();
    FAIL() << "no error";
  } catch (const Error& e) {
    const std::string m = e.what();
    for (const std::string& p : parts) EXPECT_NE(m.find(p), std::string::npos) << "'" << p << "' not in: " << m;
  }
}

SweepCommand Command(const testing::TempDir& dir, int jobs) {
  SweepCommand c;
  c.contactlab = dir / "bin" / "fake contactlab";  // a space, to check the quoting
  c.config = dir / "it's a config.yaml";           // and a quote
  c.run_args = {"--set", "trajectory.duration=0.5", "--profile", "quick"};
  c.out_dir = dir / "out";
  c.name = "my sweep/1";
  c.jobs = jobs;
  return c;
}

TEST(SlurmScript, ArrayScriptAsksForTheResourcesAndOneTaskPerSweepPoint) {
  testing::TempDir dir;
  SlurmOptions o{.partition = "short", .time = "0-00:20:00", .cpus_per_task = 4, .mem = "2G"};
  const SlurmScripts s = MakeSlurmScripts(Command(dir, 7), o);
  for (const std::string line : {"#SBATCH --array=0-6\n", "#SBATCH --partition=short\n", "#SBATCH --time=0-00:20:00\n",
                                 "#SBATCH --cpus-per-task=4\n", "#SBATCH --mem=2G\n",
                                 "#SBATCH --job-name=contactlab-my_sweep_1\n"}) {
    EXPECT_NE(s.array.find(line), std::string::npos) << line << " not in:\n" << s.array;
  }
  EXPECT_NE(s.array.find("#SBATCH --output=" + (dir / "out" / "slurm").string() + "/job-%a.log\n"), std::string::npos);
  EXPECT_NE(s.merge.find("#SBATCH --job-name=contactlab-my_sweep_1-merge\n"), std::string::npos) << s.merge;
  EXPECT_NE(s.merge.find("--jobs 7"), std::string::npos) << s.merge;
  EXPECT_EQ(s.merge.find("--array"), std::string::npos) << s.merge;
  EXPECT_NE(s.submit.find("--dependency=afterany:"), std::string::npos) << s.submit;
  // Without a partition or memory, none is asked for.
  const SlurmScripts d = MakeSlurmScripts(Command(dir, 1), SlurmOptions{});
  EXPECT_EQ(d.array.find("--partition"), std::string::npos);
  EXPECT_EQ(d.array.find("--mem"), std::string::npos);
  EXPECT_NE(d.array.find("#SBATCH --array=0-0\n"), std::string::npos);
}

// Each task, run by bash as Slurm would, runs `contactlab run CONFIG ARGS --job I --out OUT/job-I`
// with every argument intact; the merge runs `contactlab merge --sweep OUT --jobs N --out OUT`.
TEST(SlurmScript, TasksAndMergeRunTheExpectedCommands) {
  testing::TempDir dir;
  fs::create_directories(dir / "bin");
  WriteScript(dir / "bin" / "fake contactlab",
              "for a in \"$@\"; do printf '[%s]' \"$a\"; done >> \"$(dirname \"$0\")/calls.txt\"\necho >> "
              "\"$(dirname \"$0\")/calls.txt\"\n");
  const SweepCommand c = Command(dir, 3);
  const fs::path slurm = WriteSlurmScripts(c, SlurmOptions{});
  for (int task : {0, 2}) {
    ASSERT_EQ(Shell("SLURM_ARRAY_TASK_ID=" + std::to_string(task) + " bash '" + (slurm / "array.sbatch").string() + "'"), 0);
  }
  ASSERT_EQ(Shell("bash '" + (slurm / "merge.sbatch").string() + "'"), 0);
  const std::string calls = ReadWholeFile(dir / "bin" / "calls.txt");
  const std::string config = "[" + c.config.string() + "]";
  const std::string out = (dir / "out").string();
  EXPECT_EQ(calls, "[run]" + config + "[--set][trajectory.duration=0.5][--profile][quick][--job][0][--out][" + out +
                       "/job-0]\n" + "[run]" + config + "[--set][trajectory.duration=0.5][--profile][quick][--job][2][--out][" +
                       out + "/job-2]\n" + "[merge][--sweep][" + out + "][--jobs][3][--out][" + out + "]\n");
  // Written executable.
  EXPECT_NE(fs::status(slurm / "submit.sh").permissions() & fs::perms::owner_exec, fs::perms::none);
}

TEST(SlurmScript, BadOptionsAreRejectedNamingTheOption) {
  testing::TempDir dir;
  ExpectError([&] { MakeSlurmScripts(Command(dir, 2), SlurmOptions{.time = "1h"}); }, {"--time", "'1h'"});
  ExpectError([&] { MakeSlurmScripts(Command(dir, 2), SlurmOptions{.partition = "a b"}); }, {"--partition", "'a b'"});
  ExpectError([&] { MakeSlurmScripts(Command(dir, 2), SlurmOptions{.cpus_per_task = 0}); }, {"--cpus-per-task"});
  ExpectError([&] { MakeSlurmScripts(Command(dir, 2), SlurmOptions{.mem = "lots"}); }, {"--mem", "'lots'"});
  ExpectError([&] { MakeSlurmScripts(Command(dir, 0), SlurmOptions{}); }, {"no jobs"});
  SweepCommand spaced = Command(dir, 2);
  spaced.out_dir = dir / "with space";
  ExpectError([&] { MakeSlurmScripts(spaced, SlurmOptions{}); }, {"with space", "spaces"});
  for (const char* t : {"30", "10:00", "01:00:00", "2-0", "2-12:30", "1-00:00:00"}) {
    EXPECT_NO_THROW(CheckSlurmOptions(SlurmOptions{.time = t})) << t;
  }
}

// A stand-in sbatch on $PATH that logs its arguments and answers as `sbatch --parsable` does.
class FakeSbatch : public ::testing::Test {
 protected:
  void SetUp() override {
    fs::create_directories(dir_ / "bin");
    old_path_ = std::getenv("PATH");
    ::setenv("PATH", ((dir_ / "bin").string() + ":" + old_path_).c_str(), 1);
    WriteScript(dir_ / "bin" / "scancel", "echo \"scancel $*\" >> \"$(dirname \"$0\")/log.txt\"\n");
  }
  void TearDown() override { ::setenv("PATH", old_path_.c_str(), 1); }
  // The Nth call (1-based) of sbatch prints REPLY[N-1] and exits with CODE[N-1].
  void Sbatch(const std::string& first, int first_code, const std::string& second, int second_code) {
    WriteScript(dir_ / "bin" / "sbatch",
                "log=\"$(dirname \"$0\")/log.txt\"\necho \"sbatch $*\" >> \"$log\"\n"
                "n=$(grep -c '^sbatch' \"$log\")\n"
                "if [ \"$n\" = 1 ]; then echo '" + first + "'; exit " + std::to_string(first_code) + "; fi\n"
                "echo '" + second + "'; exit " + std::to_string(second_code) + "\n");
  }
  std::string Log() { return ReadWholeFile(dir_ / "bin" / "log.txt"); }
  testing::TempDir dir_;
  std::string old_path_;
};

TEST_F(FakeSbatch, SubmitsTheArrayThenTheMergeAfterIt) {
  Sbatch("4711;cluster", 0, "4712", 0);
  const SlurmSubmission sub = SubmitSlurmScripts(dir_ / "s");
  EXPECT_EQ(sub.array_job, "4711");
  EXPECT_EQ(sub.merge_job, "4712");
  EXPECT_EQ(Log(), "sbatch --parsable " + (dir_ / "s" / "array.sbatch").string() + "\n" +
                       "sbatch --parsable --dependency=afterany:4711 " + (dir_ / "s" / "merge.sbatch").string() + "\n");
}

TEST_F(FakeSbatch, FailedSubmissionsReportSbatchAndCancelTheArray) {
  Sbatch("sbatch: error: invalid partition specified: nope", 1, "", 0);
  ExpectError([&] { SubmitSlurmScripts(dir_ / "s"); }, {"array.sbatch", "invalid partition specified: nope"});
  fs::remove(dir_ / "bin" / "log.txt");
  Sbatch("12", 0, "sbatch: error: Batch job submission failed", 1);
  ExpectError([&] { SubmitSlurmScripts(dir_ / "s"); }, {"merge.sbatch", "submission failed", "array job 12 was cancelled"});
  EXPECT_NE(Log().find("scancel 12"), std::string::npos) << Log();
}

// Writes the complete results of task I of a STUDY into OUT/job-I (as `contactlab run --job I`
// does): its tables, then meta.json naming the study.
void WriteTask(const fs::path& out, int i, const std::string& jobs_json, const std::string& study = "contact") {
  const fs::path d = out / ("job-" + std::to_string(i));
  fs::create_directories(d);
  for (const std::string& table : FindStudy(study)->TableFiles()) std::ofstream(d / table) << "job\n" << i << "\n";
  std::ofstream(d / "meta.json") << "{\"experiment\": \"e\", \"study\": \"" << study << "\", \"jobs\": " << jobs_json
                                 << "}\n";
}

TEST(SlurmScript, SweepTaskFoldersAreInJobOrderAndEveryIncompleteTaskIsNamed) {
  testing::TempDir out;
  for (int i = 0; i < 12; ++i) WriteTask(out.path(), i, "[" + std::to_string(i) + "]");
  const std::vector<fs::path> dirs = SweepTaskFolders(out.path(), 12);
  ASSERT_EQ(dirs.size(), 12u);
  EXPECT_EQ(dirs[2].filename(), "job-2");  // numeric, not lexicographic, order
  EXPECT_EQ(dirs[10].filename(), "job-10");
  fs::remove(out / "job-3" / "summary.csv");
  fs::remove_all(out / "job-11");
  WriteTask(out.path(), 7, "[0]");
  std::ofstream(out / "job-5" / "meta.json") << "{\"experiment\": \"e\", \"study\": \"nope\", \"jobs\": [5]}\n";
  ExpectError([&] { SweepTaskFolders(out.path(), 12); },
              {"4 of 12 sweep tasks", "task 3: ", "no summary.csv", (out / "slurm" / "job-3.log").string(), "task 11: ",
               "no meta.json", "task 7: ", "holds jobs [0], not [7]", "task 5: ", "names study 'nope'"});
}

// A task's files are those of the study its meta.json names: a deformed-field task needs its two
// tables, and no cycles.csv.
TEST(SlurmScript, SweepTaskFoldersAskTheStudyForItsFiles) {
  testing::TempDir out;
  for (int i = 0; i < 3; ++i) WriteTask(out.path(), i, "[" + std::to_string(i) + "]", "deformed-field");
  EXPECT_EQ(SweepTaskFolders(out.path(), 3).size(), 3u);
  EXPECT_FALSE(fs::exists(out / "job-0" / "cycles.csv"));
  fs::remove(out / "job-1" / "field_slice.csv");
  ExpectError([&] { SweepTaskFolders(out.path(), 3); }, {"1 of 3 sweep tasks", "task 1: ", "no field_slice.csv"});
}

}  // namespace
}  // namespace contactlab
