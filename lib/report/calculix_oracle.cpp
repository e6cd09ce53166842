#include "report/calculix_oracle.hpp"

#include <cstdlib>
#include <fstream>
#include <map>
#include <sstream>

#include "core/atomic_file.hpp"
#include "core/errors.hpp"

namespace corofem {

bool calculix_available() {
  return std::system("command -v ccx > /dev/null 2>&1") == 0;
}

std::string calculix_deck(const FeProblem& problem, bool nlgeom, int increments) {
  // ccx reads numeric fields of at most 20 characters: 14 significant digits fit with sign and
  // exponent (and are far below what the comparisons resolve).
  std::ostringstream deck;
  deck.precision(14);
  deck << "** corofem: " << problem.mesh.num_vertices() << " nodes, " << problem.mesh.num_tets()
       << " C3D4 elements, " << (nlgeom ? "NLGEOM" : "linear") << "\n*NODE, NSET=NALL\n";
  for (int v = 0; v < problem.mesh.num_vertices(); ++v) {
    const Vec3& x = problem.mesh.rest[v];
    deck << v + 1 << ", " << x.x() << ", " << x.y() << ", " << x.z() << "\n";
  }
  // One element set and material per distinct (E, nu, rho).
  std::map<std::tuple<double, double, double>, std::vector<int>> groups;
  for (int e = 0; e < problem.mesh.num_tets(); ++e) {
    const Material& m = problem.materials[e];
    groups[{m.young, m.poisson, m.density}].push_back(e);
  }
  int group = 0;
  for (const auto& [material, elements] : groups) {
    ++group;
    deck << "*ELEMENT, TYPE=C3D4, ELSET=E" << group << "\n";
    for (int e : elements) {
      const Tet& t = problem.mesh.tets[e];
      deck << e + 1 << ", " << t[0] + 1 << ", " << t[1] + 1 << ", " << t[2] + 1 << ", " << t[3] + 1
           << "\n";
    }
    deck << "*MATERIAL, NAME=M" << group << "\n*ELASTIC\n"
         << std::get<0>(material) << ", " << std::get<1>(material) << "\n";
    if (std::get<2>(material) > 0) deck << "*DENSITY\n" << std::get<2>(material) << "\n";
    deck << "*SOLID SECTION, ELSET=E" << group << ", MATERIAL=M" << group << "\n";
  }
  deck << "*BOUNDARY\n";
  for (int i = 0; i < problem.num_dofs(); ++i)
    if (problem.dirichlet.fixed[i])
      deck << i / 3 + 1 << ", " << i % 3 + 1 << ", " << i % 3 + 1 << ", "
           << problem.dirichlet.value[i] << "\n";
  if (nlgeom) {
    const double step = 1.0 / increments;
    deck << "*STEP, NLGEOM, INC=1000\n*STATIC\n"
         << step << ", 1.0, " << step * 1e-4 << ", " << step << "\n";
  } else {
    deck << "*STEP\n*STATIC\n";
  }
  deck << "*CLOAD\n";
  for (int i = 0; i < problem.num_dofs(); ++i)
    if (!problem.dirichlet.fixed[i] && problem.external_force[i] != 0)
      deck << i / 3 + 1 << ", " << i % 3 + 1 << ", " << problem.external_force[i] << "\n";
  deck << "*NODE PRINT, NSET=NALL\nU\n*END STEP\n";
  return deck.str();
}

namespace {

std::string tail_of(const std::filesystem::path& file, std::size_t chars) {
  std::ifstream in(file);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  return text.size() > chars ? text.substr(text.size() - chars) : text;
}

}  // namespace

Eigen::VectorXd run_calculix(const FeProblem& problem, bool nlgeom,
                             const std::filesystem::path& work_dir, const std::string& job,
                             int increments) {
  // Absolute: the command changes into it and then writes the log by its path (`corofem report
  // --out out/report`, ci/report's default, made every job fail with an empty log).
  const std::filesystem::path dir = std::filesystem::absolute(work_dir);
  std::filesystem::create_directories(dir);
  const std::string deck = calculix_deck(problem, nlgeom, increments);
  write_file_atomically(dir / (job + ".inp"), [&](std::ostream& out) { out << deck; });
  const std::filesystem::path log = dir / (job + ".log");
  const std::string command = "cd '" + dir.string() + "' && OMP_NUM_THREADS=1 ccx -i '" + job +
                              "' > '" + log.string() + "' 2>&1";
  const int status = std::system(command.c_str());
  const auto fail = [&](const std::string& what) -> NumericalFault {
    return NumericalFault("CalculiX job '" + job + "' " + what +
                          "; the end of its log: " + tail_of(log, 400));
  };
  if (status != 0) throw fail("exited with status " + std::to_string(status));
  // The .dat holds one displacement block per printed increment: keep the last.
  std::ifstream dat(dir / (job + ".dat"));
  std::string line;
  Eigen::VectorXd u =
      Eigen::VectorXd::Constant(problem.num_dofs(), std::numeric_limits<double>::quiet_NaN());
  bool in_block = false;
  while (std::getline(dat, line)) {
    if (line.find("displacements (vx,vy,vz)") != std::string::npos) {
      in_block = true;
      u.setConstant(std::numeric_limits<double>::quiet_NaN());
      continue;
    }
    if (!in_block) continue;
    std::istringstream row(line);
    long node = 0;
    double ux = 0, uy = 0, uz = 0;
    if (!(row >> node >> ux >> uy >> uz)) {
      if (line.find_first_not_of(" \t\r") != std::string::npos) in_block = false;
      continue;
    }
    if (node < 1 || node > problem.mesh.num_vertices())
      throw fail("printed node " + std::to_string(node));
    u.segment<3>(3 * (node - 1)) = Vec3(ux, uy, uz);
  }
  if (!u.allFinite()) throw fail("printed no displacements for some nodes (did it converge?)");
  return u;
}

}  // namespace corofem
