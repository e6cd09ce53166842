#include "mesh/msh_precheck.hpp"

#include <cstdint>
#include <cstring>
#include <fstream>
#include <sstream>
#include <string>
#include <unordered_set>
#include <vector>

#include "core/errors.hpp"
#include "mesh/msh_binary_check.hpp"

namespace corofem {
namespace {

constexpr unsigned long long kMaxTag = 1'000'000'000ULL;

[[noreturn]] void reject(const std::filesystem::path& file, const std::string& what) {
  throw InputError("mesh file '" + file.string() + "' is malformed: " + what);
}

/// Offset just after "\n$Name\n" (or at the start of the file), or npos.
std::size_t section_start(const std::string& bytes, const std::string& name) {
  const std::string key = "$" + name + "\n";
  if (bytes.compare(0, key.size(), key) == 0) return key.size();
  const std::size_t at = bytes.find("\n" + key);
  return at == std::string::npos ? at : at + key.size() + 1;
}

/// n whitespace-separated unsigned integers as text at `offset`.
std::vector<unsigned long long> ascii_counts(const std::string& bytes, std::size_t offset, int n,
                                             const std::filesystem::path& file,
                                             const std::string& section) {
  std::istringstream in(bytes.substr(offset, 256));
  std::vector<unsigned long long> v(n);
  for (auto& x : v) {
    long long signed_value = 0;
    if (!(in >> signed_value) || signed_value < 0) reject(file, "bad count in $" + section);
    x = static_cast<unsigned long long>(signed_value);
  }
  return v;
}

/// Whitespace-separated tokens of the section body from `offset` up to "$End<name>".
std::vector<std::string> section_lines(const std::string& bytes, std::size_t offset,
                                       const std::string& name, const std::filesystem::path& file) {
  const std::size_t end = bytes.find("$End" + name, offset);
  if (end == std::string::npos) reject(file, "$" + name + " has no $End" + name);
  std::vector<std::string> lines;
  std::istringstream in(bytes.substr(offset, end - offset));
  for (std::string line; std::getline(in, line);)
    if (line.find_first_not_of(" \t\r") != std::string::npos) lines.push_back(line);
  return lines;
}

std::vector<long long> integers(const std::string& line, const std::filesystem::path& file,
                                const std::string& section) {
  std::istringstream in(line);
  std::vector<long long> v;
  std::string token;
  while (in >> token) {
    std::size_t used = 0;
    long long x = 0;
    try {
      x = std::stoll(token, &used);
    } catch (...) {
      reject(file, "non-integer '" + token + "' in $" + section);
    }
    if (used != token.size()) reject(file, "non-integer '" + token + "' in $" + section);
    v.push_back(x);
  }
  return v;
}

/// ASCII files: every node reference of every element names a node of $Nodes (gmsh 4.8 keeps
/// a null vertex for a missing one and crashes later, in getElements).
/// The node tags an ASCII file's $Nodes lists (checked on the way: counts, tags, coordinates).
std::unordered_set<long long> ascii_node_tags(const std::string& bytes, int major,
                                              const std::filesystem::path& file) {
  std::unordered_set<long long> tags;
  const std::size_t nodes_at = section_start(bytes, "Nodes");
  if (nodes_at != std::string::npos) {
    const auto node_lines = section_lines(bytes, nodes_at, "Nodes", file);
    if (node_lines.empty()) reject(file, "empty $Nodes");
    const auto head = integers(node_lines[0], file, "Nodes");
    std::size_t row = 1;
    if (major == 2) {
      if (head.size() != 1 || head[0] < 0 ||
          static_cast<std::size_t>(head[0]) != node_lines.size() - 1)
        reject(file, "$Nodes declares " + node_lines[0] + " nodes but lists " +
                         std::to_string(node_lines.size() - 1));
      for (; row < node_lines.size(); ++row) {
        std::istringstream in(node_lines[row]);
        long long tag = 0;
        double x = 0, y = 0, z = 0;
        if (!(in >> tag >> x >> y >> z) || tag <= 0)
          reject(file, "bad node line in $Nodes: '" + node_lines[row] + "'");
        tags.insert(tag);
      }
    } else {
      if (head.size() != 4) reject(file, "bad $Nodes header");
      long long listed = 0;
      while (row < node_lines.size()) {
        const auto block = integers(node_lines[row++], file, "Nodes");
        if (block.size() != 4 || block[3] < 0) reject(file, "bad entity block header in $Nodes");
        const long long n = block[3];
        if (row + 2 * static_cast<std::size_t>(n) > node_lines.size())
          reject(file, "truncated $Nodes");
        for (long long k = 0; k < n; ++k) {
          const auto tag = integers(node_lines[row++], file, "Nodes");
          if (tag.size() != 1 || tag[0] < head[2] || tag[0] > head[3] || tag[0] <= 0)
            reject(file, "node tag outside the declared range in $Nodes");
          tags.insert(tag[0]);
        }
        for (long long k = 0; k < n; ++k) {
          std::istringstream in(node_lines[row++]);
          double x = 0, y = 0, z = 0;
          if (!(in >> x >> y >> z)) reject(file, "bad coordinates in $Nodes");
        }
        listed += n;
      }
      if (listed != head[1])
        reject(file, "$Nodes declares " + std::to_string(head[1]) + " nodes but lists " +
                         std::to_string(listed));
    }
  }
  return tags;
}

/// Each element of an ASCII file's $Elements refers to nodes in `tags`; counts and tags checked.
void check_ascii_elements(const std::string& bytes, int major, const std::filesystem::path& file,
                          const std::unordered_set<long long>& tags) {
  const std::size_t elements_at = section_start(bytes, "Elements");
  if (elements_at == std::string::npos) return;
  const auto element_lines = section_lines(bytes, elements_at, "Elements", file);
  if (element_lines.empty()) reject(file, "empty $Elements");
  const auto head = integers(element_lines[0], file, "Elements");
  auto check_nodes = [&](const std::vector<long long>& v, std::size_t first) {
    if (first >= v.size()) reject(file, "an element of $Elements has no nodes");
    for (std::size_t i = first; i < v.size(); ++i)
      if (!tags.count(v[i]))
        reject(file, "element " + std::to_string(v[0]) + " refers to node " + std::to_string(v[i]) +
                         ", which $Nodes does not define");
  };
  std::size_t row = 1;
  if (major == 2) {
    if (head.size() != 1 || head[0] < 0 ||
        static_cast<std::size_t>(head[0]) != element_lines.size() - 1)
      reject(file, "$Elements declares " + element_lines[0] + " elements but lists " +
                       std::to_string(element_lines.size() - 1));
    for (; row < element_lines.size(); ++row) {
      const auto v = integers(element_lines[row], file, "Elements");
      if (v.size() < 3 || v[2] < 0) reject(file, "bad element line in $Elements");
      check_nodes(v, 3 + static_cast<std::size_t>(v[2]));
    }
  } else {
    if (head.size() != 4) reject(file, "bad $Elements header");
    long long listed = 0;
    while (row < element_lines.size()) {
      const auto block = integers(element_lines[row++], file, "Elements");
      if (block.size() != 4 || block[3] < 0) reject(file, "bad entity block header in $Elements");
      if (row + static_cast<std::size_t>(block[3]) > element_lines.size())
        reject(file, "truncated $Elements");
      for (long long k = 0; k < block[3]; ++k) {
        const auto v = integers(element_lines[row++], file, "Elements");
        if (v.empty() || v[0] < head[2] || v[0] > head[3] || v[0] <= 0)
          reject(file, "element tag outside the declared range in $Elements");
        check_nodes(v, 1);
      }
      listed += block[3];
    }
    if (listed != head[1])
      reject(file, "$Elements declares " + std::to_string(head[1]) + " elements but lists " +
                       std::to_string(listed));
  }
}

void check_ascii_references(const std::string& bytes, int major,
                            const std::filesystem::path& file) {
  // Each section is checked whenever it is present: gmsh parses whatever it finds.
  check_ascii_elements(bytes, major, file, ascii_node_tags(bytes, major, file));
}

/// ASCII files: $PhysicalNames lists as many names as it declares, each well formed.
void check_ascii_physical_names(const std::string& bytes, const std::filesystem::path& file) {
  const std::size_t at = section_start(bytes, "PhysicalNames");
  if (at == std::string::npos) return;
  const auto lines = section_lines(bytes, at, "PhysicalNames", file);
  if (lines.empty()) reject(file, "empty $PhysicalNames");
  const auto head = integers(lines[0], file, "PhysicalNames");
  if (head.size() != 1 || head[0] < 0 || static_cast<std::size_t>(head[0]) != lines.size() - 1)
    reject(file, "$PhysicalNames declares " + lines[0] + " names but lists " +
                     std::to_string(lines.size() - 1));
  for (std::size_t i = 1; i < lines.size(); ++i) check_physical_name_line(lines[i], file);
}

/// ASCII files: every "$" line is a known section header. gmsh matches section names by prefix,
/// so "$Nodes1" is read as $Nodes by gmsh but skipped by the checks above; a fuzzed file built
/// that way corrupted gmsh's heap.
void check_section_names(const std::string& bytes, const std::filesystem::path& file) {
  static const std::unordered_set<std::string> known = {"MeshFormat",
                                                        "PhysicalNames",
                                                        "Entities",
                                                        "PartitionedEntities",
                                                        "Nodes",
                                                        "Elements",
                                                        "Periodic",
                                                        "GhostElements",
                                                        "Parametrizations",
                                                        "NodeData",
                                                        "ElementData",
                                                        "ElementNodeData",
                                                        "InterpolationScheme",
                                                        "Comments"};
  std::istringstream in(bytes);
  for (std::string line; std::getline(in, line);) {
    if (line.empty() || line[0] != '$') continue;
    std::string name = line.substr(1);
    while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
    if (name.rfind("End", 0) == 0) name = name.substr(3);
    if (!known.count(name)) reject(file, "unknown section header '" + line.substr(0, 40) + "'");
  }
}

}  // namespace

void precheck_msh(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  const unsigned long long size = bytes.size();
  const std::size_t format = section_start(bytes, "MeshFormat");
  if (format != std::strlen("$MeshFormat\n")) reject(file, "it does not start with $MeshFormat");
  std::istringstream line(bytes.substr(format, 64));
  double version = 0;
  int type = -1, data_size = 0;
  if (!(line >> version >> type >> data_size)) reject(file, "unreadable $MeshFormat line");
  // Range first: converting an out-of-range double to int is undefined (UBSan found 4.2e33 here).
  const int major = version >= 2 && version < 5 ? static_cast<int>(version) : 0;
  if ((major != 2 && major != 4) || (type != 0 && type != 1) || data_size != 8)
    reject(file, "unsupported $MeshFormat '" +
                     bytes.substr(format, bytes.find('\n', format) - format) +
                     "' (need version 2.x or 4.x, type 0 or 1, data size 8)");
  if (type == 1) {
    check_binary_msh(bytes, version, file);
    return;
  }
  struct Section {
    const char* name;
    int v4_counts;  // numbers in the v4 header (v2 and $PhysicalNames: 1)
    bool has_tag_range;
  };
  const Section sections[] = {{"Entities", 4, false},
                              {"Nodes", 4, true},
                              {"Elements", 4, true},
                              {"PhysicalNames", 1, false}};
  for (const Section& s : sections) {
    const std::size_t at = section_start(bytes, s.name);
    if (at == std::string::npos) continue;
    const int n = major == 4 ? s.v4_counts : (std::string(s.name) == "Entities" ? 0 : 1);
    if (n == 0) continue;
    const auto counts = ascii_counts(bytes, at, n, file, s.name);
    for (std::size_t i = 0; i < counts.size(); ++i)
      if (!(s.has_tag_range && major == 4 && i >= 2) && counts[i] > size)
        reject(file, "$" + std::string(s.name) + " declares " + std::to_string(counts[i]) +
                         " items in a file of " + std::to_string(size) + " bytes");
    if (s.has_tag_range && major == 4 && counts[1] > 0 &&
        (counts[3] > kMaxTag || counts[2] > counts[3]))
      reject(file, "$" + std::string(s.name) + " has tag range [" + std::to_string(counts[2]) +
                       ", " + std::to_string(counts[3]) + "] (tags above 1e9 are not accepted)");
  }
  check_section_names(bytes, file);
  check_ascii_physical_names(bytes, file);
  check_ascii_references(bytes, major, file);
}

void check_physical_name_line(const std::string& line, const std::filesystem::path& file) {
  std::istringstream in(line);
  long long dim = -1, tag = 0;
  std::string rest;
  const bool parsed = static_cast<bool>(in >> dim >> tag) && std::getline(in, rest);
  const std::size_t open = rest.find_first_not_of(" \t");
  std::string name = open == std::string::npos ? "" : rest.substr(open);
  while (!name.empty() && (name.back() == '\r' || name.back() == ' ')) name.pop_back();
  if (!parsed || dim < 0 || dim > 3 || tag <= 0 || tag > 2147483647LL || name.size() < 2 ||
      name.front() != '"' || name.back() != '"')
    reject(file, "bad $PhysicalNames line '" + line.substr(0, 60) +
                     "' (need: dimension 0-3, tag > 0, \"name\")");
}

void precheck_stl(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  char header[84] = {};
  in.read(header, sizeof header);
  const auto got = in.gcount();
  if (got >= 5 && std::string(header, 5) == "solid") return;  // ASCII: gmsh parses it line by line
  if (got < 84) reject(file, "binary STL shorter than its 84-byte header");
  std::uint32_t triangles = 0;
  std::memcpy(&triangles, header + 80, sizeof triangles);
  const auto size = std::filesystem::file_size(file);
  if (size != 84 + 50ULL * triangles)
    reject(file, "binary STL declares " + std::to_string(triangles) + " triangles (" +
                     std::to_string(84 + 50ULL * triangles) + " bytes) but has " +
                     std::to_string(size) + " bytes");
}

}  // namespace corofem
