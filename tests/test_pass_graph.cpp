// The pass graph written in renderer.hpp's header comment stays true: every example's frame,
// as built, and variants that switch on what no example does (the GPU jump flooding, shadows,
// per-frame clip-surface sprites, ghost lines), run exactly the passes it lists in its order;
// and every line of it is run by one of them, so it lists no pass that does not exist.
#include <gtest/gtest.h>

#include <filesystem>
#include <memory>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>

#include "cutaway/cutters/adaptive.hpp"
#include "cutaway/cutters/clip_surfaces.hpp"
#include "cutaway/render/renderer.hpp"
#include "cutaway/render/techniques.hpp"
#include "gl_test_context.hpp"

using namespace cutaway;

namespace {

// The graph's lines: renderer.hpp's comment lines between the blank comment lines that follow
// the sentence naming this test.
std::vector<std::string> documentedGraph() {
  std::ifstream in(std::string(CUTAWAY_SOURCE_DIR) + "/include/cutaway/render/renderer.hpp");
  std::vector<std::string> lines;
  int blanks = -1;  // blank comment lines seen since the sentence
  for (std::string line; std::getline(in, line) && blanks < 2;) {
    if (line.find("tests/test_pass_graph.cpp") != std::string::npos) blanks = 0;
    else if (blanks >= 0 && line == "//") ++blanks;
    else if (blanks == 1 && line.rfind("//   ", 0) == 0) lines.push_back(line.substr(5));
  }
  return lines;
}

// One graph line as a regular expression over "name " tokens: [a b] is optional, (a | b) a
// choice, "X/N..." one or more passes X/<number>.
std::string lineRegex(const std::string& line) {
  std::string out;
  std::istringstream words(line);
  for (std::string w; words >> w;) {
    std::string open, close;
    while (!w.empty() && (w.front() == '[' || w.front() == '(')) {
      open += "(?:";
      w.erase(0, 1);
    }
    while (!w.empty() && (w.back() == ']' || w.back() == ')')) {
      close += w.back() == ']' ? ")?" : ")";
      w.pop_back();
    }
    if (w == "|") {
      out += "|";
      continue;
    }
    std::string token;
    if (w.size() > 5 && w.compare(w.size() - 5, 5, "/N...") == 0)
      token = "(?:" + w.substr(0, w.size() - 5) + "/[0-9]+ )+";
    else
      token = w + " ";
    out += open + token + close;
  }
  return out;
}

std::string joined(const std::vector<std::string>& names) {
  std::string s;
  for (const auto& n : names) s += n + " ";
  return s;
}

struct Variant {
  std::string file;
  std::vector<std::pair<std::string, std::string>> options;  // setOption(path, value)
  std::shared_ptr<const Scene> scene;  // the file, loaded once for all its variants
};

std::string variantName(const Variant& v) {
  std::string name = v.file;
  for (const auto& [path, value] : v.options) name += " " + path + "=" + value;
  return name;
}

// Every example, and each with the GPU jump flooding, shadows, per-frame sprites and ghost
// lines where it has the cutter they belong to.
std::vector<Variant> variants() {
  std::vector<Variant> out;
  for (const auto& e : std::filesystem::directory_iterator(std::string(CUTAWAY_SOURCE_DIR) +
                                                           "/examples")) {
    if (e.path().extension() != ".json") continue;
    const std::string file = e.path().filename().string();
    const auto scene = std::make_shared<const Scene>(loadScene(e.path()));
    out.push_back({file, {}, scene});
    if (scene->cutters.find<AdaptiveCutawayOptions>())
      out.push_back({file,
                     {{"cutters.adaptive.compute", "gpu"}, {"cutters.adaptive.ghostLines", "true"}},
                     scene});
    if (scene->cutters.find<ClipSurfaceOptions>())
      out.push_back({file, {{"cutters.clipSurfaces.parity", "perFrame"}}, scene});
    if (!scene->networks.empty()) out.push_back({file, {{"style.shadows", "true"}}, scene});
  }
  std::sort(out.begin(), out.end(),
            [](const Variant& a, const Variant& b) { return variantName(a) < variantName(b); });
  return out;
}

std::vector<std::string> passesOf(const Variant& v) {
  Scene scene = *v.scene;
  scene.width = 64, scene.height = 48;
  for (const auto& [path, value] : v.options) setOption(scene, path, value);
  const Renderer renderer(scene, test::glContext().info());
  return renderer.frame().passNames();
}

TEST(PassGraph, IsDocumentedInRendererHpp) {
  const auto graph = documentedGraph();
  ASSERT_GE(graph.size(), 5u) << "renderer.hpp's pass graph not found";
  EXPECT_EQ(graph.front().substr(0, 12), "[cutawaySeed");
  EXPECT_EQ(graph.back(), "[translucentComposite]");
}

// Every variant matches the whole graph; every line runs in at least one.
TEST(PassGraph, EveryExampleRunsTheDocumentedPassesInOrder) {
  const auto graph = documentedGraph();
  std::string whole;
  for (const auto& line : graph) whole += "(" + lineRegex(line) + ")";
  const std::regex pattern(whole);
  std::set<std::size_t> exercised;
  for (const Variant& v : variants()) {
    SCOPED_TRACE(variantName(v));
    const std::string names = joined(passesOf(v));
    std::smatch m;
    ASSERT_TRUE(std::regex_match(names, m, pattern)) << "passes: " << names;
    for (std::size_t i = 0; i < graph.size(); ++i)
      if (m.length(int(i) + 1) > 0) exercised.insert(i);
  }
  for (std::size_t i = 0; i < graph.size(); ++i)
    EXPECT_TRUE(exercised.count(i)) << "no example runs the documented line: " << graph[i];
}

// The matcher itself: it refuses what the graph forbids.
TEST(PassGraph, TheMatcherRefusesOtherOrders) {
  const std::regex line(lineRegex("[a (b | c d/N...) e]"));
  EXPECT_TRUE(std::regex_match("", line));
  EXPECT_TRUE(std::regex_match("a b e ", line));
  EXPECT_TRUE(std::regex_match("a c d/4 d/2 d/1 e ", line));
  EXPECT_FALSE(std::regex_match("a c e ", line));
  EXPECT_FALSE(std::regex_match("a e ", line));
  EXPECT_FALSE(std::regex_match("b a e ", line));
}

}  // namespace
