// Stand-ins for the mesher and the plane-stress solver until their branches are merged: every
// call says that finite elements are not available in this build, so `--method fe` ends in a
// clear error instead of a link failure. Removed from src/CMakeLists.txt when mesh.cpp and
// plane_stress.cpp arrive.
#include <stdexcept>

#include "nbar/stress/mesh.hpp"
#include "nbar/stress/plane_stress.hpp"

namespace nbar::fe {

namespace {
[[noreturn]] void unavailable() {
  throw std::invalid_argument(
      "finite elements are not available in this build (no mesher and plane-stress solver): use the beam method");
}
}  // namespace

TriMesh mesh_region(const Region&, const MeshOptions&) { unavailable(); }
MeshQuality mesh_quality(const TriMesh&) { return {}; }

struct PlateModel::Impl {
  TriMesh mesh;
  ElasticMaterial material;
};
PlateModel::PlateModel(TriMesh, ElasticMaterial) { unavailable(); }
PlateModel::~PlateModel() = default;
PlateModel::PlateModel(PlateModel&&) noexcept = default;
PlateModel& PlateModel::operator=(PlateModel&&) noexcept = default;
StressField PlateModel::solve(const LoadCase&) const { unavailable(); }
const TriMesh& PlateModel::mesh() const { return impl_->mesh; }
const ElasticMaterial& PlateModel::material() const { return impl_->material; }

}  // namespace nbar::fe
