#include "measure/local_strain.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <unordered_map>

namespace grainlab {
namespace {

bool invert(const Matrix3& m, Matrix3& inv) {
  const double det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1]) -
                     m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0]) +
                     m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
  double scale = 0.0;
  for (const auto& row : m)
    for (double v : row) scale = std::max(scale, std::abs(v));
  if (!(std::abs(det) > 1e-9 * scale * scale * scale)) return false;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const int i1 = (j + 1) % 3, i2 = (j + 2) % 3, j1 = (i + 1) % 3, j2 = (i + 2) % 3;
      inv[i][j] = (m[i1][j1] * m[i2][j2] - m[i1][j2] * m[i2][j1]) / det;
    }
  return true;
}

}  // namespace

std::vector<Matrix3> local_displacement_gradient(const std::vector<Vec3>& reference,
                                                 const std::vector<Vec3>& current, double radius) {
  const size_t n = reference.size();
  // A hash grid of cells `radius` wide over the reference positions.
  auto key = [&](const Vec3& x, int dx, int dy, int dz) {
    const long i = static_cast<long>(std::floor(x.x / radius)) + dx;
    const long j = static_cast<long>(std::floor(x.y / radius)) + dy;
    const long k = static_cast<long>(std::floor(x.z / radius)) + dz;
    // Exact for |cell index| < 2^20 (a million cells per axis).
    constexpr long offset = 1L << 20;
    return ((i + offset) << 42) | ((j + offset) << 21) | (k + offset);
  };
  std::unordered_map<long, std::vector<uint32_t>> cells;
  for (size_t i = 0; i < n; ++i) cells[key(reference[i], 0, 0, 0)].push_back(i);
  std::vector<Matrix3> out(n);
  const double r2 = radius * radius;
#pragma omp parallel for schedule(dynamic, 256)
  for (long i = 0; i < static_cast<long>(n); ++i) {
    Matrix3 a{}, b{};  // sum dX dX^T, sum du dX^T
    int neighbours = 0;
    const Vec3 ui = current[i] - reference[i];
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy)
        for (int dz = -1; dz <= 1; ++dz) {
          const auto found = cells.find(key(reference[i], dx, dy, dz));
          if (found == cells.end()) continue;
          for (uint32_t j : found->second) {
            if (j == static_cast<uint32_t>(i)) continue;
            const Vec3 dX = reference[j] - reference[i];
            if (norm2(dX) > r2) continue;
            const Vec3 du = (current[j] - reference[j]) - ui;
            for (int p = 0; p < 3; ++p)
              for (int q = 0; q < 3; ++q) a[p][q] += dX[p] * dX[q], b[p][q] += du[p] * dX[q];
            ++neighbours;
          }
        }
    Matrix3 inv, l{};
    if (neighbours < 4 || !invert(a, inv)) {
      for (auto& row : l) row.fill(NAN);
    } else {
      for (int p = 0; p < 3; ++p)
        for (int q = 0; q < 3; ++q)
          for (int k = 0; k < 3; ++k) l[p][q] += b[p][k] * inv[k][q];
    }
    out[i] = l;
  }
  return out;
}

double max_shear_strain(const Matrix3& g, int a, int b) {
  const double eaa = g[a][a], ebb = g[b][b], eab = 0.5 * (g[a][b] + g[b][a]);
  return std::sqrt((eaa - ebb) * (eaa - ebb) + 4.0 * eab * eab);
}

}  // namespace grainlab
