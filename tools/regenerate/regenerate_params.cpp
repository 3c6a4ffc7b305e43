// robodds_regenerate_params REPO_ROOT: rewrites every registered component's
// config/<name>.params.yaml from its parameter table (scripts/regenerate_params.sh runs it).
#include <cstdio>
#include <exception>
#include <filesystem>
#include <fstream>

#include "runtime/component/registry.hpp"
#include "tools/robodds/params_files.hpp"

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: %s REPO_ROOT\n", argv[0]);
    return 2;
  }
  try {
    robodds::ComponentRegistry registry;
    robodds::register_builtin_components(registry);
    for (const robodds::ComponentType& type : registry.types()) {
      const std::string path = std::string(argv[1]) + "/" + type.defaults_file;
      // A new component has no config/ folder yet (docs/writing-a-component.md's first build).
      std::error_code ignored;
      std::filesystem::create_directories(std::filesystem::path(path).parent_path(), ignored);
      std::ofstream out(path, std::ios::binary | std::ios::trunc);
      out << robodds::expected_params_file(type);
      out.close();
      if (!out) {
        std::fprintf(stderr, "robodds_regenerate_params: cannot write %s\n", path.c_str());
        return 1;
      }
      std::printf("wrote %s\n", type.defaults_file.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "robodds_regenerate_params: %s\n", e.what());
    return 1;
  }
  return 0;
}
