// The viewer's ES modules (src/view/web/viewer/) as one script, for a page that must work
// opened from a file: a browser loads no module file from file:// (its origin is opaque), so
// `contactlab view` inlines the modules into the page it writes, bundled by this step, while a
// session's live view serves them as files.
//
// The bundle keeps each module's scope: every module becomes a function, run once in
// dependency order, that returns its exports, and each import becomes a destructuring of the
// exports of a module run before it. The modules keep to the subset of the syntax this needs,
// each statement on one line starting at column 0:
//   import { a, b as c } from './name.js';     (a file of the same folder; no cycles)
//   export function NAME / export async function NAME / export class NAME / export const NAME
// (no `export let`: an exported binding never changes, so a copy of it is the binding).
#pragma once

#include <string>
#include <string_view>
#include <vector>

namespace contactlab {

struct JsModule {
  std::string name;         // its path among the others, e.g. "viewer/main.js"
  std::string_view source;  // its text
};

// The modules ENTRY imports, directly or not, each once and after those it imports, then
// ENTRY, as the text of one <script type="module">. Throws Error naming the module and line of
// an import or export outside the subset above, an import of a module not in MODULES, or the
// modules of an import cycle.
std::string BundleModules(const std::vector<JsModule>& modules, std::string_view entry);

}  // namespace contactlab
