#include "design/catalog.hpp"

namespace sw {

const std::vector<CatalogDrive>& catalog_drives() {
  // shared/reference/catalog_torsional_stiffness.md: CSF/CSG component sets, ratio >= 80; rated torque at ratio 100
  // (CSG). Sizes 25 and 32: pitch diameter and T1, T2 only (size 25 also its rated torque); no stiffness.
  static const std::vector<CatalogDrive> table = {
      {14, 35.6e-3, 2.0, 6.9, 0.47e4, 0.61e4, 0.71e4, 10.0},
      {17, 43.2e-3, 3.9, 12.0, 1.0e4, 1.4e4, 1.6e4, 31.0},
      {20, 50.8e-3, 7.0, 25.0, 1.6e4, 2.5e4, 2.9e4, 52.0},
      {25, 63.5e-3, 14.0, 48.0, 0.0, 0.0, 0.0, 87.0},
      {32, 81.3e-3, 29.0, 108.0, 0.0, 0.0, 0.0, 0.0},
  };
  return table;
}

const CatalogDrive* catalog_drive(int size) {
  for (const auto& d : catalog_drives())
    if (d.size == size) return &d;
  return nullptr;
}

std::optional<CatalogDrive> catalog_stiffness(int size, int ratio) {
  const CatalogDrive* d = catalog_drive(size);
  if (!d || !d->has_stiffness()) return std::nullopt;
  if (ratio >= 80) return *d;
  // shared/reference/catalog_torsional_stiffness.md, "Other ratios": (size, ratio, K1, K2, K3; 0 not listed).
  struct Row {
    int size, ratio;
    double k1, k2, k3;
  };
  static const Row rows[] = {{14, 30, 0.19e4, 0.24e4, 0.34e4}, {17, 30, 0.34e4, 0.44e4, 0.67e4},
                             {20, 30, 0.57e4, 0.71e4, 1.1e4},  {14, 50, 0.34e4, 0.47e4, 0},
                             {17, 50, 0.81e4, 1.1e4, 0},       {20, 50, 1.3e4, 1.8e4, 0}};
  for (const Row& r : rows)
    if (r.size == size && r.ratio == ratio) {
      CatalogDrive row = *d;
      row.k1_Nm_per_rad = r.k1;
      row.k2_Nm_per_rad = r.k2;
      row.k3_Nm_per_rad = r.k3;
      return row;
    }
  return std::nullopt;
}

const CatalogLimits* catalog_limits(int size) {
  // shared/reference/catalog_strength_life_losses.md, as read. Ratcheting: (ratio, CSF, CSG).
  static const std::vector<CatalogLimits> table = {
      {14, {{30, 59, 0}, {50, 88, 110}, {80, 110, 140}, {100, 84, 100}}, 190, 260, 10, 36, 14, 58, 7000, 10000,
       0.67, 35e-3, 21e-3, 2.21},
      {17, {{30, 100, 0}, {50, 150, 190}, {80, 200, 260}, {100, 160, 200}, {120, 120, 150}}, 330, 500, 31, 70, 51,
       109, 7000, 10000, 0.77, 51e-3, 29e-3, 3.06},
      {20, {{30, 170, 0}, {50, 220, 280}, {80, 350, 450}, {100, 260, 330}, {120, 240, 310}, {160, 220, 280}}, 560,
       800, 52, 107, 64, 191, 7000, 10000, 0.77, 105e-3, 37e-3, 3.89},
  };
  for (const auto& d : table)
    if (d.size == size) return &d;
  return nullptr;
}

std::string catalog_sizes_text() {
  std::string s;
  for (const auto& d : catalog_drives()) s += (s.empty() ? "" : ", ") + std::to_string(d.size);
  return s;
}

}  // namespace sw
