#include "io/vtu_writer.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <ostream>

#include "core/atomic_file.hpp"

namespace corofem {

double rotation_angle(const Mat3& q) {
  const Mat3 proper = q.determinant() < 0 ? Mat3(-q) : q;
  return std::acos(std::clamp((proper.trace() - 1) / 2, -1.0, 1.0));
}

void write_vtu(const std::filesystem::path& file, const TetMesh& mesh,
               const Eigen::VectorXd& displacement, const std::vector<Mat3>& rotations) {
  write_file_atomically(file, [&](std::ostream& out) {
    out.precision(17);
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"UnstructuredGrid\" version=\"0.1\">\n"
        << "<UnstructuredGrid><Piece NumberOfPoints=\"" << mesh.num_vertices()
        << "\" NumberOfCells=\"" << mesh.num_tets() << "\">\n";
    out << "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">\n";
    for (const Vec3& p : mesh.rest) out << p.x() << ' ' << p.y() << ' ' << p.z() << '\n';
    out << "</DataArray></Points>\n<Cells>\n"
        << "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n";
    for (const Tet& t : mesh.tets) out << t[0] << ' ' << t[1] << ' ' << t[2] << ' ' << t[3] << '\n';
    out << "</DataArray>\n<DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n";
    for (int e = 1; e <= mesh.num_tets(); ++e) out << 4 * e << '\n';
    out << "</DataArray>\n<DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n";
    for (int e = 0; e < mesh.num_tets(); ++e) out << "10\n";  // VTK_TETRA
    out << "</DataArray>\n</Cells>\n<PointData Vectors=\"displacement\">\n"
        << "<DataArray type=\"Float64\" Name=\"displacement\" NumberOfComponents=\"3\" "
           "format=\"ascii\">\n";
    for (int v = 0; v < mesh.num_vertices(); ++v)
      out << displacement[3 * v] << ' ' << displacement[3 * v + 1] << ' ' << displacement[3 * v + 2]
          << '\n';
    out << "</DataArray>\n</PointData>\n<CellData Scalars=\"rotation_angle\">\n"
        << "<DataArray type=\"Float64\" Name=\"rotation_angle\" format=\"ascii\">\n";
    for (const Mat3& q : rotations) out << rotation_angle(q) << '\n';
    out << "</DataArray>\n</CellData>\n</Piece></UnstructuredGrid>\n</VTKFile>\n";
  });
}

void write_pvtu(const std::filesystem::path& file, const std::vector<std::string>& pieces) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "<?xml version=\"1.0\"?>\n<VTKFile type=\"PUnstructuredGrid\" version=\"0.1\">\n"
        << "<PUnstructuredGrid GhostLevel=\"0\">\n"
        << "<PPoints><PDataArray type=\"Float64\" NumberOfComponents=\"3\"/></PPoints>\n"
        << "<PPointData Vectors=\"displacement\"><PDataArray type=\"Float64\" "
           "Name=\"displacement\" NumberOfComponents=\"3\"/></PPointData>\n"
        << "<PCellData Scalars=\"rotation_angle\"><PDataArray type=\"Float64\" "
           "Name=\"rotation_angle\"/></PCellData>\n";
    for (const std::string& piece : pieces) out << "<Piece Source=\"" << piece << "\"/>\n";
    out << "</PUnstructuredGrid>\n</VTKFile>\n";
  });
}

}  // namespace corofem
