// Every field of ContactStats by name: what reports all of them (`contactlab contact --json`,
// the Python module's query and query_many) reads this list, so a new field is one row here.
// cycles.csv has its own column table (experiment/studies/contact/result_csv.cc), with formats
// per column.
#pragma once

#include <array>

#include "contact/contact_model.h"

namespace contactlab {

struct ContactStatField {
  const char* name;
  double (*value)(const ContactStats&);  // exact for the counts (below 2^53)
  bool count;                            // an integer
};

inline constexpr std::array<ContactStatField, 11> kContactStatFields{{
    {"points_in_contact", [](const ContactStats& s) { return double(s.points_in_contact); }, true},
    {"nodes_visited", [](const ContactStats& s) { return double(s.nodes_visited); }, true},
    {"level_rendered", [](const ContactStats& s) { return double(s.level_rendered); }, true},
    {"nodes_skipped_coherence", [](const ContactStats& s) { return double(s.nodes_skipped_coherence); }, true},
    {"max_penetration", [](const ContactStats& s) { return s.max_penetration; }, false},
    {"stiffness_scale", [](const ContactStats& s) { return s.stiffness_scale; }, false},
    {"contact_area", [](const ContactStats& s) { return s.contact_area; }, false},
    {"patches", [](const ContactStats& s) { return double(s.patches); }, true},
    {"faults", [](const ContactStats& s) { return double(s.faults); }, true},
    {"degraded", [](const ContactStats& s) { return double(s.degraded); }, true},
    {"contacts_sliding", [](const ContactStats& s) { return double(s.contacts_sliding); }, true},
}};

}  // namespace contactlab
