#include "experiment/result_csv.h"

#include <cstdio>
#include <sstream>

namespace contactlab {
namespace {

template <class Row>
struct Column {
  const char* name;
  void (*write)(const Row&, CsvLine&);
};

// cycles.csv: the moving body's pose (origin x,y,z and orientation quaternion qw,qx,qy,qz,
// world), the model's wrench on the moving body, its contact statistics and time per cycle,
// and the reference force where one was evaluated (empty cells elsewhere).
const Column<CycleRow> kCycleColumns[] = {
    {"model", [](const CycleRow& r, CsvLine& l) { l.Text(r.model); }},
    {"cycle", [](const CycleRow& r, CsvLine& l) { l.Int(r.cycle); }},
    {"t", [](const CycleRow& r, CsvLine& l) { l.Num("%.6f", r.t); }},
    {"x", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.position.x()); }},
    {"y", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.position.y()); }},
    {"z", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.position.z()); }},
    {"qw", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.w()); }},
    {"qx", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.x()); }},
    {"qy", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.y()); }},
    {"qz", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.rotation.z()); }},
    {"fx", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.force.x()); }},
    {"fy", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.force.y()); }},
    {"fz", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.force.z()); }},
    {"tx", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.torque.x()); }},
    {"ty", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.torque.y()); }},
    {"tz", [](const CycleRow& r, CsvLine& l) { l.Num("%.9g", r.torque.z()); }},
    {"contacts", [](const CycleRow& r, CsvLine& l) { l.Int(r.contacts); }},
    {"nodes", [](const CycleRow& r, CsvLine& l) { l.Int(r.nodes); }},
    {"level", [](const CycleRow& r, CsvLine& l) { l.Int(r.level); }},
    {"max_penetration", [](const CycleRow& r, CsvLine& l) { l.Num("%.6g", r.max_penetration); }},
    {"depth_voxels", [](const CycleRow& r, CsvLine& l) { l.Num("%.4g", r.depth_voxels); }},
    {"time_us", [](const CycleRow& r, CsvLine& l) { l.Num("%.3f", r.time_us); }},
    {"ref_fx", [](const CycleRow& r, CsvLine& l) { r.has_reference ? l.Num("%.9g", r.reference_force.x()) : l.Empty(); }},
    {"ref_fy", [](const CycleRow& r, CsvLine& l) { r.has_reference ? l.Num("%.9g", r.reference_force.y()) : l.Empty(); }},
    {"ref_fz", [](const CycleRow& r, CsvLine& l) { r.has_reference ? l.Num("%.9g", r.reference_force.z()) : l.Empty(); }},
    {"step_us", [](const CycleRow& r, CsvLine& l) { r.q.empty() ? l.Empty() : l.Num("%.3f", r.step_us); }},
    {"step_B_us", [](const CycleRow& r, CsvLine& l) { r.q_B.empty() ? l.Empty() : l.Num("%.3f", r.step_B_us); }},
    {"elastic_energy_J", [](const CycleRow& r, CsvLine& l) { r.deformable ? l.Num("%.9g", r.elastic_energy) : l.Empty(); }},
    {"kinetic_energy_J", [](const CycleRow& r, CsvLine& l) { r.deformable ? l.Num("%.9g", r.kinetic_energy) : l.Empty(); }},
    {"max_displacement", [](const CycleRow& r, CsvLine& l) { r.deformable ? l.Num("%.9g", r.max_displacement) : l.Empty(); }},
    {"q", [](const CycleRow& r, CsvLine& l) { l.Numbers("%.9g", r.q); }},
    {"q_B", [](const CycleRow& r, CsvLine& l) { l.Numbers("%.9g", r.q_B); }},
};

// summary.csv: per model and job, continuity, timing, error against the reference and force
// magnitude metrics (an error of -1: no reference), and the memory of the body data the model
// reads (empty cells for data it does not read).
const Column<SummaryRow> kSummaryColumns[] = {
    {"model", [](const SummaryRow& r, CsvLine& l) { l.Text(r.model); }},
    {"points", [](const SummaryRow& r, CsvLine& l) { l.Int(r.points); }},
    {"cycles", [](const SummaryRow& r, CsvLine& l) { l.Int(r.cycles); }},
    {"max_jump_N", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.max_jump); }},
    {"lipschitz_N_per_m", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.lipschitz); }},
    {"hf_share", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.hf_share); }},
    {"max_jump_rel", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.max_jump_rel); }},
    {"lipschitz_rel_per_m", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.lipschitz_rel); }},
    {"median_us", [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.median_us); }},
    {"p99_us", [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.p99_us); }},
    {"max_us", [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.max_us); }},
    {"mean_nodes", [](const SummaryRow& r, CsvLine& l) { l.Num("%.1f", r.mean_nodes); }},
    {"level_switches_per_s", [](const SummaryRow& r, CsvLine& l) { l.Num("%.3f", r.level_switches_per_s); }},
    {"rms_rel_error", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.rms_rel_error); }},
    {"max_dir_error_deg", [](const SummaryRow& r, CsvLine& l) { l.Num("%.4g", r.max_dir_error_deg); }},
    {"median_dir_error_deg", [](const SummaryRow& r, CsvLine& l) { l.Num("%.4g", r.median_dir_error_deg); }},
    {"p95_dir_error_deg", [](const SummaryRow& r, CsvLine& l) { l.Num("%.4g", r.p95_dir_error_deg); }},
    {"ref_scale", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.ref_scale); }},
    {"rms_rel_error_calibrated", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.rms_rel_error_calibrated); }},
    {"max_force_N", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.max_force); }},
    {"mean_force_N", [](const SummaryRow& r, CsvLine& l) { l.Num("%.6g", r.mean_force); }},
    {"max_depth_voxels", [](const SummaryRow& r, CsvLine& l) { l.Num("%.4g", r.max_depth_voxels); }},
    {"coherence_resets", [](const SummaryRow& r, CsvLine& l) { l.Int(r.coherence_resets); }},
    {"contact_faults", [](const SummaryRow& r, CsvLine& l) { l.Int(r.contact_faults); }},
    {"modes", [](const SummaryRow& r, CsvLine& l) { l.Int(r.modes); }},
    {"median_step_us", [](const SummaryRow& r, CsvLine& l) { r.modes > 0 ? l.Num("%.3f", r.median_step_us) : l.Empty(); }},
    {"modes_B", [](const SummaryRow& r, CsvLine& l) { l.Int(r.modes_B); }},
    {"median_step_B_us", [](const SummaryRow& r, CsvLine& l) { r.modes_B > 0 ? l.Num("%.3f", r.median_step_B_us) : l.Empty(); }},
    {"max_displacement", [](const SummaryRow& r, CsvLine& l) { r.modes + r.modes_B > 0 ? l.Num("%.9g", r.max_displacement) : l.Empty(); }},
    {"field_B_bytes", [](const SummaryRow& r, CsvLine& l) { r.field_B_bytes >= 0 ? l.Int(r.field_B_bytes) : l.Empty(); }},
    {"pointshell_A_bytes", [](const SummaryRow& r, CsvLine& l) { r.pointshell_A_bytes >= 0 ? l.Int(r.pointshell_A_bytes) : l.Empty(); }},
};

// experiment,job,<axis names>,<column names>
template <class Row, std::size_t N>
std::string Header(const ExperimentConfig& config, const Column<Row> (&columns)[N]) {
  std::string h;
  CsvLine line(&h);
  line.Text("experiment");
  line.Text("job");
  for (const SweepAxis& a : config.sweep) line.Text(a.name);
  for (const Column<Row>& c : columns) line.Text(c.name);
  return h + "\n";
}

template <class Row, std::size_t N>
void AppendRows(const ExperimentConfig& config, const JobResult& r, const std::vector<Row>& rows,
                const Column<Row> (&columns)[N], std::string* out) {
  for (const Row& row : rows) {
    CsvLine line(out);
    line.Text(config.name);
    line.Int(r.job.index);
    for (const auto& [axis, value] : r.job.axis_values) line.Text(value);
    for (const Column<Row>& c : columns) c.write(row, line);
    *out += '\n';
  }
}

}  // namespace

std::string CyclesCsvHeader(const ExperimentConfig& config) { return Header(config, kCycleColumns); }
std::string SummaryCsvHeader(const ExperimentConfig& config) { return Header(config, kSummaryColumns); }

void AppendCyclesCsv(const ExperimentConfig& config, const JobResult& r, std::string* out) {
  AppendRows(config, r, r.cycles, kCycleColumns, out);
}
void AppendSummaryCsv(const ExperimentConfig& config, const JobResult& r, std::string* out) {
  AppendRows(config, r, r.summary, kSummaryColumns, out);
}

std::vector<std::string> SplitCsvLine(const std::string& line) {
  std::vector<std::string> cells;
  std::stringstream ss(line);
  std::string cell;
  while (std::getline(ss, cell, ',')) cells.push_back(cell);
  if (!line.empty() && line.back() == ',') cells.emplace_back();
  return cells;
}

}  // namespace contactlab
