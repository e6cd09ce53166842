#include "io/matrix_market.hpp"

#include <fstream>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace corofem {

void write_matrix_market(const std::filesystem::path& file, const Eigen::SparseMatrix<double>& m) {
  write_file_atomically(file, [&](std::ostream& out) {
    out << "%%MatrixMarket matrix coordinate real general\n"
        << m.rows() << ' ' << m.cols() << ' ' << m.nonZeros() << '\n';
    out.precision(17);
    for (int c = 0; c < m.outerSize(); ++c)
      for (Eigen::SparseMatrix<double>::InnerIterator it(m, c); it; ++it)
        out << it.row() + 1 << ' ' << it.col() + 1 << ' ' << it.value() << '\n';
  });
}

Eigen::SparseMatrix<double> read_matrix_market(const std::filesystem::path& file) {
  std::ifstream in(file);
  if (!in) throw InputError("cannot read Matrix Market file '" + file.string() + "'");
  std::string line;
  std::getline(in, line);
  if (line.rfind("%%MatrixMarket matrix coordinate real general", 0) != 0)
    throw InputError("'" + file.string() + "' is not a coordinate real general Matrix Market file");
  while (std::getline(in, line) && !line.empty() && line[0] == '%') {
  }
  long rows = 0, cols = 0, entries = 0;
  std::istringstream(line) >> rows >> cols >> entries;
  if (rows <= 0 || cols <= 0 || entries < 0)
    throw InputError("bad size line in '" + file.string() + "'");
  std::vector<Eigen::Triplet<double>> triplets;
  for (long n = 0; n < entries; ++n) {
    long r = 0, c = 0;
    double v = 0;
    if (!(in >> r >> c >> v) || r < 1 || r > rows || c < 1 || c > cols)
      throw InputError("bad entry " + std::to_string(n + 1) + " in '" + file.string() + "'");
    triplets.emplace_back(r - 1, c - 1, v);
  }
  Eigen::SparseMatrix<double> m(rows, cols);
  m.setFromTriplets(triplets.begin(), triplets.end());
  return m;
}

}  // namespace corofem
