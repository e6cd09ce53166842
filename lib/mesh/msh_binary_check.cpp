#include "mesh/msh_binary_check.hpp"

#include <cstdint>
#include <cstring>
#include <limits>
#include <unordered_set>

#include "core/errors.hpp"
#include "mesh/msh_precheck.hpp"

namespace corofem {
namespace {

constexpr std::uint64_t kMaxTag = 1'000'000'000ULL;

/// Nodes per element of the gmsh element types accepted in binary files (linear and quadratic
/// points, lines, triangles, quads, tets, hexes, prisms, pyramids); 0 for any other type.
int nodes_of_element_type(std::int64_t type) {
  static constexpr int kNodes[] = {0, 2,  3,  4,  4,  8, 6, 5,  3,  6,
                                   9, 10, 27, 18, 14, 1, 8, 20, 15, 13};
  return type > 0 && type < static_cast<std::int64_t>(std::size(kNodes)) ? kNodes[type] : 0;
}

/// Text for a message: control and non-ASCII bytes shown as '?'.
std::string printable(const std::string& text) {
  std::string out;
  for (char c : text)
    out += c == '\n' ? std::string("\\n")
                     : (c >= 32 && c < 127 ? std::string(1, c) : std::string("?"));
  return out;
}

/// Reads a binary .msh front to back; every read is checked against the bytes that remain.
class MshCursor {
 public:
  MshCursor(const std::string& bytes, const std::filesystem::path& file)
      : bytes_(bytes), file_(file) {}

  [[noreturn]] void reject(const std::string& section, const std::string& what) const {
    throw InputError("mesh file '" + file_.string() + "' is malformed: " + what + " in $" +
                     section + " (byte " + std::to_string(at_) + " of " +
                     std::to_string(bytes_.size()) + ")");
  }

  std::uint64_t left() const { return bytes_.size() - at_; }
  bool only_whitespace_left() const {
    return bytes_.find_first_not_of(" \t\r\n", at_) == std::string::npos;
  }

  template <class T>
  T read(const std::string& section) {
    if (left() < sizeof(T)) reject(section, "the file ends inside a record");
    T value;
    std::memcpy(&value, bytes_.data() + at_, sizeof(T));
    at_ += sizeof(T);
    return value;
  }

  /// Checks that `count` items of `item_bytes` each fit in what remains (no overflow), before
  /// anything is read or allocated from `count`.
  void need(std::uint64_t count, std::uint64_t item_bytes, const std::string& section,
            const std::string& what) const {
    if (item_bytes > 0 && count > left() / item_bytes)
      reject(section, what + " declares " + std::to_string(count) + " items of " +
                          std::to_string(item_bytes) + " bytes but only " + std::to_string(left()) +
                          " bytes remain");
  }

  void skip(std::uint64_t count, std::uint64_t item_bytes, const std::string& section,
            const std::string& what) {
    need(count, item_bytes, section, what);
    at_ += count * item_bytes;
  }

  void expect(const std::string& text, const std::string& section) {
    if (bytes_.compare(at_, text.size(), text) != 0)
      reject(section, "expected '" + printable(text) + "'");
    at_ += text.size();
  }

  /// Text up to the next newline (which is consumed).
  std::string line(const std::string& section) {
    const std::size_t end = bytes_.find('\n', at_);
    if (end == std::string::npos) reject(section, "the file ends inside a text line");
    std::string text = bytes_.substr(at_, end - at_);
    at_ = end + 1;
    if (!text.empty() && text.back() == '\r') text.pop_back();
    return text;
  }

  /// A text line holding one non-negative decimal count.
  std::uint64_t count_line(const std::string& section) {
    const std::string text = line(section);
    if (text.empty() || text.size() > 18 ||
        text.find_first_not_of("0123456789") != std::string::npos)
      reject(section, "bad count line '" + printable(text.substr(0, 40)) + "'");
    return std::stoull(text);
  }

 private:
  const std::string& bytes_;
  const std::filesystem::path& file_;
  std::size_t at_ = 0;
};

/// Tags of the nodes defined so far; each tag once.
class NodeTags {
 public:
  void define(std::uint64_t tag, std::uint64_t min_tag, std::uint64_t max_tag, MshCursor& in) {
    if (tag == 0 || tag < min_tag || tag > max_tag)
      in.reject("Nodes", "node tag " + std::to_string(tag) + " is outside [" +
                             std::to_string(min_tag) + ", " + std::to_string(max_tag) + "]");
    if (!tags_.insert(tag).second)
      in.reject("Nodes", "node " + std::to_string(tag) + " is defined twice");
  }
  void check_reference(std::uint64_t node, std::uint64_t element, MshCursor& in) const {
    if (!tags_.count(node))
      in.reject("Elements", "element " + std::to_string(element) + " refers to node " +
                                std::to_string(node) + ", which $Nodes does not define");
  }

 private:
  std::unordered_set<std::uint64_t> tags_;
};

/// $PhysicalNames has a text body in binary files too: a count, then one line per name.
void check_physical_names(MshCursor& in, const std::filesystem::path& file) {
  const std::uint64_t count = in.count_line("PhysicalNames");
  in.need(count, 6, "PhysicalNames", "the header");  // "d t \"\"\n" is the shortest line
  for (std::uint64_t k = 0; k < count; ++k)
    check_physical_name_line(in.line("PhysicalNames"), file);
  in.expect("$EndPhysicalNames\n", "PhysicalNames");
}

void check_entities_v41(MshCursor& in) {
  std::uint64_t counts[4];
  for (auto& c : counts) c = in.read<std::uint64_t>("Entities");
  for (int dim = 0; dim < 4; ++dim) {
    const std::uint64_t record = dim == 0 ? 4 + 3 * 8 + 8 : 4 + 6 * 8 + 8 + 8;  // smallest record
    in.need(counts[dim], record, "Entities", "the dimension-" + std::to_string(dim) + " count");
    for (std::uint64_t e = 0; e < counts[dim]; ++e) {
      in.read<std::int32_t>("Entities");
      in.skip(dim == 0 ? 3 : 6, 8, "Entities", "a bounding box");
      in.skip(in.read<std::uint64_t>("Entities"), 4, "Entities", "a physical tag list");
      if (dim > 0)
        in.skip(in.read<std::uint64_t>("Entities"), 4, "Entities", "a bounding entity list");
    }
  }
}

struct TagHeader {
  std::uint64_t blocks, total, min_tag, max_tag;
};

TagHeader read_tag_header(MshCursor& in, const std::string& section, std::uint64_t smallest_item) {
  TagHeader h{};
  h.blocks = in.read<std::uint64_t>(section);
  h.total = in.read<std::uint64_t>(section);
  h.min_tag = in.read<std::uint64_t>(section);
  h.max_tag = in.read<std::uint64_t>(section);
  in.need(h.blocks, 20, section, "the block count");
  in.need(h.total, smallest_item, section, "the item count");
  if (h.total > 0 && (h.max_tag > kMaxTag || h.min_tag > h.max_tag || h.min_tag == 0))
    in.reject(section, "tag range [" + std::to_string(h.min_tag) + ", " +
                           std::to_string(h.max_tag) + "] (tags are 1 to 1e9)");
  return h;
}

void check_nodes_v41(MshCursor& in, NodeTags& nodes) {
  const TagHeader h = read_tag_header(in, "Nodes", 8 + 3 * 8);
  std::uint64_t listed = 0;
  for (std::uint64_t b = 0; b < h.blocks; ++b) {
    const auto dim = in.read<std::int32_t>("Nodes");
    in.read<std::int32_t>("Nodes");  // entity tag: gmsh creates a discrete entity if it is new
    const auto parametric = in.read<std::int32_t>("Nodes");
    const auto count = in.read<std::uint64_t>("Nodes");
    if (dim < 0 || dim > 3 || (parametric != 0 && parametric != 1))
      in.reject("Nodes", "bad block header (dimension " + std::to_string(dim) + ", parametric " +
                             std::to_string(parametric) + ")");
    if (count > h.total - listed)
      in.reject("Nodes", "blocks list more nodes than the header's " + std::to_string(h.total));
    const std::uint64_t doubles = 3 + (parametric ? dim : 0);
    in.need(count, 8 + 8 * doubles, "Nodes", "a block");
    for (std::uint64_t k = 0; k < count; ++k)
      nodes.define(in.read<std::uint64_t>("Nodes"), h.min_tag, h.max_tag, in);
    in.skip(count, 8 * doubles, "Nodes", "a block's coordinates");
    listed += count;
  }
  if (listed != h.total)
    in.reject("Nodes", "the header declares " + std::to_string(h.total) +
                           " nodes but the blocks list " + std::to_string(listed));
}

void check_elements_v41(MshCursor& in, const NodeTags& nodes) {
  const TagHeader h = read_tag_header(in, "Elements", 16);
  std::unordered_set<std::uint64_t> seen;
  std::uint64_t listed = 0;
  for (std::uint64_t b = 0; b < h.blocks; ++b) {
    const auto dim = in.read<std::int32_t>("Elements");
    in.read<std::int32_t>("Elements");  // entity tag: gmsh reports an unknown one as an error
    const auto type = in.read<std::int32_t>("Elements");
    const auto count = in.read<std::uint64_t>("Elements");
    const int per_element = nodes_of_element_type(type);
    if (dim < 0 || dim > 3 || per_element == 0)
      in.reject("Elements", "bad block header (dimension " + std::to_string(dim) +
                                ", element type " + std::to_string(type) + ")");
    if (count > h.total - listed)
      in.reject("Elements",
                "blocks list more elements than the header's " + std::to_string(h.total));
    in.need(count, 8ULL * (1 + per_element), "Elements", "a block");
    for (std::uint64_t k = 0; k < count; ++k) {
      const auto tag = in.read<std::uint64_t>("Elements");
      if (tag == 0 || tag < h.min_tag || tag > h.max_tag || !seen.insert(tag).second)
        in.reject("Elements", "element tag " + std::to_string(tag) +
                                  " is outside the header's range or repeated");
      for (int a = 0; a < per_element; ++a)
        nodes.check_reference(in.read<std::uint64_t>("Elements"), tag, in);
    }
    listed += count;
  }
  if (listed != h.total)
    in.reject("Elements", "the header declares " + std::to_string(h.total) +
                              " elements but the blocks list " + std::to_string(listed));
}

void check_nodes_v22(MshCursor& in, NodeTags& nodes) {
  const std::uint64_t count = in.count_line("Nodes");
  in.need(count, 4 + 3 * 8, "Nodes", "the header");
  for (std::uint64_t k = 0; k < count; ++k) {
    const auto tag = in.read<std::int32_t>("Nodes");
    nodes.define(tag < 0 ? 0 : static_cast<std::uint64_t>(tag), 1, kMaxTag, in);
    in.skip(3, 8, "Nodes", "coordinates");
  }
}

void check_elements_v22(MshCursor& in, const NodeTags& nodes) {
  const std::uint64_t total = in.count_line("Elements");
  in.need(total, 4 * 2, "Elements", "the header");
  std::unordered_set<std::uint64_t> seen;
  for (std::uint64_t listed = 0; listed < total;) {
    const auto type = in.read<std::int32_t>("Elements");
    const auto count = in.read<std::int32_t>("Elements");
    const auto tags = in.read<std::int32_t>("Elements");
    const int per_element = nodes_of_element_type(type);
    if (per_element == 0 || count <= 0 || tags < 0 ||
        static_cast<std::uint64_t>(count) > total - listed)
      in.reject("Elements", "bad block header (element type " + std::to_string(type) + ", " +
                                std::to_string(count) + " elements, " + std::to_string(tags) +
                                " tags)");
    in.need(static_cast<std::uint64_t>(count), 4ULL * (1 + tags + per_element), "Elements",
            "a block");
    for (std::int32_t k = 0; k < count; ++k) {
      const auto tag = in.read<std::int32_t>("Elements");
      if (tag <= 0 || static_cast<std::uint64_t>(tag) > kMaxTag || !seen.insert(tag).second)
        in.reject("Elements",
                  "element number " + std::to_string(tag) + " is not positive or repeated");
      in.skip(static_cast<std::uint64_t>(tags), 4, "Elements", "an element's tags");
      for (int a = 0; a < per_element; ++a) {
        const auto node = in.read<std::int32_t>("Elements");
        nodes.check_reference(node < 0 ? 0 : static_cast<std::uint64_t>(node), tag, in);
      }
    }
    listed += count;
  }
}

}  // namespace

void check_binary_msh(const std::string& bytes, double version, const std::filesystem::path& file) {
  MshCursor in(bytes, file);
  const bool v41 = version == 4.1;
  if (!v41 && version != 2.2)
    in.reject(
        "MeshFormat",
        "binary version " + std::to_string(version) +
            " is not read (binary files must be 4.1 or 2.2; gmsh -save -format msh41 converts)");
  in.expect("$MeshFormat\n", "MeshFormat");
  in.line("MeshFormat");
  if (in.read<std::int32_t>("MeshFormat") != 1)
    in.reject("MeshFormat",
              "the file was written with the other byte order (the endianness marker is not 1)");
  in.expect("\n$EndMeshFormat\n", "MeshFormat");
  NodeTags nodes;
  bool have_nodes = false, have_elements = false;
  while (!in.only_whitespace_left()) {
    const std::string header = in.line("MeshFormat");
    const std::string name = header.empty() || header[0] != '$' ? std::string() : header.substr(1);
    if (name == "PhysicalNames") {
      check_physical_names(in, file);
      continue;
    }
    if (name == "Entities" && v41) {
      check_entities_v41(in);
    } else if (name == "Nodes" && !have_nodes) {
      v41 ? check_nodes_v41(in, nodes) : check_nodes_v22(in, nodes);
      have_nodes = true;
    } else if (name == "Elements" && have_nodes && !have_elements) {
      v41 ? check_elements_v41(in, nodes) : check_elements_v22(in, nodes);
      have_elements = true;
    } else {
      in.reject(name.empty() ? "MeshFormat" : name,
                "unexpected '" + printable(header.substr(0, 40)) +
                    "' (binary files may hold $PhysicalNames, " + (v41 ? "$Entities, " : "") +
                    "$Nodes and then $Elements, each once; other sections and text between them "
                    "are not read)");
    }
    in.expect("\n$End" + name + "\n", name);
  }
}

}  // namespace corofem
