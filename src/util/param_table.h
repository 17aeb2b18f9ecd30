// Parameters declared once. A parameter block (a scene's pointshell, field or deformable section,
// the contact model's section, ...) is one table; each row is one key: its type and range, its
// unit, what it means, the member it fills, which cached artefacts its value shapes, and whether
// a sweep may name it by its key alone. From the table come the block's parsing (unknown keys
// refused, every value range-checked, errors naming file, line and key), its part of each
// artefact's cache key, the sweep-axis aliases and its section of the scene reference
// (`contactlab params`). Adding a parameter is adding a row.
//
//   using P = ParamRows<PointshellSpec>;
//   const ParamTable<PointshellSpec> table("pointshell", "the body's pointshell", {
//       P::Integer("points", PARAM_MEMBER(points), 1, kMaxPointshellPoints, "points on the deepest level")
//           .Shapes(kShapesPointshell).Sweepable().Example("1000"),
//       ...});
#pragma once

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <functional>
#include <limits>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "util/config_node.h"
#include "util/hasher.h"

namespace contactlab {

// The member of a block's struct that a row fills: PARAM_MEMBER(material.density).
#define PARAM_MEMBER(member) [](auto& s) -> auto& { return s.member; }

// The cached artefacts of a body (scene/scene_assets.h) a parameter's value may shape.
enum ParamArtefact : unsigned {
  kShapesNothing = 0,
  kShapesField = 1u << 0,
  kShapesPointshell = 1u << 1,
  kShapesReducedModel = 1u << 2,
};

// The names of the artefacts in SHAPES ("field, pointshell"; "" for none).
inline std::string ArtefactNames(unsigned shapes) {
  std::string s;
  const std::pair<unsigned, const char*> names[] = {
      {kShapesField, "field"}, {kShapesPointshell, "pointshell"}, {kShapesReducedModel, "reduced model"}};
  for (const auto& [bit, name] : names) {
    if (shapes & bit) s += (s.empty() ? "" : ", ") + std::string(name);
  }
  return s;
}

template <class Spec>
struct ParamRow {
  std::string key;
  std::string type;   // as the reference shows it: integer, number, boolean, choice, ...
  std::string range;  // "8 to 1024", "> 0", "stvk, linear", ...
  std::string unit;   // "m", "Pa", ... ("" for none)
  std::string doc;
  unsigned shapes = kShapesNothing;  // ParamArtefact bits
  bool sweep = false;                // a sweep axis may name it by its key alone
  std::string example;               // a valid value other than the default (YAML), for tests
  std::string default_text;          // the reference's default when the member's value says less
  std::function<void(const ConfigNode& value, Spec*)> read;          // checks VALUE, sets the member
  std::function<void(const Spec&, unsigned artefact, Hasher*)> hash;  // its part of ARTEFACT's key
  std::function<std::string(const Spec&)> show;                      // the member as text

  ParamRow& Shapes(unsigned artefacts) {
    shapes = artefacts;
    return *this;
  }
  ParamRow& Sweepable() {
    sweep = true;
    return *this;
  }
  ParamRow& Unit(std::string u) {
    unit = std::move(u);
    return *this;
  }
  ParamRow& Example(std::string e) {
    example = std::move(e);
    return *this;
  }
  ParamRow& Default(std::string text) {
    default_text = std::move(text);
    return *this;
  }
};

template <class Spec>
class ParamTable {
 public:
  // Cross-checks of the whole block after its keys are read (e.g. "band applies to sparse
  // storage only"), throwing through BLOCK.Fail or its children's, and values derived from
  // others (a body's name defaults to its mesh).
  using Check = std::function<void(const ConfigNode& block, Spec*)>;

  ParamTable(std::string name, std::string doc, std::vector<ParamRow<Spec>> rows, Check check = nullptr)
      : name_(std::move(name)), doc_(std::move(doc)), rows_(std::move(rows)), check_(std::move(check)) {}

  const std::string& name() const { return name_; }
  const std::string& doc() const { return doc_; }
  const std::vector<ParamRow<Spec>>& rows() const { return rows_; }
  const Check& check() const { return check_; }
  const ParamRow<Spec>* Find(const std::string& key) const {
    for (const auto& r : rows_) {
      if (r.key == key) return &r;
    }
    return nullptr;
  }
  std::vector<std::string> Keys() const {
    std::vector<std::string> keys;
    for (const auto& r : rows_) keys.push_back(r.key);
    return keys;
  }
  std::vector<std::string> SweepKeys() const {
    std::vector<std::string> keys;
    for (const auto& r : rows_) {
      if (r.sweep) keys.push_back(r.key);
    }
    return keys;
  }
  // The artefacts any row shapes.
  unsigned Shapes() const {
    unsigned s = 0;
    for (const auto& r : rows_) s |= r.shapes;
    return s;
  }

  // Reads the mapping NODE over BASE: a key that is neither a row nor in EXTRA_KEYS (keys the
  // caller reads itself) is an error, each row present reads and checks its value, then the
  // table's cross-checks run.
  Spec Parse(const ConfigNode& node, Spec base = Spec(), const std::vector<std::string>& extra_keys = {}) const {
    std::vector<std::string> keys = Keys();
    keys.insert(keys.end(), extra_keys.begin(), extra_keys.end());
    node.ExpectKeys(keys);
    for (const auto& r : rows_) {
      if (auto v = node.Find(r.key)) r.read(*v, &base);
    }
    if (check_) check_(node, &base);
    return base;
  }

  // SPEC's part of ARTEFACT's cache key: every row that shapes it, key and value.
  void Hash(const Spec& spec, unsigned artefact, Hasher* h) const {
    for (const auto& r : rows_) {
      if (!(r.shapes & artefact) || !r.hash) continue;
      h->Text(r.key);
      r.hash(spec, artefact, h);
    }
  }

  // The block's section of the scene reference (Markdown), defaults from DEFAULTS; a sweep names
  // a key as ALIAS_PREFIX + key.
  std::string Reference(const std::string& path, const Spec& defaults = Spec(), const std::string& alias_prefix = "") const {
    std::string s = "### `" + path + "`\n\n" + doc_ + "\n\n| key | type | range | default | unit | cached in | sweep axis | meaning |\n|---|---|---|---|---|---|---|---|\n";
    for (const auto& r : rows_) {
      const std::string cached = ArtefactNames(r.shapes);
      const std::string value = r.default_text.empty() ? r.show(defaults) : r.default_text;
      s += "| `" + r.key + "` | " + Cell(r.type) + " | " + Cell(r.range) + " | " + Cell(value) + " | " + r.unit +
           " | " + cached + " | " + (r.sweep ? "`" + alias_prefix + r.key + "`" : "") + " | " + Cell(r.doc) + " |\n";
    }
    return s + "\n";
  }

 private:
  // TEXT as a Markdown table cell: its bars escaped.
  static std::string Cell(const std::string& text) {
    std::string out;
    for (const char c : text) out += c == '|' ? std::string("\\|") : std::string(1, c);
    return out;
  }

  std::string name_, doc_;
  std::vector<ParamRow<Spec>> rows_;
  Check check_;
};

// Bounds of a number row: a value and whether it is excluded.
struct ParamBound {
  double value;
  bool open;
};
inline ParamBound Above(double v) { return {v, true}; }
inline ParamBound AtLeast(double v) { return {v, false}; }
inline ParamBound Below(double v) { return {v, true}; }
inline ParamBound AtMost(double v) { return {v, false}; }
inline ParamBound NoLowerBound() { return {-std::numeric_limits<double>::infinity(), false}; }
inline ParamBound NoUpperBound() { return {std::numeric_limits<double>::infinity(), false}; }

namespace param_detail {

inline std::string Number(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

template <class T>
void HashValue(const T& v, Hasher* h) {
  if constexpr (std::is_same_v<T, std::string>) {
    h->Text(v);
  } else {
    h->Value(v);
  }
}

}  // namespace param_detail

// The kinds of row, for a block whose struct is SPEC. GET is a member accessor (PARAM_MEMBER).
template <class Spec>
struct ParamRows {
  using Row = ParamRow<Spec>;

  // An integer in [LO, HI] (HI = kNoLimit: no upper bound).
  static constexpr long long kNoLimit = std::numeric_limits<long long>::max();
  template <class Get>
  static Row Integer(std::string key, Get get, long long lo, long long hi, std::string doc) {
    const std::string range =
        hi == kNoLimit ? ">= " + std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi);
    Row r = Base(std::move(key), "integer", range, std::move(doc), get);
    r.read = [get, lo, hi](const ConfigNode& v, Spec* s) {
      const long long x = v.AsInt();
      if (x < lo || x > hi) {
        v.Fail((hi == kNoLimit ? (lo == 0 ? std::string("must not be negative")
                                          : "must be at least " + std::to_string(lo))
                               : "must be between " + std::to_string(lo) + " and " + std::to_string(hi)) +
               ", got " + v.Quoted());
      }
      get(*s) = static_cast<std::remove_reference_t<decltype(get(*s))>>(x);
    };
    r.show = [get](const Spec& s) { return std::to_string(get(s)); };
    return r;
  }

  template <class Get>
  static Row Number(std::string key, Get get, ParamBound lo, ParamBound hi, std::string doc) {
    Row r = Base(std::move(key), "number", RangeText(lo, hi), std::move(doc), get);
    r.read = [get, lo, hi](const ConfigNode& v, Spec* s) {
      const double x = v.AsDouble();
      const bool low_ok = lo.open ? x > lo.value : x >= lo.value;
      const bool high_ok = hi.open ? x < hi.value : x <= hi.value;
      if (!low_ok || !high_ok) v.Fail(MustBe(lo, hi) + ", got " + v.Quoted());
      get(*s) = x;
    };
    r.show = [get](const Spec& s) { return param_detail::Number(get(s)); };
    return r;
  }

  template <class Get>
  static Row Text(std::string key, Get get, std::string doc) {
    Row r = Base(std::move(key), "text", "", std::move(doc), get);
    r.read = [get](const ConfigNode& v, Spec* s) { get(*s) = v.AsString(); };
    r.show = [get](const Spec& s) { return get(s); };
    return r;
  }

  template <class Get>
  static Row Boolean(std::string key, Get get, std::string doc) {
    Row r = Base(std::move(key), "boolean", "true, false", std::move(doc), get);
    r.read = [get](const ConfigNode& v, Spec* s) { get(*s) = v.AsBool(); };
    r.show = [get](const Spec& s) { return std::string(get(s) ? "true" : "false"); };
    return r;
  }

  // A text member that must be one of CHOICES.
  template <class Get>
  static Row Choice(std::string key, Get get, std::vector<std::string> choices, std::string doc) {
    return Mapped(std::move(key), get, Identity(choices), std::move(doc));
  }

  // A member of any type set by one of a list of names.
  template <class Get, class T>
  static Row Mapped(std::string key, Get get, std::vector<std::pair<std::string, T>> choices, std::string doc) {
    std::string list;
    for (const auto& c : choices) list += (list.empty() ? "" : ", ") + c.first;
    Row r = Base(std::move(key), "choice", list, std::move(doc), get);
    r.read = [get, choices, list](const ConfigNode& v, Spec* s) {
      const std::string name = v.AsString();
      for (const auto& c : choices) {
        if (c.first == name) {
          get(*s) = c.second;
          return;
        }
      }
      v.Fail("'" + v.Quoted() + "' is not one of: " + list);
    };
    r.show = [get, choices](const Spec& s) {
      for (const auto& c : choices) {
        if (c.second == get(s)) return c.first;
      }
      return std::string();
    };
    return r;
  }

  // A nested block read by its own table SUB (kept alive by the caller, e.g. a static).
  template <class Get, class Sub>
  static Row Block(std::string key, Get get, const ParamTable<Sub>& sub, std::string doc) {
    Row r;
    r.key = std::move(key);
    r.type = "block";
    r.range = "see `" + sub.name() + "`";
    r.doc = std::move(doc);
    r.shapes = sub.Shapes();
    const ParamTable<Sub>* table = &sub;
    r.read = [get, table](const ConfigNode& v, Spec* s) { get(*s) = table->Parse(v, get(*s)); };
    r.hash = [get, table](const Spec& s, unsigned artefact, Hasher* h) { table->Hash(get(s), artefact, h); };
    r.show = [](const Spec&) { return std::string(); };
    return r;
  }

  // A row with its own reading (a value with structure of its own), hashing (null: a value no
  // cache key holds) and showing.
  static Row Custom(std::string key, std::string type, std::string range, std::string doc,
                    std::function<void(const ConfigNode&, Spec*)> read,
                    std::function<void(const Spec&, Hasher*)> hash_value, std::function<std::string(const Spec&)> show) {
    Row r;
    r.key = std::move(key);
    r.type = std::move(type);
    r.range = std::move(range);
    r.doc = std::move(doc);
    r.read = std::move(read);
    if (hash_value) r.hash = [hash_value](const Spec& s, unsigned, Hasher* h) { hash_value(s, h); };
    r.show = std::move(show);
    return r;
  }

  // The rows of TABLE, a block of INNER held at GET in SPEC, as rows of SPEC's own block.
  template <class Inner, class Get>
  static std::vector<Row> Lifted(const ParamTable<Inner>& table, Get get) {
    std::vector<Row> rows;
    for (const ParamRow<Inner>& in : table.rows()) {
      Row r;
      r.key = in.key, r.type = in.type, r.range = in.range, r.unit = in.unit, r.doc = in.doc;
      r.shapes = in.shapes, r.sweep = in.sweep, r.example = in.example, r.default_text = in.default_text;
      auto read = in.read;
      auto hash = in.hash;
      auto show = in.show;
      r.read = [get, read](const ConfigNode& v, Spec* s) { read(v, &get(*s)); };
      r.hash = [get, hash](const Spec& s, unsigned a, Hasher* h) { hash(get(s), a, h); };
      r.show = [get, show](const Spec& s) { return show(get(s)); };
      rows.push_back(std::move(r));
    }
    return rows;
  }

 private:
  template <class Get>
  static Row Base(std::string key, std::string type, std::string range, std::string doc, Get get) {
    Row r;
    r.key = std::move(key);
    r.type = std::move(type);
    r.range = std::move(range);
    r.doc = std::move(doc);
    r.hash = [get](const Spec& s, unsigned, Hasher* h) { param_detail::HashValue(get(s), h); };
    return r;
  }
  static std::vector<std::pair<std::string, std::string>> Identity(const std::vector<std::string>& names) {
    std::vector<std::pair<std::string, std::string>> v;
    for (const auto& n : names) v.emplace_back(n, n);
    return v;
  }
  static std::string MustBe(ParamBound lo, ParamBound hi) {
    if (std::isfinite(lo.value) && !std::isfinite(hi.value)) {
      if (lo.value == 0) return lo.open ? "must be positive" : "must not be negative";
      return (lo.open ? "must be greater than " : "must be at least ") + param_detail::Number(lo.value);
    }
    return "must be " + RangeText(lo, hi);
  }
  static std::string RangeText(ParamBound lo, ParamBound hi) {
    const bool has_lo = std::isfinite(lo.value), has_hi = std::isfinite(hi.value);
    if (has_lo && has_hi) {
      return std::string("in ") + (lo.open ? "(" : "[") + param_detail::Number(lo.value) + ", " +
             param_detail::Number(hi.value) + (hi.open ? ")" : "]");
    }
    if (has_lo) return (lo.open ? "> " : ">= ") + param_detail::Number(lo.value);
    if (has_hi) return (hi.open ? "< " : "<= ") + param_detail::Number(hi.value);
    return "any finite";
  }
};

}  // namespace contactlab
