#include "core/particles.hpp"

namespace grainlab {
namespace {
template <class T>
void apply(std::vector<T>& field, const std::vector<uint32_t>& order, std::vector<T>& scratch) {
  scratch.resize(field.size());
  const long n = static_cast<long>(order.size());
#pragma omp parallel for schedule(static) if (n > parallel_threshold)
  for (long k = 0; k < n; ++k) scratch[k] = field[order[k]];
  field.swap(scratch);
}
}  // namespace

void ParticleStore::permute(const std::vector<uint32_t>& order) {
  std::vector<Vec3> v3;
  std::vector<double> d;
  apply(position, order, v3);
  apply(velocity, order, v3);
  apply(angular_velocity, order, v3);
  apply(force, order, v3);
  apply(torque, order, v3);
  apply(rotation, order, v3);
  apply(initial_position, order, v3);
  apply(external_force, order, v3);
  apply(radius, order, d);
  apply(inverse_mass, order, d);
  apply(inverse_inertia, order, d);
  std::vector<int32_t> i32;
  apply(material, order, i32);
  std::vector<uint32_t> u32;
  apply(id, order, u32);
}

}  // namespace grainlab
