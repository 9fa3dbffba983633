#include "measure/shear_band.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace grainlab {

StrainMap strain_map(const std::vector<Vec3>& x, const std::vector<double>& v, int a, int b,
                     double cell) {
  StrainMap m;
  double lo_a = INFINITY, hi_a = -INFINITY, lo_b = INFINITY, hi_b = -INFINITY;
  for (const Vec3& p : x) {
    lo_a = std::min(lo_a, p[a]), hi_a = std::max(hi_a, p[a]);
    lo_b = std::min(lo_b, p[b]), hi_b = std::max(hi_b, p[b]);
  }
  m.cell = cell, m.low_a = lo_a, m.low_b = lo_b;
  m.n_a = std::max(1, static_cast<int>(std::ceil((hi_a - lo_a) / cell)));
  m.n_b = std::max(1, static_cast<int>(std::ceil((hi_b - lo_b) / cell)));
  std::vector<double> sum(static_cast<size_t>(m.n_a) * m.n_b, 0.0);
  std::vector<long> count(sum.size(), 0);
  for (size_t i = 0; i < x.size(); ++i) {
    if (std::isnan(v[i])) continue;
    const int ka = std::min(m.n_a - 1, static_cast<int>((x[i][a] - lo_a) / cell));
    const int kb = std::min(m.n_b - 1, static_cast<int>((x[i][b] - lo_b) / cell));
    sum[static_cast<size_t>(kb) * m.n_a + ka] += v[i];
    ++count[static_cast<size_t>(kb) * m.n_a + ka];
  }
  // Cells cut by the specimen's edge hold few particles, and the particles along an edge have
  // one-sided neighbourhoods (a noisy fit): both are left out, as a DIC field's border is.
  std::vector<long> filled;
  for (long c : count)
    if (c > 0) filled.push_back(c);
  std::nth_element(filled.begin(), filled.begin() + filled.size() / 2, filled.end());
  const long typical = filled.empty() ? 1 : filled[filled.size() / 2];
  std::vector<double> value(sum.size(), NAN);
  for (size_t k = 0; k < sum.size(); ++k)
    if (2 * count[k] >= typical && count[k] > 0) value[k] = sum[k] / count[k];
  m.value = value;
  for (int kb = 0; kb < m.n_b; ++kb)
    for (int ka = 0; ka < m.n_a; ++ka) {
      auto empty = [&](int a2, int b2) {
        return a2 < 0 || b2 < 0 || a2 >= m.n_a || b2 >= m.n_b ||
               std::isnan(value[static_cast<size_t>(b2) * m.n_a + a2]);
      };
      if (empty(ka - 1, kb) || empty(ka + 1, kb) || empty(ka, kb - 1) || empty(ka, kb + 1))
        m.value[static_cast<size_t>(kb) * m.n_a + ka] = NAN;
    }
  return m;
}

namespace {

// The map's value at a point (m, relative to the map's low corner); NaN outside.
double sample(const StrainMap& m, double pa, double pb) {
  const int ka = static_cast<int>(std::floor(pa / m.cell)),
            kb = static_cast<int>(std::floor(pb / m.cell));
  if (ka < 0 || kb < 0 || ka >= m.n_a || kb >= m.n_b) return NAN;
  return m.at(ka, kb);
}

double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::nth_element(v.begin(), v.begin() + v.size() / 2, v.end());
  return v[v.size() / 2];
}

}  // namespace

ShearBand find_shear_band(const StrainMap& m) {
  ShearBand best;
  const double size_a = m.n_a * m.cell, size_b = m.n_b * m.cell;
  const double step = 0.5 * m.cell, reach = std::hypot(size_a, size_b);
  const int min_samples = static_cast<int>(0.6 * std::min(size_a, size_b) / step);
  double best_mean = -INFINITY;
  for (double deg = 15.0; deg <= 165.0 + 1e-9; deg += 0.25) {
    const double th = deg * std::numbers::pi / 180.0;
    const double ta = std::cos(th), tb = std::sin(th), na = -tb, nb = ta;
    for (double c = -reach; c <= reach; c += step) {
      double sum = 0.0;
      int n = 0;
      for (double s = -reach; s <= reach; s += step) {
        const double v = sample(m, c * na + s * ta, c * nb + s * tb);
        if (!std::isnan(v)) sum += v, ++n;
      }
      if (n >= min_samples && n > 0 && sum / n > best_mean) {
        best_mean = sum / n;
        best.found = true;
        best.direction_deg = deg;
        best.offset = c;
      }
    }
  }
  if (!best.found) return best;
  best.inclination_deg = best.direction_deg <= 90 ? best.direction_deg : 180 - best.direction_deg;
  // The profile across the band: every cell's value against its distance from the line.
  const double th = best.direction_deg * std::numbers::pi / 180.0;
  const double na = -std::sin(th), nb = std::cos(th);
  const double half = 0.5 * std::min(size_a, size_b);
  const int bins = static_cast<int>(std::ceil(half / step));
  std::vector<double> sum(2 * bins + 1, 0.0);
  std::vector<long> count(sum.size(), 0);
  std::vector<double> all;
  for (int kb = 0; kb < m.n_b; ++kb)
    for (int ka = 0; ka < m.n_a; ++ka) {
      const double v = m.at(ka, kb);
      if (std::isnan(v)) continue;
      all.push_back(v);
      const double d = ((ka + 0.5) * m.cell) * na + ((kb + 0.5) * m.cell) * nb - best.offset;
      const long k = std::lround(d / step) + bins;
      if (k >= 0 && k < static_cast<long>(sum.size())) sum[k] += v, ++count[k];
    }
  best.background = median(all);
  for (size_t k = 0; k < sum.size(); ++k)
    if (count[k]) {
      best.profile_distance.push_back((static_cast<long>(k) - bins) * step);
      best.profile_value.push_back(sum[k] / count[k]);
    }
  // Peak near the line, then the half-height crossings on both sides.
  const std::vector<double>& d = best.profile_distance;
  const std::vector<double>& v = best.profile_value;
  size_t top = 0;
  best.peak = -INFINITY;
  for (size_t k = 0; k < d.size(); ++k)
    if (std::abs(d[k]) <= 2.0 * m.cell && v[k] > best.peak) best.peak = v[k], top = k;
  const double level = best.background + 0.5 * (best.peak - best.background);
  auto crossing = [&](int dir) {
    for (long k = static_cast<long>(top); k + dir >= 0 && k + dir < static_cast<long>(d.size());
         k += dir)
      if (v[k + dir] < level)  // interpolate between k and k + dir
        return d[k] + (d[k + dir] - d[k]) * (v[k] - level) / (v[k] - v[k + dir]);
    return d[dir < 0 ? 0 : d.size() - 1];
  };
  best.thickness = crossing(1) - crossing(-1);
  return best;
}

}  // namespace grainlab
