#include "geometry/pose_samples_csv.h"

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>

#include "util/atomic_file.h"
#include "util/error.h"

namespace contactlab {

PoseSamples ReadPoseSamplesCsv(const std::filesystem::path& file) {
  const std::string name = file.string();
  // A named pipe would block the open; a folder or device is named for what it is.
  if (const std::string kind = NonRegularFileKind(file); !kind.empty()) Fail(name, "is " + kind + ", not a trajectory file");
  // Read whole through the one input reader, which records it as an input of the command.
  std::istringstream in(ReadWholeFile(file));
  PoseSamples out;
  std::string line;
  long line_no = 0;
  bool first_row = true;
  while (std::getline(in, line)) {
    ++line_no;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    const std::size_t first = line.find_first_not_of(" \t");
    if (first == std::string::npos || line[first] == '#') continue;
    // An optional header before the first row.
    if (first_row && std::isalpha(static_cast<unsigned char>(line[first]))) {
      if (line.compare(first, 19, "t,x,y,z,qw,qx,qy,qz") != 0) {
        FailAtLine(name, line_no, "header must start with t,x,y,z,qw,qx,qy,qz");
      }
      first_row = false;
      continue;
    }
    first_row = false;
    // At least eight comma-separated numbers.
    double v[8];
    int count = 0;
    std::size_t pos = 0;
    while (count < 8 && pos <= line.size()) {
      std::size_t end = line.find(',', pos);
      if (end == std::string::npos) end = line.size();
      std::string item = line.substr(pos, end - pos);
      const std::size_t a = item.find_first_not_of(" \t"), b = item.find_last_not_of(" \t");
      item = a == std::string::npos ? std::string() : item.substr(a, b - a + 1);
      const auto [ptr, ec] = std::from_chars(item.data(), item.data() + item.size(), v[count]);
      if (ec != std::errc() || ptr != item.data() + item.size()) {
        FailAtLine(name, line_no, "column " + std::to_string(count + 1) + " '" + QuoteToken(item) + "' is not a number");
      }
      if (!std::isfinite(v[count])) FailAtLine(name, line_no, "column " + std::to_string(count + 1) + " is not finite");
      ++count;
      if (end == line.size()) break;
      pos = end + 1;
    }
    if (count < 8) {
      FailAtLine(name, line_no, "expected at least 8 columns t,x,y,z,qw,qx,qy,qz, got " + std::to_string(count));
    }
    const Eigen::Quaterniond q(v[4], v[5], v[6], v[7]);
    if (const std::optional<std::string> e = NonUnitQuaternionError(q)) FailAtLine(name, line_no, *e);
    if (!out.t.empty() && !(v[0] > out.t.back())) {
      FailAtLine(name, line_no, "time " + std::to_string(v[0]) + " is not greater than the previous row's");
    }
    out.t.push_back(v[0]);
    out.poses.push_back(Pose{q.normalized(), Eigen::Vector3d(v[1], v[2], v[3])});
  }
  if (out.t.empty()) Fail(name, "the trajectory has no samples (rows t,x,y,z,qw,qx,qy,qz)");
  return out;
}

}  // namespace contactlab
