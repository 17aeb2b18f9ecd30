// The closed-loop study (closed_loop_study.h): one job builds the scene's assets, finds
// where the hand touches, and runs the simulated loop per model and motion.
#include "experiment/studies/closed_loop/closed_loop_study.h"

#include <algorithm>
#include <cstdio>

#include "contact/model_registry.h"
#include "contact/scaled_contact_model.h"
#include "experiment/csv_line.h"
#include "experiment/result_table.h"
#include "experiment/run_metadata.h"
#include "experiment/runner.h"
#include "scene/scene_assets.h"
#include "experiment/study.h"
#include "util/error.h"

namespace contactlab {

const ParamTable<LoopSpec>& LoopParams() {
  using P = ParamRows<LoopSpec>;
  static const std::vector<std::pair<std::string, LoopMotion>> kMotions = {
      {"push", LoopMotion::kPush}, {"slide", LoopMotion::kSlide}, {"corner", LoopMotion::kCorner}};
  static const ParamTable<LoopSpec> table(
      "loop",
      "The simulated haptic loop of a closed-loop study (experiment/studies/closed_loop/closed_loop_study.h): the "
      "coupling, the damping and the hand's motions.",
      {
          P::Number("k_vc", PARAM_MEMBER(loop.k_vc), Above(0), NoUpperBound(), "linear coupling stiffness")
              .Unit("N/m").Sweepable().Example("5000"),
          P::Number("k_vc_rot", PARAM_MEMBER(loop.k_vc_rot), Above(0), NoUpperBound(), "rotational coupling stiffness")
              .Unit("N m/rad").Example("0.5"),
          P::Number("alpha", PARAM_MEMBER(loop.alpha), AtLeast(0), AtMost(1), "quasi-static damping of a 1 ms cycle (paper sec. 5); a cycle of T uses alpha^(T / 1 ms)")
              .Example("0.3"),
          P::Boolean("alpha_per_cycle", PARAM_MEMBER(loop.alpha_per_cycle),
                     "apply alpha per cycle at any rate (the paper's rule read literally: at 10 kHz H follows "
                     "the device ten times faster in time) instead of per 1 ms")
              .Sweepable().Example("true"),
          P::Number("push_depth", PARAM_MEMBER(loop.push_depth), Above(0), AtMost(1),
                    "how far past first touch the hand's target goes (push, slide)")
              .Unit("m").Example("0.004"),
          P::Number("corner_depth", PARAM_MEMBER(loop.corner_depth), Above(0), AtMost(1),
                    "the same for the tilted corner push")
              .Unit("m").Example("0.02"),
          P::Number("slide_distance", PARAM_MEMBER(loop.slide_distance), Above(0), AtMost(1),
                    "how far the slide motion moves along the surface")
              .Unit("m").Example("0.01"),
          P::Custom(
               "motions", "list", "push, slide, corner", "the motions run, each from rest in free space",
               [](const ConfigNode& v, LoopSpec* s) {
                 s->motions.clear();
                 for (const ConfigNode& e : v.Elements()) {
                   const std::string name = e.AsString();
                   const auto m = std::find_if(kMotions.begin(), kMotions.end(),
                                               [&](const auto& c) { return c.first == name; });
                   if (m == kMotions.end()) e.Fail("'" + e.Quoted() + "' is not one of: push, slide, corner");
                   s->motions.push_back(m->second);
                 }
                 if (s->motions.empty()) v.Fail("lists no motion");
               },
               nullptr,
               [](const LoopSpec& s) {
                 std::string t;
                 for (LoopMotion m : s.motions) t += (t.empty() ? "" : ", ") + std::string(LoopMotionName(m));
                 return "[" + t + "]";
               })
              .Example("[push]"),
      });
  return table;
}

LoopSpec ParseLoopSpec(const ConfigNode& root) {
  if (auto l = root.Find("loop")) return LoopParams().Parse(*l);
  return LoopSpec();
}

LoopJobResult RunClosedLoopJob(const Job& job, const RunOptions& options) {
  const LoopSpec spec = ParseLoopSpec(job.config);
  SceneAssets assets(job.scene, options.assets);
  const ClosedLoopScene where = MakeClosedLoopScene(job.scene, assets);
  LoopJobResult result;
  result.job = job;
  for (const std::string& name : job.models) {
    const std::unique_ptr<ContactModel> model = MakeSceneContactModel(name, job.scene, assets);
    SceneDynamics dynamics = MakeSceneDynamics(assets, where.cycle.cycle_seconds);
    for (LoopMotion motion : spec.motions) {
      LoopRow row{name, motion, spec.loop, {}, WrenchScaleOf(*model)};
      row.loop.motion = motion;
      row.metrics = RunClosedLoop(*model, where, row.loop, &dynamics);
      result.rows.push_back(std::move(row));
    }
  }
  return result;
}

namespace {

// stability.csv's declared columns (after experiment, job and the sweep axes not named here).
const TableColumn<LoopRow> kLoopColumns[] = {
    {"model", "", "the contact model, by its registered name",
     [](const LoopRow& r, CsvLine& l) { l.Text(r.model); }},
    {"motion", "", "the hand's motion: push, slide or corner",
     [](const LoopRow& r, CsvLine& l) { l.Text(LoopMotionName(r.motion)); }},
    {"k_vc", "N/m", "linear coupling stiffness",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.loop.k_vc); }},
    {"wrench_scale", "", "the factor model.stiffness: matched applied to the model's wrench to match the paper's model's stiffness (1: its own stiffness)",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.wrench_scale); }},
    {"k_vc_rot", "N m/rad", "rotational coupling stiffness",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.loop.k_vc_rot); }},
    {"energy_into_hand_J", "J", "passivity observer: work of the device wrench on the handle over the run (positive: the loop put energy in)",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.energy_into_hand); }},
    {"peak_stored_energy_J", "J", "largest coupling-spring energy seen",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.peak_stored_energy); }},
    {"passive", "", "1 when energy_into_hand_J is at most max(1e-6 J, 1 % of peak_stored_energy_J), else 0",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.passive()); }},
    {"early_position_rms_m", "m", "RMS of H's position about its trend over the first 200 ms of the hold",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.early_position_rms); }},
    {"late_position_rms_m", "m", "the same over the last 200 ms of the hold",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.late_position_rms); }},
    {"early_force_rms_N", "N", "RMS of the device force about its trend over the first 200 ms of the hold",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.early_force_rms); }},
    {"late_force_rms_N", "N", "the same over the last 200 ms of the hold",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.late_force_rms); }},
    {"hold_force_mean_N", "N", "|mean device force| over the last 200 ms of the hold",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6e", r.metrics.hold_force_mean); }},
    {"settled", "", "1 when late_position_rms_m < 20 um and late_force_rms_N < 0.05 N, else 0",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.settled()); }},
    {"max_contact_force_N", "N", "largest contact force",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.metrics.max_contact_force); }},
    {"max_device_force_N", "N", "largest force written to the device, after the safety filter",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.metrics.max_device_force); }},
    {"clamped_cycles", "", "cycles whose force or torque the safety filter clamped",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.clamped_cycles); }},
    {"non_finite_cycles", "", "cycles whose non-finite wrench the safety filter zeroed",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.non_finite_cycles); }},
    {"solve_failures", "", "cycles whose virtual-coupling solve failed",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.solve_failures); }},
    {"coherence_resets", "", "cycles where H outran model.max_point_speed, each resetting the model",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.coherence_resets); }},
    {"contact_faults", "", "cycles whose query the model refused (no force)",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.contact_faults); }},
    {"max_q_norm", "", "largest |q| of a deformable body (0: both rigid)",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.metrics.max_q_norm); }},
    {"max_points_in_contact", "", "most points in contact in one cycle",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.max_points_in_contact); }},
    {"max_force_jump_N", "N", "largest change of the device force from one cycle to the next",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.metrics.max_force_jump); }},
    {"rate_hz", "Hz", "the loop's rate, 1 / model.cycle_seconds",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.6g", r.metrics.rate_hz); }},
    {"cycles", "", "cycles simulated (at rate_hz)",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.cycles); }},
    {"stable", "", "1 when finite, without faults, passive and settled, else 0",
     [](const LoopRow& r, CsvLine& l) { l.Int(r.metrics.stable()); }},
    {"verdict", "", "why the run is not stable (non-finite, solve failed, contact faults, active, oscillates), or ok",
     [](const LoopRow& r, CsvLine& l) { l.Text(StabilityVerdict(r.metrics)); }},
    {"wall_s", "s", "wall time of the run",
     [](const LoopRow& r, CsvLine& l) { l.Num("%.3f", r.metrics.wall_seconds); }},
};

const ResultTable& StabilityTable() {
  static const ResultTable table = DeclareTable("stability.csv", "one row per job, model and motion",
                                                TableKeys::kJobAndOtherAxes, kLoopColumns);
  return table;
}

// Every job's loop section parses and its cycle is one the study can judge (an error names
// the job's sweep values).
void CheckClosedLoopStudy(const ExperimentConfig& config, const ConfigNode&, const Job& job) {
  try {
    (void)ParseLoopSpec(job.config);
    CheckClosedLoopApproach(job.scene, config.file);
    if (job.scene.model.cycle_seconds > kClosedLoopMaxCycleSeconds) {
      char text[200];
      std::snprintf(text, sizeof text,
                    "model.cycle_seconds: %g s is too slow for the closed-loop study, whose 200 ms windows need at "
                    "least 10 cycles each: at most %g s",
                    job.scene.model.cycle_seconds, kClosedLoopMaxCycleSeconds);
      Fail(config.file, text);
    }
  } catch (const Error& e) {
    if (config.sweep.empty()) throw;
    Fail(config.file + " (job " + job.Label() + ")", e.what());
  }
}

// Runs the jobs, writes stability.csv and meta.json, prints one line per run.
void RunClosedLoopStudy(const ExperimentConfig& config, const RunOptions& options, const std::vector<int>& only) {
  const std::size_t total = JobCount(config);
  std::fprintf(stderr, "experiment %s (closed-loop study): %zu of %zu jobs, models:", config.name.c_str(),
               only.empty() ? total : only.size(), total);
  for (const auto& m : config.models) std::fprintf(stderr, " %s", m.c_str());
  std::fprintf(stderr, "\n");
  std::vector<LoopJobResult> results(only.empty() ? total : only.size());
  const JobsRun jobs = RunJobs(config, only, options, [&](std::size_t i, const Job& job) {
    results[i] = RunClosedLoopJob(job, options);
  });
  WriteStudyResults(StudyOf(config), options.out_dir, {StabilityCsv(config, results)},
                    RunMetadata(config, jobs.indices, jobs.wall_seconds, jobs.parallel));
  std::printf("%-6s %-24s %-7s %9s %12s %12s %12s  %s\n", "job", "model", "motion", "k_vc", "energy J", "late H m",
              "late F N", "verdict");
  for (const LoopJobResult& r : results) {
    for (const LoopRow& row : r.rows) {
      std::printf("%-6d %-24s %-7s %9.4g %+12.3e %12.3e %12.3e  %s\n", r.job.index, row.model.c_str(),
                  LoopMotionName(row.motion), row.loop.k_vc, row.metrics.energy_into_hand,
                  row.metrics.late_position_rms, row.metrics.late_force_rms, StabilityVerdict(row.metrics).c_str());
    }
  }
}

}  // namespace

std::string StabilityCsv(const ExperimentConfig& config, const std::vector<LoopJobResult>& results) {
  const ResultTable& table = StabilityTable();
  std::string out = table.Header(config);
  for (const LoopJobResult& r : results) {
    for (const LoopRow& row : r.rows) {
      CsvLine line(&out);
      table.AppendKeys(config, r.job, &line);
      AppendCells(kLoopColumns, row, &line);
      out += '\n';
    }
  }
  return out;
}

void RegisterClosedLoopStudy() {
  Study s;
  s.name = "closed-loop";
  s.description = "passivity and settling of the simulated haptic loop per model and motion (sec. 5)";
  s.sections = {
      {"models", "list of model names (default: the scene's)", "the contact models each job closes the loop with"},
      {"loop", "mapping (below)", "the simulated hand, the coupling and the motions"},
  };
  for (const std::string& key : LoopParams().SweepKeys()) s.aliases.push_back({key, "loop." + key});
  s.tables = {StabilityTable()};
  s.check = CheckClosedLoopStudy;
  s.run = RunClosedLoopStudy;
  s.reference = [] { return LoopParams().Reference("loop"); };
  RegisterStudy(std::move(s));
}

}  // namespace contactlab
