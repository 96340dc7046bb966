// stagger-options: the option tables of docs/scenes.md, generated from the library's option
// tables (stagger/option_table.hpp) so that the docs cannot drift from the code.
//
//   stagger-options --check FILE    exit 1 (and say which) if FILE's generated blocks differ
//   stagger-options --update FILE   rewrite FILE's generated blocks in place
//   stagger-options                 print the tables
#include <cstring>
#include <fstream>
#include <iostream>
#include <sstream>
#include <string>

#include "stagger/error.hpp"
#include "stagger/option_table.hpp"
#include "stagger/output.hpp"

namespace {

std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw stagger::Error("stagger-options: cannot read '" + path + "'");
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

template <class Options>
void print(const stagger::OptionTable<Options>& table) {
  std::cout << "### [" << table.section << "] (" << table.struct_name << ")\n" << table.markdown() << "\n";
}

}  // namespace

int main(int argc, char** argv) {
  try {
    if (argc == 1) {
      print(stagger::time_option_table());
      print(stagger::deposit_option_table());
      std::cout << stagger::strength_option_tables_listing();  // one table per strength model
      print(stagger::numerics_option_table());
      print(stagger::ale_option_table());
      print(stagger::output_option_table());
      return 0;
    }
    const bool check = argc == 3 && std::strcmp(argv[1], "--check") == 0;
    const bool update = argc == 3 && std::strcmp(argv[1], "--update") == 0;
    if (!check && !update) {
      std::cerr << "usage: stagger-options [--check FILE | --update FILE]\n";
      return 2;
    }
    const std::string path = argv[2];
    const std::string text = read_text(path);
    std::string generated;
    try {
      generated = stagger::with_generated_option_tables(text);
    } catch (const stagger::Error& failure) {
      throw stagger::Error(path + ": " + failure.what());
    }
    if (generated == text) return 0;
    if (check) {
      std::cerr << "stagger-options: " << path
                << ": the option tables differ from the code; run stagger-options --update " << path << "\n";
      return 1;
    }
    stagger::write_file_atomically(path, generated);
    std::cout << "stagger-options: updated " << path << "\n";
    return 0;
  } catch (const std::exception& failure) {
    std::cerr << "stagger-options: error: " << failure.what() << "\n";
    return 1;
  }
}
