#include "mesh/box_mesh.hpp"

#include "core/errors.hpp"

namespace corofem {

TetMesh make_box_mesh(const Vec3& size, const std::array<int, 3>& cells) {
  const int nx = cells[0], ny = cells[1], nz = cells[2];
  if (nx < 1 || ny < 1 || nz < 1) throw InputError("box mesh needs at least one cell per axis");
  if (!(size.minCoeff() > 0) || !size.allFinite())
    throw InputError("box mesh needs finite positive extents");
  TetMesh mesh;
  mesh.source = "box";
  auto index = [&](int i, int j, int k) { return i + (nx + 1) * (j + (ny + 1) * k); };
  for (int k = 0; k <= nz; ++k)
    for (int j = 0; j <= ny; ++j)
      for (int i = 0; i <= nx; ++i)
        mesh.rest.emplace_back(size.x() * i / nx, size.y() * j / ny, size.z() * k / nz);
  // The six monotone lattice paths from corner 000 to 111; odd permutations are mirrored and get
  // their last two vertices swapped so that every tet is positively oriented.
  const int paths[6][3] = {{0, 1, 2}, {1, 2, 0}, {2, 0, 1}, {0, 2, 1}, {2, 1, 0}, {1, 0, 2}};
  for (int k = 0; k < nz; ++k)
    for (int j = 0; j < ny; ++j)
      for (int i = 0; i < nx; ++i)
        for (int p = 0; p < 6; ++p) {
          int corner[3] = {0, 0, 0};
          Tet t;
          t[0] = index(i, j, k);
          for (int s = 0; s < 3; ++s) {
            corner[paths[p][s]] = 1;
            t[s + 1] = index(i + corner[0], j + corner[1], k + corner[2]);
          }
          if (p >= 3) std::swap(t[2], t[3]);
          mesh.tets.push_back(t);
        }
  validate_mesh(mesh);
  return mesh;
}

}  // namespace corofem
