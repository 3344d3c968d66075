#include "io/inp.hpp"

#include <cstdio>
#include <fstream>
#include <string>

#include "common/error.hpp"
#include "io/atomic_file.hpp"

namespace sw {

namespace fs = std::filesystem;

void write_inp_deck(const fs::path& final_path, const Case& c, const TetMesh& mesh, const std::vector<bool>& fixed_node,
                    const Eigen::VectorXd& load, const std::string& origin) {
  write_via_temp(final_path, [&](const fs::path& path) {
    std::FILE* f = std::fopen(path.c_str(), "w");
    if (!f) throw InputError("cannot write " + path.string());
    static char buffer[1 << 20];
    std::setvbuf(f, buffer, _IOFBF, sizeof buffer);
    std::fprintf(f, "** strainwave %s: %s (SI units: m, N, Pa)\n*HEADING\nstrainwave %s\n", origin.c_str(),
                 c.path.c_str(), c.stem.c_str());
    std::fprintf(f, "*NODE, NSET=NALL\n");
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
      std::fprintf(f, "%zu,%.13e,%.13e,%.13e\n", i + 1, mesh.nodes(i, 0), mesh.nodes(i, 1), mesh.nodes(i, 2));
    std::fprintf(f, "*ELEMENT, TYPE=C3D10, ELSET=EALL\n");
    for (std::size_t e = 0; e < mesh.tets.size(); ++e) {
      std::fprintf(f, "%zu", e + 1);
      for (int v : mesh.tets[e]) std::fprintf(f, ",%d", v + 1);
      std::fprintf(f, "\n");
    }
    std::fprintf(f, "*NSET, NSET=NFIX\n");
    int on_line = 0;
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i)
      if (fixed_node[i]) {
        std::fprintf(f, on_line ? ",%zu" : "%zu", i + 1);
        if (++on_line == 12) {
          std::fprintf(f, "\n");
          on_line = 0;
        }
      }
    if (on_line) std::fprintf(f, "\n");
    std::fprintf(f, "*BOUNDARY\nNFIX,1,3\n");
    std::fprintf(f, "*MATERIAL, NAME=MAT\n*ELASTIC\n%.13e,%.13e\n", c.material.youngs_modulus_Pa,
                 c.material.poisson_ratio);
    std::fprintf(f, "*SOLID SECTION, ELSET=EALL, MATERIAL=MAT\n");
    std::fprintf(f, "*STEP\n*STATIC\n*CLOAD\n");
    for (std::size_t i = 0; i < mesh.n_nodes(); ++i) {
      if (fixed_node[i]) continue;  // a load on a fixed dof goes straight into the reaction, in both codes
      for (int d = 0; d < 3; ++d)
        if (load[3 * i + d] != 0.0) std::fprintf(f, "%zu,%d,%.13e\n", i + 1, d + 1, load[3 * i + d]);
    }
    std::fprintf(f, "*NODE FILE\nU\n*END STEP\n");
    if (std::fclose(f) != 0) throw InputError("cannot write " + path.string());
  });
}


Eigen::VectorXd read_frd_displacements(const fs::path& path, std::size_t n_nodes) {
  std::ifstream in(path);
  if (!in) throw InputError("cannot read " + path.string());
  Eigen::VectorXd u;
  std::vector<bool> seen;
  std::string line;
  bool in_disp = false, found = false;
  while (std::getline(in, line)) {
    if (line.rfind(" -4", 0) == 0) {
      in_disp = line.compare(3, 6, "  DISP") == 0;
      if (in_disp) {
        u = Eigen::VectorXd::Zero(3 * n_nodes);
        seen.assign(n_nodes, false);
        found = true;
      }
      continue;
    }
    if (!in_disp) continue;
    if (line.rfind(" -3", 0) == 0) {
      in_disp = false;
      continue;
    }
    if (line.rfind(" -1", 0) != 0) continue;
    // " -1" + node id + 3 x E12.5: the id's width is what is left (I10 in ccx 2.x, I5 in the short format).
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ')) line.pop_back();
    const std::size_t id_width = line.size() - 3 - 36;
    if (line.size() < 3 + 36 + 1 || id_width > 10) throw InputError(path.string() + ": bad DISP line \"" + line + "\"");
    const long id = std::stol(line.substr(3, id_width));
    if (id < 1 || static_cast<std::size_t>(id) > n_nodes)
      throw InputError(path.string() + ": node " + std::to_string(id) + " out of range");
    for (int d = 0; d < 3; ++d) u[3 * (id - 1) + d] = std::stod(line.substr(3 + id_width + 12 * d, 12));
    seen[id - 1] = true;
  }
  if (!found) throw InputError(path.string() + ": no DISP block (did ccx finish?)");
  for (std::size_t i = 0; i < n_nodes; ++i)
    if (!seen[i]) throw InputError(path.string() + ": no displacement for node " + std::to_string(i + 1));
  return u;
}

}  // namespace sw
