// Strict reading of YAML configuration files (scenes, experiments): every key must be known,
// every value of the right type, and every error names the file, the line and the key path
// ("scene.yaml:12: bodies[1].pointshell.points: expected a positive integer, got 'many'").
#pragma once

#include <yaml-cpp/yaml.h>

#include <cstddef>
#include <filesystem>
#include <initializer_list>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace contactlab {

// The largest scene or experiment config read, in bytes (1 MiB; the shipped ones are under
// 4 kB). Checked before a file is read and parsed: the YAML parser takes about a hundred times
// a text's size in memory, so a 100 MB config would end in std::bad_alloc, not in an Error.
inline constexpr std::size_t kMaxConfigBytes = std::size_t(1) << 20;

class ConfigNode {
 public:
  // The text of the config or scene FILE; throws Error naming it when it is missing, not a
  // regular file, or larger than kMaxConfigBytes (checked before it is read).
  static std::string ReadText(const std::filesystem::path& file);
  // Parses FILE (ReadText, then LoadString); throws Error naming it on a YAML syntax error or a
  // missing or oversized file.
  static ConfigNode LoadFile(const std::filesystem::path& file);
  // Parses TEXT as if read from FILE_LABEL (for tests and --set overrides); a TEXT larger than
  // kMaxConfigBytes is refused before it is parsed.
  static ConfigNode LoadString(const std::string& text, const std::string& file_label);

  ConfigNode() : file_(std::make_shared<const std::string>()) {}
  ConfigNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path);

  const std::string& file() const { return *file_; }
  const std::string& path() const { return path_; }
  const YAML::Node& yaml() const { return node_; }
  bool IsMap() const { return node_.IsMap(); }
  bool IsSequence() const { return node_.IsSequence(); }
  bool IsScalar() const { return node_.IsScalar(); }

  // Throws unless this is a map whose keys are all in ALLOWED.
  void ExpectKeys(std::initializer_list<const char*> allowed) const;
  void ExpectKeys(const std::vector<std::string>& allowed) const;
  void ExpectMap() const;
  bool Has(const std::string& key) const;
  // Child by key (must exist) or nullopt.
  ConfigNode Get(const std::string& key) const;
  std::optional<ConfigNode> Find(const std::string& key) const;
  // Elements of a sequence.
  std::vector<ConfigNode> Elements() const;
  std::vector<std::string> Keys() const;

  // Typed values of this node.
  double AsDouble() const;
  long long AsInt() const;
  bool AsBool() const;
  std::string AsString() const;
  std::vector<double> AsDoubles() const;

  // Typed child values with defaults (the key may be absent).
  double Double(const std::string& key, double fallback) const;
  long long Int(const std::string& key, long long fallback) const;
  bool Bool(const std::string& key, bool fallback) const;
  std::string String(const std::string& key, const std::string& fallback) const;
  // Constrained helpers.
  double NonNegative(const std::string& key, double fallback) const;
  double Positive(const std::string& key, double fallback) const;
  long long PositiveInt(const std::string& key, long long fallback) const;
  // An integer in [LO, HI]; the error names both bounds.
  long long IntInRange(const std::string& key, long long fallback, long long lo, long long hi) const;
  std::string OneOf(const std::string& key, const std::string& fallback,
                    std::initializer_list<const char*> choices) const;
  std::string OneOf(const std::string& key, const std::string& fallback, const std::vector<std::string>& choices) const;

  // This scalar's text as error messages quote it (shortened, control characters escaped).
  std::string Quoted() const;

  // "FILE:LINE: PATH", the place Fail names.
  std::string Location() const;
  // Throws Error("FILE:LINE: PATH: WHAT").
  [[noreturn]] void Fail(const std::string& what) const;

 private:
  std::string ChildPath(const std::string& key) const;
  // Throws naming the second occurrence of a key repeated in this mapping.
  void RejectDuplicateKeys() const;
  YAML::Node node_;
  std::shared_ptr<const std::string> file_;
  std::string path_;
};

}  // namespace contactlab
