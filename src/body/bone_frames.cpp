#include "body/bone_frames.hpp"

#include <Eigen/Geometry>
#include <cmath>

namespace body {

namespace {

bool sided(const std::string& name) {
  return name.rfind("left", 0) == 0 || name.rfind("right", 0) == 0 || name.rfind("l_", 0) == 0 ||
         name.rfind("r_", 0) == 0;
}

}  // namespace

std::vector<int> bone_targets(const std::vector<int>& parents,
                              const std::vector<std::string>& names) {
  const std::size_t J = parents.size();
  std::vector<std::vector<int>> children(J);
  for (std::size_t j = 0; j < J; ++j) {
    if (parents[j] >= 0)
      children[static_cast<std::size_t>(parents[j])].push_back(static_cast<int>(j));
  }
  std::vector<int> descendants(J, 0);
  for (std::size_t j = 0; j < J; ++j) {
    for (int k = parents[j]; k >= 0; k = parents[static_cast<std::size_t>(k)]) {
      ++descendants[static_cast<std::size_t>(k)];
    }
  }
  auto name_of = [&](int j) {
    return static_cast<std::size_t>(j) < names.size() ? names[static_cast<std::size_t>(j)]
                                                      : std::string();
  };
  std::vector<int> target(J, -1);
  for (std::size_t j = 0; j < J; ++j) {
    int best = -1, best_score = -1;
    for (int c : children[j]) {
      const std::string n = name_of(c);
      const int score =
          (!n.empty() && !sided(n) ? 4 : 0) + (n.find("middle") != std::string::npos ? 2 : 0);
      const int tie = descendants[static_cast<std::size_t>(c)];
      if (best < 0 || score > best_score ||
          (score == best_score && tie > descendants[static_cast<std::size_t>(best)])) {
        best = c;
        best_score = score;
      }
    }
    target[j] = best;
  }
  return target;
}

std::vector<Eigen::Matrix3f> bone_frames(const std::vector<int>& parents,
                                         const std::vector<std::string>& names,
                                         const Vertices& joints) {
  const std::size_t J = parents.size();
  const std::vector<int> target = bone_targets(parents, names);
  std::vector<Eigen::Vector3f> dir(J, Eigen::Vector3f::UnitY());
  std::vector<char> known(J, 0);
  for (std::size_t j = 0; j < J; ++j) {
    if (target[j] < 0) continue;
    const Eigen::Vector3f d =
        (joints.row(target[j]) - joints.row(static_cast<Eigen::Index>(j))).transpose();
    if (d.norm() > 1e-6f) {
      dir[j] = d.normalized();
      known[j] = 1;
    }
  }
  // Leaves (and zero-length bones) continue the nearest ancestor's bone.
  for (std::size_t j = 0; j < J; ++j) {
    if (known[j]) continue;
    for (int k = parents[j]; k >= 0; k = parents[static_cast<std::size_t>(k)]) {
      if (known[static_cast<std::size_t>(k)]) {
        dir[j] = dir[static_cast<std::size_t>(k)];
        break;
      }
    }
  }
  std::vector<Eigen::Matrix3f> frames(J);
  for (std::size_t j = 0; j < J; ++j) {
    const Eigen::Vector3f y = dir[j];
    Eigen::Matrix3f r;
    if (std::abs(y.z()) < 0.9f) {
      const Eigen::Vector3f z = (Eigen::Vector3f::UnitZ() - y.z() * y).normalized();
      r.col(0) = y.cross(z);
      r.col(1) = y;
      r.col(2) = z;
    } else {
      const Eigen::Vector3f x = (Eigen::Vector3f::UnitX() - y.x() * y).normalized();
      r.col(0) = x;
      r.col(1) = y;
      r.col(2) = x.cross(y);
    }
    frames[j] = r;
  }
  return frames;
}

}  // namespace body
