// Blocks of parameters held by their tables: what lets one holder (a scene's `model:` section,
// a body's per-model blocks) carry the parameters of models it does not know. Each block is
// the struct its table (util/param_table.h) fills, stored under that table; a reader asks for
// it by the same table and gets its own struct back, or the struct's defaults when the block
// was never given.
//
//   const ParamTable<ProxySpec>& ProxyParams();          // a model's own table
//   ParamTable<ParamValues> rows = ErasedTable(ProxyParams());  // what a scene reads it through
//   const ProxySpec& proxy = values.Get(ProxyParams());   // what the model reads
#pragma once

#include <any>
#include <map>
#include <type_traits>
#include <utility>

#include "util/param_table.h"

namespace contactlab {

class ParamValues {
 public:
  // The block of TABLE: as read, or Spec's defaults when it was not.
  template <class Spec>
  const Spec& Get(const ParamTable<Spec>& table) const {
    const auto it = blocks_.find(&table);
    if (it == blocks_.end()) {
      static const Spec defaults{};
      return defaults;
    }
    return *std::any_cast<Spec>(&it->second);
  }
  // The block of TABLE to change, made from Spec's defaults the first time.
  template <class Spec>
  Spec& Mutable(const ParamTable<Spec>& table) {
    return *std::any_cast<Spec>(&blocks_.try_emplace(&table, Spec{}).first->second);
  }

 private:
  std::map<const void*, std::any> blocks_;  // by the address of the block's table
};

// TABLE's rows (and its cross-checks) as rows of a ParamValues that holds TABLE's block:
// parsing, range checks, showing and hashing as TABLE's own. TABLE must outlive the result.
template <class Spec>
ParamTable<ParamValues> ErasedTable(const ParamTable<Spec>& table) {
  const ParamTable<Spec>* t = &table;
  const auto block = [t](auto& values) -> auto& {
    if constexpr (std::is_const_v<std::remove_reference_t<decltype(values)>>) {
      return values.Get(*t);
    } else {
      return values.Mutable(*t);
    }
  };
  typename ParamTable<ParamValues>::Check check;
  if (table.check()) {
    check = [t, block](const ConfigNode& node, ParamValues* values) { t->check()(node, &block(*values)); };
  }
  return ParamTable<ParamValues>(table.name(), table.doc(), ParamRows<ParamValues>::Lifted(table, block),
                                 std::move(check));
}

}  // namespace contactlab
