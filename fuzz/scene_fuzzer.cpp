// libFuzzer target: the scene reader (stagger::load_scene) on arbitrary bytes. Every
// input must either load or throw stagger::Error; anything else (a crash, a sanitizer
// report, another exception type escaping) is a finding. See scripts/fuzz.sh.
#include <unistd.h>

#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>

#include "stagger/error.hpp"
#include "stagger/scene.hpp"

namespace {

// Inputs that ask for a legitimately huge mesh (nx = 10^7) only measure the allocator:
// skip any integer or decimal literal above 300 right after a zone-count or refine key.
bool asks_for_a_huge_mesh(const std::string& text) {
  for (const char* key : {"nx", "ny", "n_theta", "n_r", "refine"}) {
    for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
      std::size_t k = at + std::char_traits<char>::length(key);
      while (k < text.size() && (text[k] == ' ' || text[k] == '=' || text[k] == '\t' || text[k] == '"')) ++k;
      const double value = std::strtod(text.c_str() + k, nullptr);
      if (!(value <= 300)) return true;  // also NaN
    }
  }
  return false;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  if (asks_for_a_huge_mesh(text)) return -1;  // not added to the corpus
  static const std::filesystem::path directory = [] {
    auto path = std::filesystem::temp_directory_path() / ("stagger_scene_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(path);
    return path;
  }();
  const std::filesystem::path file = directory / "scene.toml";
  std::ofstream(file, std::ios::binary | std::ios::trunc) << text;
  try {
    const stagger::Scene scene = stagger::load_scene(file.string());
    static_cast<void>(stagger::describe(scene));
  } catch (const stagger::Error&) {
    // A clean, reported error: the expected outcome for most inputs.
  }
  return 0;
}
