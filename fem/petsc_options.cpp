// PETSc's options on the strainwave command line (fem/petsc_solver.hpp), in every build: without PETSc they are
// refused by name rather than misread as strainwave's own.
#include <cctype>
#include <string>
#include <vector>

#include "fem/petsc_solver.hpp"

namespace sw::parallel {

std::vector<std::string> take_petsc_options(std::vector<std::string>& args) {
  auto is_option = [](const std::string& a) {
    return a.size() >= 3 && a[0] == '-' && a[1] != '-' && std::isalpha(static_cast<unsigned char>(a[1]));
  };
  std::vector<std::string> options, kept;
  for (std::size_t i = 0; i < args.size(); ++i) {
    if (i == 0 || !is_option(args[i])) {
      kept.push_back(args[i]);
      continue;
    }
    options.push_back(args[i]);
    if (i + 1 < args.size() && !is_option(args[i + 1]) && args[i + 1].rfind("--", 0) != 0) options.push_back(args[++i]);
  }
  args = kept;
  return options;
}
}  // namespace sw::parallel
