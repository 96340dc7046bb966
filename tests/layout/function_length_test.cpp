// No function in lib/ is longer than 200 lines (docs/architecture.md, "Layers and doors"): a
// long function is a room of several concepts; split it into named stages. The count is of the
// lines between a function body's opening and closing brace, found by brace depth outside
// comments, strings and character literals (a namespace, class, struct, enum or union body is
// a scope, not a function).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace {

namespace fs = std::filesystem;

constexpr int kMaxFunctionLines = 200;

// The text with comments, string and character literals blanked (newlines kept).
std::string code_only(const std::string& text) {
  std::string out = text;
  enum { code, line_comment, block_comment, string_literal, char_literal } mode = code;
  for (std::size_t i = 0; i < out.size(); ++i) {
    const char ch = text[i], next = i + 1 < text.size() ? text[i + 1] : '\0';
    switch (mode) {
      case code:
        if (ch == '/' && next == '/')
          mode = line_comment, out[i] = ' ';
        else if (ch == '/' && next == '*')
          mode = block_comment, out[i] = ' ';
        else if (ch == '"')
          mode = string_literal;
        else if (ch == '\'' && !(i > 0 && std::isxdigit(static_cast<unsigned char>(text[i - 1]))))
          mode = char_literal;
        break;
      case line_comment:
        if (ch == '\n')
          mode = code;
        else
          out[i] = ' ';
        break;
      case block_comment:
        if (ch == '*' && next == '/')
          out[i] = out[i + 1] = ' ', ++i, mode = code;
        else if (ch != '\n')
          out[i] = ' ';
        break;
      case string_literal:
      case char_literal:
        if (ch == '\\')
          out[i] = ' ', out[i + 1] = ' ', ++i;
        else if ((mode == string_literal && ch == '"') || (mode == char_literal && ch == '\''))
          mode = code;
        else if (ch != '\n')
          out[i] = ' ';
        break;
    }
  }
  return out;
}

struct LongFunction {
  std::string where;
  int lines = 0;
};

std::vector<LongFunction> long_functions(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream buffer;
  buffer << in.rdbuf();
  const std::string code = code_only(buffer.str());
  // The text before an opening brace back to the previous ';', '{' or '}' says what it opens.
  const std::regex scope(R"((^|\s)(namespace|class|struct|enum|union|extern\s*$)\b)");
  struct Open {
    bool function;
    int line;
  };
  std::vector<Open> stack;
  std::vector<LongFunction> found;
  int line = 1;
  std::size_t head = 0;  // where the text before the next brace starts
  for (std::size_t i = 0; i < code.size(); ++i) {
    const char ch = code[i];
    if (ch == '\n') ++line;
    if (ch == ';') head = i + 1;
    if (ch == '{') {
      const std::string before = code.substr(head, i - head);
      const bool inside_function = std::any_of(stack.begin(), stack.end(), [](const Open& o) { return o.function; });
      const bool opens_scope = std::regex_search(before, scope) && before.find('(') == std::string::npos;
      const bool is_function = !inside_function && !opens_scope && before.find(')') != std::string::npos;
      stack.push_back({is_function, line});
      head = i + 1;
    } else if (ch == '}') {
      if (!stack.empty()) {
        const Open open = stack.back();
        stack.pop_back();
        if (open.function && line - open.line > kMaxFunctionLines)
          found.push_back({file.string() + ":" + std::to_string(open.line), line - open.line});
      }
      head = i + 1;
    }
  }
  return found;
}

TEST(FunctionLength, NoFunctionInTheLibraryIsOver200Lines) {
  int files = 0;
  for (const char* folder : {"lib", "meshgen"}) {
    for (const auto& entry : fs::recursive_directory_iterator(fs::path(STAGGER_SOURCE_DIR) / folder)) {
      const std::string ext = entry.path().extension().string();
      if (!entry.is_regular_file() || (ext != ".cpp" && ext != ".hpp")) continue;
      ++files;
      for (const LongFunction& f : long_functions(entry.path()))
        ADD_FAILURE() << f.where << ": a function of " << f.lines << " lines (at most " << kMaxFunctionLines
                      << "): split it into named stages";
    }
  }
  EXPECT_GT(files, 50);
}

TEST(FunctionLength, TheCounterSeesALongFunctionAndSkipsScopes) {
  const fs::path file = fs::temp_directory_path() / "stagger_function_length_probe.cpp";
  {
    std::ofstream out(file);
    out << "namespace a {\nstruct B {\n  int f() {\n";
    for (int i = 0; i < kMaxFunctionLines + 5; ++i) out << "    x(\"}{\"); // }\n";
    out << "  }\n};\nint g() { return 1; }\n}  // namespace a\n";
  }
  const std::vector<LongFunction> found = long_functions(file);
  fs::remove(file);
  ASSERT_EQ(found.size(), 1u);
  EXPECT_EQ(found[0].lines, kMaxFunctionLines + 6);
}

}  // namespace
