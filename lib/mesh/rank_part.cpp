#include "mesh/rank_part.hpp"

#include <algorithm>
#include <array>

namespace corofem {

int rank_share_start(int count, int rank, int ranks) {
  return static_cast<int>(static_cast<long long>(count) * rank / ranks);
}

int RankPart::owned_tets() const {
  return static_cast<int>(std::count(owned_tet.begin(), owned_tet.end(), 1));
}

namespace {

/// The tets to hold, ascending: those touching a vertex in [begin, end), then `extra_rings` rings.
std::vector<int> held_tets(const TetMesh& whole, int begin, int end, int extra_rings) {
  std::vector<char> held(whole.num_tets(), 0), reached(whole.num_vertices(), 0);
  for (int v = begin; v < end; ++v) reached[v] = 1;
  std::vector<int> vertex_tet_start, vertex_tets;  // vertex -> tets, built only when needed
  if (extra_rings > 0) {
    vertex_tet_start.assign(whole.num_vertices() + 1, 0);
    for (const Tet& t : whole.tets)
      for (int v : t) ++vertex_tet_start[v + 1];
    for (int v = 0; v < whole.num_vertices(); ++v) vertex_tet_start[v + 1] += vertex_tet_start[v];
    vertex_tets.resize(vertex_tet_start.back());
    std::vector<int> next(vertex_tet_start.begin(), vertex_tet_start.end() - 1);
    for (int t = 0; t < whole.num_tets(); ++t)
      for (int v : whole.tets[t]) vertex_tets[next[v]++] = t;
  }
  for (int t = 0; t < whole.num_tets(); ++t)
    for (int v : whole.tets[t]) held[t] |= reached[v];
  for (int ring = 0; ring < extra_rings; ++ring) {
    for (int t = 0; t < whole.num_tets(); ++t)
      if (held[t])
        for (int v : whole.tets[t]) reached[v] = 1;
    for (int v = 0; v < whole.num_vertices(); ++v)
      if (reached[v])
        for (int k = vertex_tet_start[v]; k < vertex_tet_start[v + 1]; ++k)
          held[vertex_tets[k]] = 1;
  }
  std::vector<int> tets;
  for (int t = 0; t < whole.num_tets(); ++t)
    if (held[t]) tets.push_back(t);
  return tets;
}

}  // namespace

std::vector<int> group_vertices_by_part(TetMesh& mesh, const std::vector<int>& part_of_vertex,
                                        int parts, std::vector<int>& new_index) {
  const int nv = mesh.num_vertices();
  std::vector<int> start(parts + 1, 0);
  for (int p : part_of_vertex) ++start[p + 1];
  for (int p = 0; p < parts; ++p) start[p + 1] += start[p];
  new_index.assign(nv, 0);
  std::vector<int> next(start.begin(), start.end() - 1);
  for (int v = 0; v < nv; ++v) new_index[v] = next[part_of_vertex[v]]++;
  std::vector<Vec3> rest(nv);
  for (int v = 0; v < nv; ++v) rest[new_index[v]] = mesh.rest[v];
  mesh.rest = std::move(rest);
  if (!mesh.node_tags.empty()) {
    std::vector<std::size_t> tags(nv);
    for (int v = 0; v < nv; ++v) tags[new_index[v]] = mesh.node_tags[v];
    mesh.node_tags = std::move(tags);
  }
  for (Tet& t : mesh.tets)
    for (int& v : t) v = new_index[v];
  return start;
}

RankPart rank_part(const TetMesh& whole, int rank, int ranks, int extra_rings) {
  return rank_part_of_range(whole, rank_share_start(whole.num_vertices(), rank, ranks),
                            rank_share_start(whole.num_vertices(), rank + 1, ranks), extra_rings);
}

namespace {

/// The part owning the vertices [begin, end) and holding the tets `held` (ascending). `local`
/// (one entry per vertex of `whole`) is all -1 on entry and is left so.
RankPart part_holding(const TetMesh& whole, int begin, int end, std::vector<int> held,
                      std::vector<int>& local) {
  RankPart part;
  part.first_vertex = begin;
  part.owned_vertices = end - begin;
  part.global_vertices = whole.num_vertices();
  part.global_tets = whole.num_tets();
  const auto owned = [&](int v) { return v >= begin && v < end; };
  for (int v = begin; v < end; ++v) local[v] = v - begin;
  std::vector<int> halo;
  part.global_tet = std::move(held);
  for (int t : part.global_tet) {
    const Tet& tet = whole.tets[t];
    part.owned_tet.push_back(owned(*std::min_element(tet.begin(), tet.end())));
    for (int v : tet)
      if (local[v] == -1) {
        local[v] = -2;  // seen: numbered below, once the halo is sorted
        halo.push_back(v);
      }
  }
  std::sort(halo.begin(), halo.end());
  part.halo_vertices = static_cast<int>(halo.size());
  for (std::size_t h = 0; h < halo.size(); ++h)
    local[halo[h]] = part.owned_vertices + static_cast<int>(h);
  part.global_vertex.resize(part.owned_vertices + halo.size());
  for (int v = begin; v < end; ++v) part.global_vertex[v - begin] = v;
  std::copy(halo.begin(), halo.end(), part.global_vertex.begin() + part.owned_vertices);

  TetMesh& m = part.mesh;
  m.source = whole.source;
  for (int g : part.global_vertex) {
    m.rest.push_back(whole.rest[g]);
    if (!whole.node_tags.empty()) m.node_tags.push_back(whole.node_tags[g]);
  }
  for (int t : part.global_tet) {
    Tet tet = whole.tets[t];
    for (int& v : tet) v = local[v];
    m.tets.push_back(tet);
    if (!whole.element_tags.empty()) m.element_tags.push_back(whole.element_tags[t]);
  }
  for (int g : part.global_vertex) local[g] = -1;
  return part;
}

}  // namespace

RankPart rank_part_of_range(const TetMesh& whole, int begin, int end, int extra_rings) {
  std::vector<int> local(whole.num_vertices(), -1);
  return part_holding(whole, begin, end, held_tets(whole, begin, end, extra_rings), local);
}

RankPartCutter::RankPartCutter(const TetMesh& whole, std::vector<int> first, int extra_rings)
    : whole_(whole),
      first_(std::move(first)),
      extra_rings_(extra_rings),
      local_(whole.num_vertices(), -1) {
  if (extra_rings_ > 0) return;  // rings are found part by part (held_tets)
  // Each tet goes to the parts of its vertices (each once, tets ascending): one pass in all.
  const int parts = static_cast<int>(first_.size()) - 1;
  std::vector<int> part_of(whole.num_vertices());
  for (int p = 0; p < parts; ++p)
    for (int v = first_[p]; v < first_[p + 1]; ++v) part_of[v] = p;
  const auto each_part = [&](const Tet& tet, auto&& visit) {
    std::array<int, 4> seen{};
    int count = 0;
    for (int v : tet) {
      const int p = part_of[v];
      if (std::find(seen.begin(), seen.begin() + count, p) == seen.begin() + count) {
        seen[count++] = p;
        visit(p);
      }
    }
  };
  held_start_.assign(parts + 1, 0);
  for (const Tet& tet : whole.tets) each_part(tet, [&](int p) { ++held_start_[p + 1]; });
  for (int p = 0; p < parts; ++p) held_start_[p + 1] += held_start_[p];
  held_.resize(held_start_.back());
  std::vector<int> next(held_start_.begin(), held_start_.end() - 1);
  for (int t = 0; t < whole.num_tets(); ++t)
    each_part(whole.tets[t], [&](int p) { held_[next[p]++] = t; });
}

RankPart RankPartCutter::cut(int rank) {
  const int begin = first_[rank], end = first_[rank + 1];
  std::vector<int> held = extra_rings_ > 0
                              ? held_tets(whole_, begin, end, extra_rings_)
                              : std::vector<int>(held_.begin() + held_start_[rank],
                                                 held_.begin() + held_start_[rank + 1]);
  return part_holding(whole_, begin, end, std::move(held), local_);
}

}  // namespace corofem
