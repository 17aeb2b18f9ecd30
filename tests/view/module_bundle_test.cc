// The bundling of the viewer's ES modules into one inline module (src/view/module_bundle.h):
// dependency order, each module once, its exports returned and its imports destructured, and
// the errors that name the module and line of syntax outside the handled subset.
#include "view/module_bundle.h"

#include <gtest/gtest.h>

#include "test_support.h"
#include "util/error.h"
#include "view/viewer_page.h"

namespace contactlab {
namespace {

using testing::ErrorOf;

// Where TEXT starts in BUNDLE, failing the test when it does not.
std::size_t At(const std::string& bundle, const std::string& text) {
  const std::size_t at = bundle.find(text);
  EXPECT_NE(at, std::string::npos) << text << "\nnot in\n" << bundle;
  return at;
}

TEST(ModuleBundle, ModulesRunOnceAfterThoseTheyImport) {
  const std::vector<JsModule> modules = {
      {"v/main.js", "import { b } from './b.js';\nimport { a as first } from './a.js';\nb(first);\n"},
      {"v/b.js", "import { a } from './a.js';\nexport function b(x) { return a + x; }\n"},
      {"v/a.js", "export const a = 1;\nexport class Shape {}\n"},
      {"v/unused.js", "export const u = 0;\n"}};
  const std::string bundle = BundleModules(modules, "v/main.js");
  const std::size_t a = At(bundle, "// --- v/a.js\nconst module_v_a_js = (() => {\n");
  const std::size_t b = At(bundle, "// --- v/b.js\nconst module_v_b_js = (() => {\n");
  const std::size_t main = At(bundle, "// --- v/main.js\nconst module_v_main_js = (() => {\n");
  EXPECT_LT(a, b);
  EXPECT_LT(b, main);
  EXPECT_EQ(bundle.find("// --- v/a.js", a + 1), std::string::npos) << "a.js twice";
  EXPECT_EQ(bundle.find("unused"), std::string::npos) << "a module nothing imports";
  // Exports without `export`, returned; imports as destructurings, `as` renaming.
  At(bundle, "const a = 1;\nclass Shape {}\nreturn {a, Shape};\n})();");
  At(bundle, "const { a } = module_v_a_js;\nfunction b(x) { return a + x; }\nreturn {b};\n})();");
  At(bundle, "const { b } = module_v_b_js;\nconst { a: first } = module_v_a_js;\nb(first);\nreturn {};\n})();");
  EXPECT_EQ(bundle.find("import "), std::string::npos);
  EXPECT_EQ(bundle.find("export "), std::string::npos);
}

TEST(ModuleBundle, SyntaxOutsideTheSubsetIsAnErrorNamingModuleAndLine) {
  const auto error = [](std::string_view source) {
    return ErrorOf([&] { BundleModules({{"v/main.js", "// x\n"}, {"v/m.js", source}}, "v/m.js"); });
  };
  for (const char* bad : {"export let n = 0;", "export default 1;", "export { a };", "import * as x from './main.js';",
                          "import {\n  a } from './main.js';", "import { a } from '../main.js';"}) {
    const std::string e = error(std::string("// first line\n") + bad + "\n");
    EXPECT_NE(e.find("v/m.js:2: an "), std::string::npos) << bad << ": " << e;
  }
  // A module that is not there, and an import cycle.
  std::string e = error("import { a } from './absent.js';\n");
  EXPECT_NE(e.find("v/m.js: imports v/absent.js, which is not among the modules"), std::string::npos) << e;
  e = ErrorOf([] {
    BundleModules({{"v/a.js", "import { b } from './b.js';\nexport const a = 1;\n"},
                   {"v/b.js", "import { a } from './a.js';\nexport const b = 2;\n"}},
                  "v/a.js");
  });
  EXPECT_NE(e.find("import cycle: v/a.js -> v/b.js -> v/a.js"), std::string::npos) << e;
}

// The viewer's own modules bundle, and main.js reaches every one of them (none is dead).
TEST(ModuleBundle, ViewerModulesBundleWhole) {
  std::vector<JsModule> modules;
  for (const std::string& name : ViewerModuleNames()) modules.push_back({name, EmbeddedWebFile(name)});
  ASSERT_GT(modules.size(), 5u);
  const std::string bundle = BundleModules(modules, "viewer/main.js");
  for (const JsModule& m : modules) EXPECT_NE(bundle.find("// --- " + m.name + "\n"), std::string::npos) << m.name;
  EXPECT_LT(bundle.find("// --- viewer/three_global.js"), bundle.find("// --- viewer/util.js"));
  EXPECT_GT(bundle.find("// --- viewer/main.js"), bundle.find("// --- viewer/replay.js"));
}

}  // namespace
}  // namespace contactlab
