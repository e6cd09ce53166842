#include "fem/edge_stretch.hpp"

#include <algorithm>

namespace corofem {

double largest_edge_stretch(const TetMesh& mesh, const Eigen::VectorXd& du) {
  double largest = 0;
  for (const Tet& t : mesh.tets)
    for (int a = 0; a < 4; ++a)
      for (int b = a + 1; b < 4; ++b) {
        const double change = (du.segment<3>(3 * t[b]) - du.segment<3>(3 * t[a])).norm();
        largest = std::max(largest, change / (mesh.rest[t[b]] - mesh.rest[t[a]]).norm());
      }
  return largest;
}

}  // namespace corofem
