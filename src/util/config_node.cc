#include "util/config_node.h"

#include <algorithm>
#include <cmath>
#include <set>

#include "util/atomic_file.h"
#include "util/error.h"
#include "util/parse_number.h"

namespace contactlab {

namespace {

[[noreturn]] void FailTooLarge(const std::string& file, std::uintmax_t bytes) {
  contactlab::Fail(file, "is " + std::to_string(bytes) + " bytes; a config or scene file may hold at most " +
                             std::to_string(kMaxConfigBytes) + " bytes (1 MiB)");
}

}  // namespace

std::string ConfigNode::ReadText(const std::filesystem::path& file) {
  // The size is checked before reading where the file says it (a regular file); what is read is
  // checked again (a file that grew, or one that reports no size).
  std::error_code ec;
  if (std::filesystem::is_regular_file(file, ec)) {
    const std::uintmax_t bytes = std::filesystem::file_size(file, ec);
    if (!ec && bytes > kMaxConfigBytes) FailTooLarge(file.string(), bytes);
  }
  std::string text = ReadWholeFile(file);
  if (text.size() > kMaxConfigBytes) FailTooLarge(file.string(), text.size());
  return text;
}

ConfigNode ConfigNode::LoadFile(const std::filesystem::path& file) {
  const std::string text = ReadText(file);
  return LoadString(text, file.string());
}

ConfigNode ConfigNode::LoadString(const std::string& text, const std::string& file_label) {
  if (text.size() > kMaxConfigBytes) FailTooLarge(file_label, text.size());
  YAML::Node root;
  try {
    root = YAML::Load(text);
  } catch (const YAML::Exception& e) {
    FailAtLine(file_label, e.mark.line + 1, "YAML syntax error: " + e.msg);
  }
  if (!root || root.IsNull()) contactlab::Fail(file_label, "the file is empty");
  return ConfigNode(root, std::make_shared<const std::string>(file_label), "");
}

ConfigNode::ConfigNode(YAML::Node node, std::shared_ptr<const std::string> file, std::string path)
    : node_(std::move(node)), file_(std::move(file)), path_(std::move(path)) {}

std::string ConfigNode::Location() const {
  std::string where = *file_;
  const YAML::Mark mark = node_.Mark();
  if (mark.line >= 0) where += ":" + std::to_string(mark.line + 1);
  return where + ": " + (path_.empty() ? std::string("(top level)") : path_);
}

void ConfigNode::Fail(const std::string& what) const { contactlab::Fail(Location(), what); }

std::string ConfigNode::ChildPath(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

void ConfigNode::ExpectMap() const {
  if (!node_.IsMap()) Fail("expected a mapping of keys to values");
}

void ConfigNode::RejectDuplicateKeys() const {
  // yaml-cpp keeps both entries of a repeated key and lookups see only the first, so a
  // second "k_C:" further down would be silently ignored.
  std::set<std::string> seen;
  for (const auto& kv : node_) {
    // A complex key ("? [a, b]: 1", "{a: 1}: 2") is no name: refused here, before any lookup
    // converts it (yaml-cpp would throw its own bad-conversion exception).
    if (!kv.first.IsScalar()) {
      ConfigNode(kv.first, file_, path_).Fail("a key must be a plain name, not a sequence or mapping");
    }
    const std::string key = kv.first.as<std::string>();
    if (!seen.insert(key).second) {
      ConfigNode(kv.first, file_, ChildPath(key)).Fail("duplicate key '" + QuoteToken(key) +
                                                       "' (each key may appear once in a mapping)");
    }
  }
}

void ConfigNode::ExpectKeys(std::initializer_list<const char*> allowed) const {
  ExpectKeys(std::vector<std::string>(allowed.begin(), allowed.end()));
}

void ConfigNode::ExpectKeys(const std::vector<std::string>& allowed) const {
  ExpectMap();
  RejectDuplicateKeys();
  for (const auto& kv : node_) {
    const std::string key = kv.first.as<std::string>();
    if (std::find(allowed.begin(), allowed.end(), key) == allowed.end()) {
      std::string list;
      for (const std::string& a : allowed) list += (list.empty() ? "" : ", ") + a;
      ConfigNode(kv.first, file_, ChildPath(key)).Fail("unknown key (known keys here: " + list + ")");
    }
  }
}

std::string ConfigNode::Quoted() const { return QuoteToken(AsString()); }

bool ConfigNode::Has(const std::string& key) const { return node_.IsMap() && node_[key]; }

ConfigNode ConfigNode::Get(const std::string& key) const {
  ExpectMap();
  const YAML::Node child = node_[key];
  if (!child) Fail("missing required key '" + key + "'");
  return ConfigNode(child, file_, ChildPath(key));
}

std::optional<ConfigNode> ConfigNode::Find(const std::string& key) const {
  if (!Has(key)) return std::nullopt;
  return ConfigNode(node_[key], file_, ChildPath(key));
}

std::vector<ConfigNode> ConfigNode::Elements() const {
  if (!node_.IsSequence()) Fail("expected a list");
  std::vector<ConfigNode> out;
  for (std::size_t i = 0; i < node_.size(); ++i) {
    out.emplace_back(node_[i], file_, path_ + "[" + std::to_string(i) + "]");
  }
  return out;
}

std::vector<std::string> ConfigNode::Keys() const {
  ExpectMap();
  RejectDuplicateKeys();
  std::vector<std::string> keys;
  for (const auto& kv : node_) keys.push_back(kv.first.as<std::string>());
  return keys;
}

std::string ConfigNode::AsString() const {
  if (!node_.IsScalar()) Fail("expected a single value");
  return node_.Scalar();
}

double ConfigNode::AsDouble() const {
  const std::string s = AsString();
  const std::optional<double> v = ParseDouble(s);
  if (!v) {
    const std::string_view t(s);
    const bool numeric = !t.empty() && t.find_first_not_of("+-.0123456789eE \t") == std::string_view::npos &&
                         t.find_first_of("0123456789") != std::string_view::npos;
    Fail(numeric ? "the number '" + QuoteToken(s) + "' is out of range (finite doubles only, |x| < 1.8e308)"
                 : "expected a finite number, got '" + QuoteToken(s) + "'");
  }
  return *v;
}

long long ConfigNode::AsInt() const {
  const std::string s = AsString();
  const std::optional<long long> v = ParseInteger(s);
  if (!v) {
    const bool digits = !s.empty() && s.find_first_not_of("+-0123456789") == std::string::npos &&
                        s.find_first_of("0123456789") != std::string::npos;
    Fail(digits ? "the integer '" + QuoteToken(s) + "' is out of range" : "expected an integer, got '" + QuoteToken(s) + "'");
  }
  return *v;
}

bool ConfigNode::AsBool() const {
  const std::string s = AsString();
  if (s == "true" || s == "yes" || s == "on") return true;
  if (s == "false" || s == "no" || s == "off") return false;
  Fail("expected true or false, got '" + QuoteToken(s) + "'");
}

std::vector<double> ConfigNode::AsDoubles() const {
  std::vector<double> v;
  for (const ConfigNode& e : Elements()) v.push_back(e.AsDouble());
  return v;
}

double ConfigNode::Double(const std::string& key, double fallback) const {
  auto c = Find(key);
  return c ? c->AsDouble() : fallback;
}
long long ConfigNode::Int(const std::string& key, long long fallback) const {
  auto c = Find(key);
  return c ? c->AsInt() : fallback;
}
bool ConfigNode::Bool(const std::string& key, bool fallback) const {
  auto c = Find(key);
  return c ? c->AsBool() : fallback;
}
std::string ConfigNode::String(const std::string& key, const std::string& fallback) const {
  auto c = Find(key);
  return c ? c->AsString() : fallback;
}

double ConfigNode::NonNegative(const std::string& key, double fallback) const {
  auto c = Find(key);
  if (!c) return fallback;
  const double v = c->AsDouble();
  if (v < 0) c->Fail("must not be negative, got " + QuoteToken(c->AsString()));
  return v;
}

double ConfigNode::Positive(const std::string& key, double fallback) const {
  auto c = Find(key);
  if (!c) return fallback;
  const double v = c->AsDouble();
  if (!(v > 0)) c->Fail("must be positive, got " + QuoteToken(c->AsString()));
  return v;
}

long long ConfigNode::PositiveInt(const std::string& key, long long fallback) const {
  auto c = Find(key);
  if (!c) return fallback;
  const long long v = c->AsInt();
  if (v <= 0) c->Fail("must be a positive integer, got " + QuoteToken(c->AsString()));
  return v;
}

long long ConfigNode::IntInRange(const std::string& key, long long fallback, long long lo, long long hi) const {
  auto c = Find(key);
  if (!c) return fallback;
  const long long v = c->AsInt();
  if (v < lo || v > hi) {
    c->Fail("must be between " + std::to_string(lo) + " and " + std::to_string(hi) + ", got " +
            QuoteToken(c->AsString()));
  }
  return v;
}

std::string ConfigNode::OneOf(const std::string& key, const std::string& fallback,
                              std::initializer_list<const char*> choices) const {
  return OneOf(key, fallback, std::vector<std::string>(choices.begin(), choices.end()));
}

std::string ConfigNode::OneOf(const std::string& key, const std::string& fallback,
                              const std::vector<std::string>& choices) const {
  auto c = Find(key);
  if (!c) return fallback;
  const std::string v = c->AsString();
  std::string list;
  for (const std::string& ch : choices) {
    if (v == ch) return v;
    list += (list.empty() ? "" : ", ") + ch;
  }
  c->Fail("'" + QuoteToken(v) + "' is not one of: " + list);
}

}  // namespace contactlab
