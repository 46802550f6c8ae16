#include "trace/photon_map.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>

#include <nanoflann.hpp>

#include "base/check.h"

namespace bounce {
namespace {

// nanoflann's view of the photons: points in 3 dimensions.
struct photon_cloud {
  const std::vector<photon>* photons = nullptr;
  std::size_t kdtree_get_point_count() const { return photons->size(); }
  double kdtree_get_pt(std::uint32_t i, std::size_t dim) const { return (*photons)[i].position[int(dim)]; }
  template <typename box>
  bool kdtree_get_bbox(box&) const {
    return false;  // nanoflann computes it
  }
};

using kd_tree = nanoflann::KDTreeSingleIndexAdaptor<nanoflann::L2_Simple_Adaptor<double, photon_cloud, double>,
                                                    photon_cloud, 3, std::uint32_t>;

// A nanoflann result set: the k nearest photons within a radius that pass
// the normal and side tests. Filtering while searching (not afterwards)
// keeps photons on the far side of a thin wall, which can be the nearest
// of all, from taking the k places and shrinking the radius.
class eligible_nearest {
 public:
  eligible_nearest(const std::vector<photon>& photons, const vec3& point, const vec3& normal, std::size_t k,
                   double radius2)
      : photons_(photons), point_(point), normal_(normal), k_(k), limit_(radius2) {
    found_.reserve(k + 1);
  }

  // nanoflann offers points closer than this.
  double worstDist() const { return full() ? found_.back().first : limit_; }
  bool full() const { return found_.size() == k_; }

  bool addPoint(double distance2, std::uint32_t index) {
    const photon& p = photons_[index];
    if (glm::dot(p.normal, normal_) <= photon_normal_agreement || glm::dot(p.incoming, normal_) <= 0.0) return true;
    // A disc, not a sphere: photons far off the tangent plane lie on
    // another surface facing the same way (a floor under a table top).
    if (std::abs(glm::dot(p.position - point_, normal_)) > photon_plane_slope * std::sqrt(distance2)) return true;
    const std::pair<double, std::uint32_t> entry(distance2, index);
    found_.insert(std::upper_bound(found_.begin(), found_.end(), entry), entry);
    if (found_.size() > k_) found_.pop_back();
    return true;  // keep searching
  }

  const std::vector<std::pair<double, std::uint32_t>>& found() const { return found_; }

 private:
  const std::vector<photon>& photons_;
  vec3 point_, normal_;
  std::size_t k_;
  double limit_;
  std::vector<std::pair<double, std::uint32_t>> found_;  // (distance^2, index), nearest first
};

}  // namespace

struct photon_map::tree {
  std::vector<photon> photons;
  photon_cloud cloud;
  std::unique_ptr<kd_tree> index;  // null when there are no photons
  rgb total{0.0};
};

photon_map::photon_map() : photon_map(std::vector<photon>{}) {}

photon_map::photon_map(std::vector<photon> photons) : tree_(std::make_unique<tree>()) {
  BOUNCE_CHECK(photons.size() < std::numeric_limits<std::uint32_t>::max());
  tree_->photons = std::move(photons);
  tree_->cloud.photons = &tree_->photons;
  for (const photon& p : tree_->photons) tree_->total += p.power;
  if (!tree_->photons.empty())
    tree_->index = std::make_unique<kd_tree>(3, tree_->cloud, nanoflann::KDTreeSingleIndexAdaptorParams(10));
}

photon_map::~photon_map() = default;
photon_map::photon_map(photon_map&&) noexcept = default;
photon_map& photon_map::operator=(photon_map&&) noexcept = default;

const std::vector<photon>& photon_map::photons() const {
  static const std::vector<photon> none;  // a moved-from map
  return tree_ ? tree_->photons : none;
}

rgb photon_map::total_power() const {
  return tree_ ? tree_->total : rgb(0.0);
}

photon_estimate photon_map::estimate(const vec3& point, const vec3& normal, double radius, int max_photons,
                                     photon_filter filter) const {
  BOUNCE_CHECK(radius > 0.0 && max_photons > 0);
  photon_estimate out;
  out.radius = radius;
  if (!tree_ || !tree_->index) return out;
  // nanoflann offers points strictly closer than the worst distance: one
  // ulp more keeps photons at exactly `radius`.
  eligible_nearest result(tree_->photons, point, normal, std::size_t(max_photons),
                          std::nextafter(radius * radius, std::numeric_limits<double>::infinity()));
  const double query[3] = {point.x, point.y, point.z};
  tree_->index->findNeighbors(result, query, nanoflann::SearchParams());
  const auto& found = result.found();
  if (found.empty()) return out;
  if (result.full() && found.back().first > 0.0) out.radius = std::min(radius, std::sqrt(found.back().first));
  const double r = out.radius;
  rgb sum(0.0);
  for (const auto& [distance2, index] : found) {
    const double weight = filter == photon_filter::cone ? 1.0 - std::sqrt(distance2) / (cone_filter_k * r) : 1.0;
    sum += weight * tree_->photons[index].power;
  }
  const double normalisation = filter == photon_filter::cone ? 1.0 - 2.0 / (3.0 * cone_filter_k) : 1.0;
  out.irradiance = sum / (normalisation * std::numbers::pi * r * r);
  out.photons = int(found.size());
  return out;
}

}  // namespace bounce
